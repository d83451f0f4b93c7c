// The statistics block printed at the end of a run (spec §5), from libcommon's counters.
#pragma once

#include <cstdio>

#include "libshade/scene.h"

namespace rs {

struct RunTimes {
    double preprocessSeconds = 0;
    double renderWallSeconds = 0;
    double cpuUserSeconds = 0;
    double cpuSystemSeconds = 0;
};

// The verbose description of a node at frame start (spec §5): `<type> "<name>":`, its
// bounding box as three `X: lo to hi` lines (when bounded), and its primitive count.
void WriteObjectSummary(std::FILE* out, const Object& object);

// The verbose options summary printed before rendering.
void WriteOptionsSummary(std::FILE* out, const Scene& scene, int threads);

// Writes the final report to `out`: ray counts, hits, supersampled pixels, bounding-box
// tests, one line per primitive type that was tested, and times.
void WriteStatistics(std::FILE* out, const RunTimes& times);

}  // namespace rs
