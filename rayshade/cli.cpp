#include "rayshade/cli.h"

#include <cerrno>
#include <cstdlib>

#include "libcommon/limits.h"

namespace rs {

namespace {

class ArgCursor {
  public:
    ArgCursor(const std::vector<std::string>& args, std::string& error) : args_(args), error_(error) {}

    bool Done() const { return next_ >= args_.size(); }
    const std::string& Take() { return args_[next_++]; }

    bool Word(const char* flag, std::string& out) {
        if (Done()) return Fail(std::string("option ") + flag + " needs an argument");
        out = Take();
        return true;
    }
    bool Real(const char* flag, double& out) {
        std::string w;
        if (!Word(flag, w)) return false;
        char* end = nullptr;
        errno = 0;
        out = std::strtod(w.c_str(), &end);
        if (w.empty() || *end != '\0' || errno == ERANGE)
            return Fail(std::string("option ") + flag + ": '" + w + "' is not a number");
        return true;
    }
    bool Int(const char* flag, int& out) {
        std::string w;
        if (!Word(flag, w)) return false;
        char* end = nullptr;
        errno = 0;
        long v = std::strtol(w.c_str(), &end, 10);
        if (w.empty() || *end != '\0' || errno == ERANGE || v < -1000000000L || v > 1000000000L)
            return Fail(std::string("option ") + flag + ": '" + w + "' is not an integer");
        out = static_cast<int>(v);
        return true;
    }
    bool Fail(const std::string& message) {
        error_ = message;
        return false;
    }

  private:
    const std::vector<std::string>& args_;
    std::string& error_;
    size_t next_ = 0;
};

// Reads the value of an implicit override option (-M, -I, -K, -J, -B, -H) into cl.implicit.
bool Implicit(ArgCursor& in, const char* flag, ImplicitOverrideKind kind, CommandLine& cl) {
    std::string value, error;
    if (!in.Word(flag, value)) return false;
    if (!ParseImplicitOverride(kind, value, cl.implicit, error)) {
        return in.Fail(std::string(flag) + ": " + error);
    }
    return true;
}

}  // namespace

namespace {

// One line of the help: the option as docs/options.md writes it, and what it does.
struct OptionHelp {
    const char* synopsis;
    const char* summary;
};
struct OptionGroup {
    const char* title;
    std::vector<OptionHelp> options;
};

// Every option, in the groups and order of docs/options.md (cli_test compares the two).
const std::vector<OptionGroup>& OptionGroups() {
    static const std::vector<OptionGroup> groups = {
        {"Input",
         {{"-P args", "arguments for the C preprocessor, one word (e.g. -P -DNAME=value)"},
          {"-u", "toggle the C preprocessor (on by default)"}}},
        {"Output",
         {{"-O file", "output file (.png, or .mtv for the original's format)"},
          {"-a", "toggle the alpha channel (RGBA PNG)"},
          {"-G g", "output gamma (default 1)"},
          {"-e", "accepted and ignored (the original's exponential RLE)"},
          {"-m", "accepted and ignored (the original's RLE sample map)"}}},
        {"Image and sampling",
         {{"-R x y", "resolution (default 512 512)"},
          {"-W x0 x1 y0 y1", "render only this window of the screen (pixels)"},
          {"-X l r b t", "crop the window (fractions, default 0 1 0 1)"},
          {"-S n", "samples per pixel side, 1-16"},
          {"-T r g b", "contrast thresholds of adaptive supersampling"},
          {"-j", "toggle jittered sampling"},
          {"-g", "toggle the Gaussian pixel filter"},
          {"-p", "preview: no shadows, depth 0, one sample per pixel"}}},
        {"Ray tracing",
         {{"-D d", "maximum reflection/refraction depth (default 5)"},
          {"-C r g b", "ray-tree cutoff per channel (default 0.002)"},
          {"-n", "toggle no shadows"},
          {"-o", "toggle transparent shadows"},
          {"-s", "toggle shadow caching (on by default; changes only statistics)"},
          {"-f", "toggle flipping of triangle and polygon normals"}}},
        {"Animation and stereo",
         {{"-A f", "first frame to render (default 0)"},
          {"-N k", "number of frames"},
          {"-E s", "eye separation for stereo"},
          {"-l", "render the left eye of a stereo pair"},
          {"-r", "render the right eye of a stereo pair"}}},
        {"Running and reporting",
         {{"-t n", "worker threads (default: all cores)"},
          {"-c", "continue an interrupted render (the same command plus -c)"},
          {"-q", "quiet: no warnings, no progress"},
          {"-v", "verbose: options, progress and statistics on standard error"},
          {"-V file", "verbose, with the report written to file"},
          {"-F n", "report progress every n scanlines"},
          {"-L name=value", "raise a resource limit (docs/robustness.md): resolutionSide,\n"
                            "resolutionPixels, samplesPerSide, rayDepth, sceneBytes, gridVoxels,\n"
                            "gridEntries, polylinePoints, octreeBytes"},
          {"-h", "print this help and exit"}}},
        {"Implicit objects (every one, whatever its scene says)",
         {{"-M method", "auto, patches, kb89, march, sphere, segment, polynomial, exact"},
          {"-I eps", "root tolerance"},
          {"-K d", "octree maximum depth (0-16)"},
          {"-J r", "Dratio of heuristic 3bis (patches)"},
          {"-B step", "march step"},
          {"-H name=on|off", "one octree heuristic or search test: range, patch, 1, 1bis,\n"
                             "3, 3bis, 4, 5, 0bis, t1, 2bis, t3"}}},
    };
    return groups;
}

std::string BuildUsage() {
    constexpr int kColumn = 18;  // where the summaries start
    std::string text = "usage: rayshade [options] [file.ray]\n";
    for (const OptionGroup& group : OptionGroups()) {
        text += std::string(group.title) + ":\n";
        for (const OptionHelp& option : group.options) {
            std::string line = std::string("  ") + option.synopsis;
            line += line.size() < kColumn ? std::string(kColumn - line.size(), ' ') : "  ";
            // Continuation lines of a long summary start in the summary column.
            for (const char* c = option.summary; *c; ++c) {
                line += *c;
                if (*c == '\n') line += std::string(kColumn, ' ');
            }
            text += line + "\n";
        }
    }
    return text;
}

}  // namespace

const char* UsageText() {
    static const std::string text = BuildUsage();
    return text.c_str();
}

int OptionArgumentCount(char letter) {
    for (const OptionGroup& group : OptionGroups()) {
        for (const OptionHelp& option : group.options) {
            const std::string synopsis = option.synopsis;
            if (synopsis[1] != letter) continue;
            int words = 0;
            for (char c : synopsis) words += c == ' ';
            return words;
        }
    }
    return -1;
}

bool ParseCommandLine(const std::vector<std::string>& args, CommandLine& cl, std::string& error) {
    ArgCursor in(args, error);
    RenderOptions& o = cl.options;
    while (!in.Done()) {
        const std::string arg = in.Take();
        if (arg.size() < 2 || arg[0] != '-') {
            if (!cl.inputFile.empty()) return in.Fail("more than one input file given");
            cl.inputFile = arg;
            continue;
        }
        if (arg.size() != 2) return in.Fail("unknown option '" + arg + "'");
        const char* flag = arg.c_str();
        switch (arg[1]) {
            case 'A': if (!in.Int(flag, o.startFrame)) return false; break;
            case 'B': if (!Implicit(in, flag, ImplicitOverrideKind::Step, cl)) return false; break;
            case 'a': cl.alpha = !cl.alpha; break;
            case 'C':
                if (!in.Real(flag, o.cutoff.r) || !in.Real(flag, o.cutoff.g) || !in.Real(flag, o.cutoff.b))
                    return false;
                o.cutoffSet = true;
                break;
            case 'c': cl.resume = true; break;
            case 'D':
                if (!in.Int(flag, o.maxDepth)) return false;
                o.maxDepthSet = true;
                break;
            case 'E':
                if (!in.Real(flag, cl.eyeSep)) return false;
                o.eyeSepSet = true;
                break;
            case 'e': break;  // exponential RLE output: no RLE writer, nothing to do
            case 'F':
                if (!in.Int(flag, o.reportFreq)) return false;
                if (o.reportFreq < 1) o.reportFreq = 1;
                o.reportFreqSet = true;
                break;
            case 'f': o.flipNormals = !o.flipNormals; break;
            case 'G': if (!in.Real(flag, o.gamma)) return false; break;
            case 'g': o.filter = o.filter == FilterKind::Box ? FilterKind::Gauss : FilterKind::Box; break;
            case 'H': if (!Implicit(in, flag, ImplicitOverrideKind::Switch, cl)) return false; break;
            case 'h': cl.help = true; break;
            case 'I': if (!Implicit(in, flag, ImplicitOverrideKind::Tolerance, cl)) return false; break;
            case 'J': if (!Implicit(in, flag, ImplicitOverrideKind::DRatio, cl)) return false; break;
            case 'K': if (!Implicit(in, flag, ImplicitOverrideKind::Depth, cl)) return false; break;
            case 'j':
                o.jitter = !o.jitter;
                o.jitterSet = true;
                break;
            case 'l': o.eyeSepSide = -1; break;
            case 'L': {
                std::string assignment;
                if (!in.Word(flag, assignment)) return false;
                std::string limitError;
                if (!SetLimit(assignment, limitError)) return in.Fail(limitError);
                break;
            }
            case 'r': o.eyeSepSide = 1; break;
            case 'M': if (!Implicit(in, flag, ImplicitOverrideKind::Method, cl)) return false; break;
            case 'm': break;  // sample map in the RLE alpha channel: no RLE writer
            case 'N':
                if (!in.Int(flag, o.frames)) return false;
                if (o.frames < 1) return in.Fail("-N: the number of frames must be at least 1");
                o.framesSet = true;
                break;
            case 'n': o.noShadows = !o.noShadows; break;
            case 'O':
                if (!in.Word(flag, o.outFile)) return false;
                o.outFileSet = true;
                break;
            case 'o': o.shadowTransparency = !o.shadowTransparency; break;
            case 'P': if (!in.Word(flag, cl.cppArgs)) return false; break;
            case 'p':
                o.noShadows = true;
                o.maxDepth = 0;
                o.samples = 1;
                o.jitter = true;
                o.maxDepthSet = o.samplesSet = o.jitterSet = true;
                break;
            case 'q': o.quiet = true; break;
            case 'R':
                if (!in.Int(flag, o.xres) || !in.Int(flag, o.yres)) return false;
                o.resolutionSet = true;
                break;
            case 'S':
                if (!in.Int(flag, o.samples)) return false;
                if (o.samples < 1) o.samples = 1;
                o.samplesSet = true;
                break;
            case 's': o.shadowCache = !o.shadowCache; break;
            case 'T':
                if (!in.Real(flag, o.contrast.r) || !in.Real(flag, o.contrast.g) ||
                    !in.Real(flag, o.contrast.b))
                    return false;
                o.contrastSet = true;
                break;
            case 't':
                if (!in.Int(flag, o.threads)) return false;
                if (o.threads < 1) return in.Fail("-t: the number of threads must be at least 1");
                break;
            case 'u': cl.useCpp = !cl.useCpp; break;
            case 'V':
                if (!in.Word(flag, o.statsFile)) return false;
                if (!o.statsFile.empty() && o.statsFile[0] == '-')
                    return in.Fail("-V needs a file name, not '" + o.statsFile + "'");
                o.statsFileSet = true;
                o.verbose = true;
                break;
            case 'v': o.verbose = true; break;
            case 'W':
                for (int i = 0; i < 4; ++i)
                    if (!in.Int(flag, o.window[i])) return false;
                o.windowSet = true;
                break;
            case 'X':
                for (int i = 0; i < 4; ++i)
                    if (!in.Real(flag, o.crop[i])) return false;
                o.cropSet = true;
                break;
            default: return in.Fail("unknown option '" + arg + "'");
        }
    }
    return true;
}

}  // namespace rs
