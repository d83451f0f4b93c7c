#include "cli.h"

#include <cmath>
#include <optional>

#include "libcommon/error.h"
#include "libimage/image.h"
#include "metrics.h"
#include "thresholds.h"

namespace rs {

namespace {

constexpr const char* kUsage =
    "usage: imgdiff [--mean M] [--max X] [--frac F] [--bright B] [--diff out.png]\n"
    "               [--thresholds FILE SCENE RES] [--pixels STEPS P] ours.png reference.png\n"
    "Compares two images after a 4x4 box downsample (channel values in [0,1]) and passes\n"
    "when mean abs error < M, max abs error < X, the fraction of pixels whose largest\n"
    "channel difference exceeds 0.03 <= F, and |mean(ours) - mean(ref)| / mean(ref) < B\n"
    "(defaults 0.005 0.15 0.05 0.01). --thresholds takes the row for SCENE at RES (a number\n"
    "or 'default') from a thresholds table, falling back to its 'default any' row; the\n"
    "single-metric options override the table. On failure a heat map of the differences\n"
    "goes to --diff (default <ours>.diff.png). --pixels adds a full-resolution test: at most\n"
    "a fraction P of the pixels may differ by more than STEPS/255 in some channel\n"
    "(self-regression: --pixels 1 0.001).\n"
    "Exit status: 0 pass, 1 fail, 2 error.\n";

struct Options {
    std::optional<double> mean, max, frac, bright;
    std::string diffPath;
    std::string tableFile, tableScene, tableResolution;
    std::optional<int> pixelSteps;  // --pixels STEPS P
    double pixelFraction = 0;
    std::vector<std::string> images;
    bool help = false;
};

// Parses `args` into `options`; on a usage error returns false with `error` set.
bool ParseOptions(const std::vector<std::string>& args, Options& options, std::string& error) {
    for (size_t i = 0; i < args.size(); ++i) {
        const std::string& arg = args[i];
        auto needs = [&](size_t count) {
            if (i + count < args.size()) return true;
            error = arg + " needs " + std::to_string(count) + " value" + (count > 1 ? "s" : "");
            return false;
        };
        std::optional<double>* metric = arg == "--mean"     ? &options.mean
                                        : arg == "--max"    ? &options.max
                                        : arg == "--frac"   ? &options.frac
                                        : arg == "--bright" ? &options.bright
                                                            : nullptr;
        if (metric) {
            if (!needs(1)) return false;
            *metric = ParseNonNegative(args[++i]);
            if (!*metric) {
                error = arg + " needs a number >= 0, not \"" + args[i] + "\"";
                return false;
            }
        } else if (arg == "--diff") {
            if (!needs(1)) return false;
            options.diffPath = args[++i];
        } else if (arg == "--thresholds") {
            if (!needs(3)) return false;
            options.tableFile = args[++i];
            options.tableScene = args[++i];
            options.tableResolution = args[++i];
        } else if (arg == "--pixels") {
            if (!needs(2)) return false;
            const std::optional<double> steps = ParseNonNegative(args[++i]);
            const std::optional<double> fraction = ParseNonNegative(args[++i]);
            if (!steps || *steps != std::floor(*steps) || *steps > 255 || !fraction) {
                error = "--pixels needs a whole number of steps in [0, 255] and a fraction >= 0";
                return false;
            }
            options.pixelSteps = static_cast<int>(*steps);
            options.pixelFraction = *fraction;
        } else if (arg == "-h" || arg == "--help") {
            options.help = true;
        } else if (arg.size() > 1 && arg[0] == '-') {
            error = "unknown option " + arg;
            return false;
        } else {
            options.images.push_back(arg);
        }
    }
    if (!options.help && options.images.size() != 2) {
        error = "expected two images (ours and the reference), got " +
                std::to_string(options.images.size());
        return false;
    }
    return true;
}

std::string Verdict(const char* name, double value, const char* relation, double limit,
                    bool ok) {
    return StringPrintf("%s %.6f (%s%g%s)", name, value, relation, limit, ok ? "" : " FAIL");
}

}  // namespace

int RunImgdiff(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
    Options options;
    std::string error;
    if (!ParseOptions(args, options, error)) {
        err << "imgdiff: " << error << "\n" << kUsage;
        return kImgdiffError;
    }
    if (options.help) {
        out << kUsage;
        return kImgdiffPass;
    }
    Thresholds limits;
    if (!options.tableFile.empty()) {
        const auto fromTable = LoadThresholds(options.tableFile, options.tableScene,
                                              options.tableResolution, error);
        if (!fromTable) {
            err << "imgdiff: " << error << "\n";
            return kImgdiffError;
        }
        limits = *fromTable;
    }
    limits.mean = options.mean.value_or(limits.mean);
    limits.max = options.max.value_or(limits.max);
    limits.frac = options.frac.value_or(limits.frac);
    limits.bright = options.bright.value_or(limits.bright);

    const std::string& oursPath = options.images[0];
    const std::string& refPath = options.images[1];
    const auto ours = ReadImage(oursPath, error);
    if (!ours) {
        err << "imgdiff: " << error << "\n";
        return kImgdiffError;
    }
    const auto ref = ReadImage(refPath, error);
    if (!ref) {
        err << "imgdiff: " << error << "\n";
        return kImgdiffError;
    }
    const auto metrics = CompareImages(*ours, *ref, error);
    if (!metrics) {
        err << "imgdiff: " << oursPath << " vs " << refPath << ": " << error << "\n";
        return kImgdiffError;
    }
    const Thresholds& t = limits;
    const DiffMetrics& m = *metrics;
    bool pass = WithinThresholds(m, t);
    std::string line = oursPath + ": " + Verdict("mean", m.mean, "<", t.mean, m.mean < t.mean) +
                       " " + Verdict("max", m.max, "<", t.max, m.max < t.max) + " " +
                       Verdict("frac", m.frac, "<=", t.frac, m.frac <= t.frac) + " " +
                       Verdict("bright", m.bright, "<", t.bright, m.bright < t.bright);
    if (options.pixelSteps) {
        const auto beyond = FractionBeyond(*ours, *ref, *options.pixelSteps, error);
        if (!beyond) {
            err << "imgdiff: " << oursPath << " vs " << refPath << ": " << error << "\n";
            return kImgdiffError;
        }
        const bool ok = *beyond <= options.pixelFraction;
        const std::string name = StringPrintf("pixels>%d/255", *options.pixelSteps);
        line += ' ';
        line += Verdict(name.c_str(), *beyond, "<=", options.pixelFraction, ok);
        pass = pass && ok;
    }
    if (pass) {
        out << line << ": PASS\n";
        return kImgdiffPass;
    }
    const std::string diffPath =
        options.diffPath.empty() ? oursPath + ".diff.png" : options.diffPath;
    if (WriteImage(diffPath, HeatMap(*ours, *ref), error)) {
        out << line << ": FAIL, heat map in " << diffPath << "\n";
    } else {
        out << line << ": FAIL\n";
        err << "imgdiff: heat map not written: " << error << "\n";
    }
    return kImgdiffFail;
}

}  // namespace rs
