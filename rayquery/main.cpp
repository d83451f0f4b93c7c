// rayquery: first hits of world-space rays against a scene (see README.md in this folder).
//   rayquery [-m METHOD] [-e EPS] [-d DEPTH] [-r DRATIO] [-k STEP] [-H NAME=on|off]
//            [-f SPREAD [WIDTH]] [-v] SCENE.ray < rays.txt
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <string>

#include "libcommon/error.h"
#include "libcommon/stats.h"
#include "libshade/command.h"
#include "libshade/parser.h"
#include "rayquery/query.h"

namespace {

constexpr const char* kUsage =
    "usage: rayquery [-m METHOD] [-e EPS] [-d DEPTH] [-r DRATIO] [-k STEP] [-H NAME=on|off]...\n"
    "                [-f SPREAD [WIDTH]] [-v] SCENE.ray < rays.txt\n"
    "  each input line: ox oy oz dx dy dz [tmin [tmax [time]]]   (world space; default\n"
    "                   tmin 0, tmax 1e14; t in units of the given direction; time, the\n"
    "                   ray time, in [start, start + shutter], default start; '#' lines\n"
    "                   skipped)\n"
    "  each output line: hit T PX PY PZ NX NY NZ OBJECT PATCH EVALS  |  miss EVALS\n"
    "  -m METHOD  intersection method of every implicit object: auto (the scene default),\n"
    "             patches, kb89, march, sphere, segment, polynomial (blob points and\n"
    "             segments) or exact (ground truth)\n"
    "  -e EPS     root tolerance of every implicit object (object-space distance, > 0)\n"
    "  -d DEPTH   octree maximum depth, 0 to 16 (patches, kb89)\n"
    "  -r DRATIO  Gascuel's Dratio (patches; -1 disables heuristic 3bis)\n"
    "  -k STEP    march step (object-space distance, > 0)\n"
    "  -H NAME=on|off  switch an octree heuristic or search test: range, patch, 1, 1bis, 3,\n"
    "             3bis, 4, 5, 0bis, t1, 2bis, t3 (repeatable, applied in order)\n"
    "  -f SPREAD [WIDTH]  every ray carries a footprint: WIDTH (default 0) at its origin,\n"
    "             growing by SPREAD per unit of distance (world units); `tolerance auto`\n"
    "             then picks the root accuracy from it, as for rendered rays\n"
    "  -v         print the statistics counters to standard error at the end\n";

// Reads the option at argv[i] (and its value) into `overrides`; `i` moves past the value.
// Returns false with a message on a malformed value; `known` tells whether it was ours.
bool ReadOverride(int argc, char** argv, int& i, rs::ImplicitOverrides& overrides, bool& known,
                  std::string& error) {
    static const std::pair<const char*, rs::ImplicitOverrideKind> kOptions[] = {
        {"-m", rs::ImplicitOverrideKind::Method}, {"-e", rs::ImplicitOverrideKind::Tolerance},
        {"-d", rs::ImplicitOverrideKind::Depth},  {"-r", rs::ImplicitOverrideKind::DRatio},
        {"-k", rs::ImplicitOverrideKind::Step},   {"-H", rs::ImplicitOverrideKind::Switch}};
    const std::string arg = argv[i];
    known = false;
    for (const auto& [option, kind] : kOptions) {
        if (arg != option) continue;
        known = true;
        if (i + 1 >= argc) {
            error = arg + " needs a value";
            return false;
        }
        if (!rs::ParseImplicitOverride(kind, argv[i + 1], overrides, error)) {
            error = arg + ": " + error;
            return false;
        }
        ++i;
        return true;
    }
    return true;
}

int Run(int argc, char** argv) {
    bool verbose = false;
    double spread = 0, width = 0;  // -f: the footprint in world units (ray.h)
    rs::ImplicitOverrides overrides;
    std::string sceneFile;
    for (int i = 1; i < argc; ++i) {
        std::string arg = argv[i];
        bool known = false;
        std::string error;
        if (!ReadOverride(argc, argv, i, overrides, known, error)) {
            std::fprintf(stderr, "rayquery: %s\n%s", error.c_str(), kUsage);
            return 1;
        }
        if (known) continue;
        if (arg == "-f") {
            auto number = [&](int at, double& value) {
                char* end = nullptr;
                if (at >= argc) return false;
                value = std::strtod(argv[at], &end);
                return end != argv[at] && *end == '\0' && std::isfinite(value) && value >= 0;
            };
            if (!number(i + 1, spread)) {
                std::fprintf(stderr, "rayquery: -f needs a spread >= 0\n%s", kUsage);
                return 1;
            }
            ++i;
            if (number(i + 1, width)) ++i;
        } else if (arg == "-v") {
            verbose = true;
        } else if (arg == "-h" || arg == "--help") {
            std::fputs(kUsage, stdout);
            return 0;
        } else if (!arg.empty() && arg[0] == '-') {
            std::fprintf(stderr, "rayquery: unknown option '%s'\n%s", arg.c_str(), kUsage);
            return 1;
        } else if (sceneFile.empty()) {
            sceneFile = arg;
        } else {
            std::fprintf(stderr, "rayquery: more than one scene file ('%s')\n%s", arg.c_str(),
                         kUsage);
            return 1;
        }
    }
    if (sceneFile.empty()) {
        std::fprintf(stderr, "rayquery: no scene file (rays come on standard input)\n%s", kUsage);
        return 1;
    }

    rs::ParseInput input;
    input.path = sceneFile;
    rs::Scene scene = rs::ParseScene(input, rs::RenderOptions{});
    if (!overrides.Empty()) {
        std::string error;
        if (rs::ApplyImplicitOverrides(*scene.world, overrides, error) < 0) {
            std::fprintf(stderr, "rayquery: %s\n", error.c_str());
            return 1;
        }
    }
    const double time = scene.options.startTime;
    scene.world->PrepareFrame(time, scene.options.shutter);

    std::string line, error;
    int lineNumber = 0;
    while (std::getline(std::cin, line)) {
        ++lineNumber;
        if (rs::IsQueryComment(line)) continue;
        rs::QueryRay query;
        if (!rs::ParseQueryLine(line, query, error)) {
            std::fflush(stdout);
            std::fprintf(stderr, "rayquery: Error: standard input:%d: %s\n", lineNumber,
                         error.c_str());
            return 1;
        }
        // The ray time must lie in the frame's exposure, where the scene was prepared.
        const double shutter = std::max(scene.options.shutter, 0.0);
        if (query.time && !(*query.time >= time && *query.time <= time + shutter)) {
            std::fflush(stdout);
            std::fprintf(stderr,
                         "rayquery: Error: standard input:%d: time %g is outside the frame's "
                         "exposure [%g, %g] (scene start time and shutter)\n",
                         lineNumber, *query.time, time, time + shutter);
            return 1;
        }
        query.ray.time = query.time.value_or(time);
        // In units of t (ray.h): a world width divided by |d|; the spread is a ratio.
        query.ray.footprintWidth = width / rs::Length(query.ray.dir);
        query.ray.footprintSpread = spread;
        std::string out = rs::FormatQueryResult(rs::RunQuery(*scene.world, query));
        std::fputs(out.c_str(), stdout);
        std::fputc('\n', stdout);
    }
    if (verbose) {
        for (const rs::CounterValue& c : rs::StatsSnapshot()) {
            if (c.value != 0) {
                std::fprintf(stderr, "%s:\t%llu\n", c.name.c_str(),
                             static_cast<unsigned long long>(c.value));
            }
        }
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    const std::atomic<bool> quiet{false};
    return rs::RunCommand("rayquery", quiet, [&] { return Run(argc, argv); });
}
