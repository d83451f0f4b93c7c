// The statistics block printed at the end of a run (spec §5), from libcommon's counters.
#pragma once

#include <cstdio>

namespace rs {

struct RunTimes {
    double preprocessSeconds = 0;
    double renderWallSeconds = 0;
    double cpuUserSeconds = 0;
    double cpuSystemSeconds = 0;
};

// Writes the final report to `out`: ray counts, hits, supersampled pixels, bounding-box
// tests, one line per primitive type that was tested, and times.
void WriteStatistics(std::FILE* out, const RunTimes& times);

}  // namespace rs
