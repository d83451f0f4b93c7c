// rayquery: first hits of world-space rays against a scene (see README.md in this folder).
//   rayquery [-m METHOD] [-f SPREAD [WIDTH]] [-v] SCENE.ray < rays.txt
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
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
    "usage: rayquery [-m patches|kb89] [-f SPREAD [WIDTH]] [-v] SCENE.ray < rays.txt\n"
    "  each input line: ox oy oz dx dy dz [tmin [tmax]]   (world space; default tmin 0,\n"
    "                   tmax 1e14; t in units of the given direction; '#' lines skipped)\n"
    "  each output line: hit T PX PY PZ NX NY NZ OBJECT PATCH EVALS  |  miss EVALS\n"
    "  -m METHOD  intersection method of every implicit object\n"
    "  -f SPREAD [WIDTH]  every ray carries a footprint: WIDTH (default 0) at its origin,\n"
    "             growing by SPREAD per unit of distance (world units); `tolerance auto`\n"
    "             then picks the root accuracy from it, as for rendered rays\n"
    "  -v         print the statistics counters to standard error at the end\n";

int Run(int argc, char** argv) {
    bool verbose = false, overrideMethod = false;
    double spread = 0, width = 0;  // -f: the footprint in world units (ray.h)
    rs::ImplicitMethod method = rs::ImplicitMethod::Patches;
    std::string sceneFile;
    for (int i = 1; i < argc; ++i) {
        std::string arg = argv[i];
        if (arg == "-m") {
            if (i + 1 >= argc || !rs::ParseImplicitMethod(argv[i + 1], method)) {
                std::fprintf(stderr, "rayquery: -m needs a method: patches or kb89\n%s", kUsage);
                return 1;
            }
            overrideMethod = true;
            ++i;
        } else if (arg == "-f") {
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
    if (overrideMethod) rs::OverrideImplicitMethod(*scene.world, method);
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
        query.ray.time = time;
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
