// Resource limits. Each one turns what would be memory or time exhaustion into a clear
// error (or, for the ray depth, a clamp with a warning). The defaults suit any sensible
// scene on an ordinary machine; a run that really needs more raises a limit with
// `rayshade -L name=value` (docs/robustness.md lists them). Set before parsing, read-only
// afterwards.
#pragma once

#include <string>

namespace rs {

struct ResourceLimits {
    long resolutionSide = 65536;        // pixels per image side (screen, -R)
    long resolutionPixels = 1L << 28;   // pixels per image (about 20 bytes each while rendering)
    long samplesPerSide = 16;           // sample, -S (n² rays per supersampled pixel)
    long rayDepth = 64;                 // maxdepth, -D (deeper requests are clamped)
    long sceneBytes = 1L << 30;         // scene text after preprocessing
    long gridVoxels = 1L << 24;         // nx·ny·nz of one grid (8 bytes each)
    long gridEntries = 1L << 28;        // child-in-voxel entries of one grid (4 bytes each)
    long polylinePoints = 1L << 20;     // points of one implicit polyline skeleton
    long octreeBytes = 64L << 20;       // node memory of one implicit LG octree
};

// The limits in force.
const ResourceLimits& Limits();

// Applies "name=value" (name as in ResourceLimits, value a positive integer). Returns false
// with `error` set for an unknown name or a bad value.
bool SetLimit(const std::string& assignment, std::string& error);

// "resolutionSide resolutionPixels ...": the names SetLimit accepts, for usage messages.
std::string LimitNames();

}  // namespace rs
