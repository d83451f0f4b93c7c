// Internal to the LG octree's two files (lg_octree.cpp builds, lg_search.cpp searches):
// the statistics counters both count into, and the cell geometry both use.
#pragma once

#include "libcommon/bounds.h"
#include "libcommon/stats.h"

namespace rs::lg_octree_detail {

struct OctreeCounters {
    CounterId cellsBuilt = RegisterCounter("Implicit octree cells built");
    CounterId rangeFired = RegisterCounter("Implicit octree value-range prunes");
    CounterId patchFired = RegisterCounter("Implicit octree patch-rule prunes");
    CounterId h1Fired = RegisterCounter("Implicit octree heuristic 1 prunes");
    CounterId h1bisFired = RegisterCounter("Implicit octree heuristic 1bis prunes");
    CounterId h2Fired = RegisterCounter("Implicit octree heuristic 2 leaves");
    CounterId h3Fired = RegisterCounter("Implicit octree heuristic 3 leaves");
    CounterId h3bisFired = RegisterCounter("Implicit octree heuristic 3bis leaves");
    CounterId budgetFired = RegisterCounter("Implicit octree memory-budget leaves");
    CounterId h4Fired = RegisterCounter("Implicit octree heuristic 4 merges");
    CounterId h5Fired = RegisterCounter("Implicit octree heuristic 5 merges");
    CounterId cellsVisited = RegisterCounter("Implicit cells visited");
    CounterId test0bis = RegisterCounter("Implicit test 0bis roots");
    CounterId test1 = RegisterCounter("Implicit test 1 (L) rejections");
    CounterId test2bisChord = RegisterCounter("Implicit test 2bis chord rejections");
    CounterId monotoneNoRoot = RegisterCounter("Implicit monotone same-sign rejections");
    CounterId test3 = RegisterCounter("Implicit test 3 single-root intervals");
    CounterId splits = RegisterCounter("Implicit interval splits");
    CounterId segmentBounds = RegisterCounter("Implicit segment bounds");
    CounterId ridders = RegisterCounter("Implicit Ridders calls");
    CounterId riddersIterations = RegisterCounter("Implicit Ridders iterations");
    CounterId floorRoots = RegisterCounter("Implicit minimum-width roots");
    CounterId unresolved = RegisterCounter("Implicit unresolved intervals");
    CounterId rejectedRoots = RegisterCounter("Implicit roots rejected by predominance");
    CounterId excludedSegments =
        RegisterCounter("Implicit single-root segments excluded by predominance");
};


// The counters, registered on first use.
const OctreeCounters& Counters();

// The sign convention of the module: inside is g > 0.
inline bool Inside(double g) { return g > 0; }

// The octant i of a cell: bit 0 x, bit 1 y, bit 2 z set for the upper half.
inline Bounds3 ChildBox(const Bounds3& box, int i) {
    Vec3 c = box.Center();
    Bounds3 b;
    b.lo = {(i & 1) ? c.x : box.lo.x, (i & 2) ? c.y : box.lo.y, (i & 4) ? c.z : box.lo.z};
    b.hi = {(i & 1) ? box.hi.x : c.x, (i & 2) ? box.hi.y : c.y, (i & 4) ? box.hi.z : c.z};
    return b;
}

// The octant of a cell holding p.
inline int ChildIndexOf(const Bounds3& box, const Vec3& p) {
    Vec3 c = box.Center();
    return (p.x >= c.x ? 1 : 0) | (p.y >= c.y ? 2 : 0) | (p.z >= c.z ? 4 : 0);
}

}  // namespace rs::lg_octree_detail
