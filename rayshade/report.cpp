#include "rayshade/report.h"

#include <map>
#include <string>

#include "libcommon/stats.h"

namespace rs {

namespace {

double Percent(uint64_t part, uint64_t whole) {
    return whole ? 100.0 * static_cast<double>(part) / static_cast<double>(whole) : 0.0;
}

}  // namespace

void WriteObjectSummary(std::FILE* out, const Object& object) {
    if (object.name.empty())
        std::fprintf(out, "%s:\n", object.TypeName().c_str());
    else
        std::fprintf(out, "%s \"%s\":\n", object.TypeName().c_str(), object.name.c_str());
    if (object.IsBounded()) {
        const Bounds3& b = object.BoundsInParent();
        std::fprintf(out, "\tX: %f to %f\n\tY: %f to %f\n\tZ: %f to %f\n", b.lo.x, b.hi.x, b.lo.y,
                     b.hi.y, b.lo.z, b.hi.z);
    } else {
        std::fprintf(out, "\tunbounded\n");
    }
    long n = object.PrimitiveCount();
    std::fprintf(out, "\t%ld primitive%s\n", n, n == 1 ? "" : "s");
}

void WriteOptionsSummary(std::FILE* out, const Scene& scene, int threads) {
    const RenderOptions& o = scene.options;
    std::fprintf(out, "Rendering frame%s %d", o.frames > 1 ? "s" : "", o.startFrame);
    if (o.frames > 1) std::fprintf(out, " to %d", o.startFrame + o.frames - 1);
    std::fprintf(out, "\nScreen resolution: %d x %d\n", o.xres, o.yres);
    std::fprintf(out, "%s sampling, %d max sample%s per pixel side, %s filter\n",
                 o.jitter ? "Jittered" : "Unjittered", o.samples, o.samples == 1 ? "" : "s",
                 o.filter == FilterKind::Gauss ? "gaussian" : "box");
    std::fprintf(out, "Contrast threshold: %f %f %f\n", o.contrast.r, o.contrast.g, o.contrast.b);
    std::fprintf(out, "Maximum ray depth: %d.  Cutoff threshold: %f %f %f\n", o.maxDepth, o.cutoff.r,
                 o.cutoff.g, o.cutoff.b);
    if (o.eyeSepSide != 0) std::fprintf(out, "Rendering %s eye view\n", o.eyeSepSide < 0 ? "left" : "right");
    std::fprintf(out, "%s\n", o.noShadows ? "No shadows"
                                          : (o.shadowTransparency ? "Shadows through transparent objects"
                                                                  : "Opaque shadows"));
    if (!o.shadowCache) std::fprintf(out, "Shadow cache disabled\n");
    std::fprintf(out, "Threads: %d\n", threads);
    if (scene.parallelParsedObjects > 0)
        std::fprintf(out, "Primitives parsed in parallel: %zu\n", scene.parallelParsedObjects);
}

void WriteStatistics(std::FILE* out, const RunTimes& times) {
    std::map<std::string, uint64_t> c;
    std::vector<CounterValue> all = StatsSnapshot();
    for (const CounterValue& v : all) c[v.name] = v.value;

    uint64_t eye = c["eye rays"], shadow = c["shadow rays"], reflected = c["reflected rays"],
             refracted = c["refracted rays"];
    uint64_t total = eye + shadow + reflected + refracted;
    uint64_t hitting = c["hit rays"] + c["shadow hits"];
    std::fprintf(out, "Eye rays:\t\t\t%llu\n", static_cast<unsigned long long>(eye));
    std::fprintf(out, "Shadow rays:\t\t\t%llu\n", static_cast<unsigned long long>(shadow));
    std::fprintf(out, "Reflected rays:\t\t\t%llu\n", static_cast<unsigned long long>(reflected));
    std::fprintf(out, "Refracted rays:\t\t\t%llu\n", static_cast<unsigned long long>(refracted));
    std::fprintf(out, "Total rays:\t\t\t%llu\n", static_cast<unsigned long long>(total));
    std::fprintf(out, "Intersecting rays:\t\t%llu (%3.3f%%)\n",
                 static_cast<unsigned long long>(hitting), Percent(hitting, total));
    std::fprintf(out, "Shadow hits:\t\t\t%llu (%3.3f%%)\n",
                 static_cast<unsigned long long>(c["shadow hits"]), Percent(c["shadow hits"], shadow));
    if (c["shadow cache hits"] + c["shadow cache misses"] > 0)
        std::fprintf(out, "Shadow cache hits:\t\t%llu (%llu misses)\n",
                     static_cast<unsigned long long>(c["shadow cache hits"]),
                     static_cast<unsigned long long>(c["shadow cache misses"]));
    std::fprintf(out, "Supersampled pixels:\t\t%llu\n",
                 static_cast<unsigned long long>(c["supersampled pixels"]));
    std::fprintf(out, "B.V. intersection tests:\t%llu\n",
                 static_cast<unsigned long long>(c["bounding box tests"]));

    // One line per primitive type that was tested ("<Type> tests" / "<Type> hits").
    uint64_t primTests = 0, primHits = 0;
    const std::string suffix = " tests";
    for (const CounterValue& v : all) {
        if (v.name.size() <= suffix.size() ||
            v.name.compare(v.name.size() - suffix.size(), suffix.size(), suffix) != 0 || v.value == 0)
            continue;
        std::string type = v.name.substr(0, v.name.size() - suffix.size());
        if (!c.count(type + " hits")) continue;
        uint64_t hits = c[type + " hits"];
        primTests += v.value;
        primHits += hits;
        std::fprintf(out, "%s intersection tests:\t%llu (%llu hit, %3.3f%%)\n", type.c_str(),
                     static_cast<unsigned long long>(v.value), static_cast<unsigned long long>(hits),
                     Percent(hits, v.value));
    }
    std::fprintf(out, "Total prim. intersection tests:\t%llu (%llu hit, %3.3f%%)\n",
                 static_cast<unsigned long long>(primTests), static_cast<unsigned long long>(primHits),
                 Percent(primHits, primTests));

    // Other counters (implicit surfaces, ...) registered by modules, when non-zero.
    static const char* kShown[] = {"eye rays", "shadow rays", "reflected rays", "refracted rays",
                                   "hit rays", "shadow hits", "shadow cache hits",
                                   "shadow cache misses", "supersampled pixels",
                                   "bounding box tests"};
    for (const CounterValue& v : all) {
        bool shown = false;
        for (const char* s : kShown) shown = shown || v.name == s;
        bool typeCounter = (v.name.size() > 6 && v.name.compare(v.name.size() - 6, 6, " tests") == 0 &&
                            c.count(v.name.substr(0, v.name.size() - 6) + " hits")) ||
                           (v.name.size() > 5 && v.name.compare(v.name.size() - 5, 5, " hits") == 0 &&
                            c.count(v.name.substr(0, v.name.size() - 5) + " tests"));
        if (!shown && !typeCounter && v.value != 0)
            std::fprintf(out, "%s:\t%llu\n", v.name.c_str(), static_cast<unsigned long long>(v.value));
    }

    double cpu = times.cpuUserSeconds + times.cpuSystemSeconds;
    std::fprintf(out, "Preprocessing time:\t\t%.2f sec\n", times.preprocessSeconds);
    std::fprintf(out, "Total CPU time (sec):\t\t%.2f (%.2fu + %.2fs)\n", cpu, times.cpuUserSeconds,
                 times.cpuSystemSeconds);
    std::fprintf(out, "Rendering wall time (sec):\t%.2f\n", times.renderWallSeconds);
    if (total) std::fprintf(out, "Seconds / ray:\t\t\t%.2e\n", cpu / static_cast<double>(total));
    if (hitting) std::fprintf(out, "Seconds / intersecting ray:\t%.2e\n", cpu / static_cast<double>(hitting));
    if (times.renderWallSeconds > 0)
        std::fprintf(out, "Rays / second (wall):\t\t%.0f\n", static_cast<double>(total) / times.renderWallSeconds);
}

}  // namespace rs
