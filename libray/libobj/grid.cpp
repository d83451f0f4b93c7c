#include "libobj/grid.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>

#include "libcommon/constants.h"
#include "libcommon/error.h"
#include "libcommon/limits.h"
#include "libcommon/parallel_build.h"
#include "libobj/object.h"

namespace rs {

namespace {

// Mailboxes: each rendering thread keeps one stamp per child of every grid (grids take
// disjoint ranges of slots, see PrepareFrame). A grid's Intersect takes a fresh stamp from the
// thread's counter and marks a child's slot with it once tested, so each child is tested at
// most once per call. Nothing is shared between threads, and a stale or cleared mark only
// causes a repeated test, which cannot change the result (tMax only shrinks), so images do
// not depend on the marks.
std::atomic<size_t> gSlotsAllocated{0};

struct ThreadMailbox {
    std::vector<uint32_t> marks;  // one per allocated slot; 0 is never a stamp
    uint32_t lastStamp = 0;

    // A stamp not yet used on any of this thread's slots; makes room for every slot allocated
    // so far. Slots are allocated only by PrepareFrame, which never runs during a walk, so
    // the calls of nested walks find the room made and never move `marks`.
    uint32_t NewStamp() {
        const size_t slots = gSlotsAllocated.load(std::memory_order_relaxed);
        if (marks.size() < slots) marks.resize(slots, 0);
        if (++lastStamp == 0) {  // wrapped after 2^32 calls: forget every mark
            std::fill(marks.begin(), marks.end(), 0);
            lastStamp = 1;
        }
        return lastStamp;
    }
};

thread_local ThreadMailbox tMailbox;

const CounterId kBoundsTests = RegisterCounter("bounding box tests");

}  // namespace

GridAggregate::GridAggregate(int nx, int ny, int nz, Search search)
    : n_{std::max(nx, 1), std::max(ny, 1), std::max(nz, 1)}, search_(search) {}

int GridAggregate::VoxelOf(double x, int axis) const {
    const double f = std::floor((x - gridBox_.lo[axis]) / voxelSize_[axis]);
    if (!(f > 0)) return 0;  // also NaN
    return f >= n_[axis] - 1 ? n_[axis] - 1 : static_cast<int>(f);
}

void GridAggregate::PrepareFrame(double /*frameTime*/, double /*shutter*/) {
    bounded_.clear();
    unbounded_.clear();
    childBoxes_.clear();
    cellStart_.clear();
    cellItems_.clear();
    emptyRun_.clear();
    hierarchy_ = ChildHierarchy{};
    bounds_ = Bounds3{};
    // The bounded children in order with their boxes padded by kEpsilon: the registered
    // boxes (a hit on a voxel face stays registered on both sides despite round-off in the
    // DDA, and flat boxes, e.g. of polygons, get a non-zero extent) and the boxes the walk
    // tests, so a hit a rounding error outside a flat child's box is never rejected. In
    // chunks of children on the build's threads (a pass over every child node: 6 ms of
    // tree's two-thread setup on one thread): each chunk counts its bounded children and
    // unites their boxes, then writes them from its offset; unions are exact in any order.
    const size_t childChunks = (children_.size() + kChunk - 1) / kChunk;
    std::vector<size_t> chunkBounded(childChunks + 1, 0);
    std::vector<Bounds3> chunkBounds(childChunks);
    RunBuildLoopInChunks(children_.size(), kChunk, [&](size_t begin, size_t end) {
        const size_t chunk = begin / kChunk;
        for (size_t i = begin; i < end; ++i) {
            if (!children_[i]->IsBounded()) continue;
            ++chunkBounded[chunk + 1];
            chunkBounds[chunk].Extend(children_[i]->BoundsInParent());
        }
    });
    for (size_t c = 0; c < childChunks; ++c) {
        chunkBounded[c + 1] += chunkBounded[c];
        bounds_.Extend(chunkBounds[c]);
    }
    bounded_.resize(chunkBounded[childChunks]);
    childBoxes_.resize(bounded_.size());
    RunBuildLoopInChunks(children_.size(), kChunk, [&](size_t begin, size_t end) {
        for (size_t i = begin, k = chunkBounded[begin / kChunk]; i < end; ++i) {
            if (!children_[i]->IsBounded()) continue;
            bounded_[k] = children_[i].get();
            childBoxes_[k++] = children_[i]->BoundsInParent().Padded(kEpsilon);
        }
    });
    if (bounded_.size() < children_.size())
        for (const auto& child : children_)
            if (!child->IsBounded()) unbounded_.push_back(child.get());
    if (bounded_.empty()) return;
    gridBox_ = bounds_.Padded(kEpsilon);
    const Vec3 extent = gridBox_.Extent();
    voxelSize_ = {extent.x / n_[0], extent.y / n_[1], extent.z / n_[2]};

    // Each child's voxel range: lo[3], hi[3] (hi < lo for an empty box); returns how many
    // voxels it covers.
    const auto voxelRange = [&](size_t i, int* r) -> uint64_t {
        const Bounds3& box = childBoxes_[i];
        if (box.IsEmpty()) {
            std::fill(r, r + 6, 0);
            r[3] = -1;
            return 0;
        }
        uint64_t cells = 1;
        for (int a = 0; a < 3; ++a) {
            r[a] = VoxelOf(box.lo[a], a);
            r[3 + a] = VoxelOf(box.hi[a], a);
            cells *= static_cast<uint64_t>(r[3 + a] - r[a] + 1);
        }
        return cells;
    };
    // The entry count first, so a grid too fine for its children is refused before any
    // entry is stored or visited, and the ranges are stored only for a voxel walk (6 ints a
    // child: megabytes on a large scene, which mostly takes the hierarchy). In chunks of
    // children on the build's threads (each chunk writes its own count; RunBuildLoop
    // returns after all).
    std::vector<uint64_t> chunkEntries((bounded_.size() + kChunk - 1) / kChunk, 0);
    RunBuildLoopInChunks(bounded_.size(), kChunk, [&](size_t begin, size_t end) {
        int r[6];
        uint64_t cells = 0;
        for (size_t i = begin; i < end; ++i) cells += voxelRange(i, r);
        chunkEntries[begin / kChunk] = cells;
    });
    uint64_t entries = 0;
    for (uint64_t e : chunkEntries) entries += e;
    if (entries > static_cast<uint64_t>(Limits().gridEntries)) {
        Report(Severity::Abort, {},
               "grid %dx%dx%d: its %zu children overlap %llu voxels in total, more than the "
               "limit of %llu; use fewer voxels",
               n_[0], n_[1], n_[2], bounded_.size(), static_cast<unsigned long long>(entries),
               static_cast<unsigned long long>(Limits().gridEntries));
    }
    if (search_ != Search::Voxels) {
        hierarchy_.Build(bounded_, childBoxes_);
        if (search_ == Search::Hierarchy ||
            !(ExpectedVoxelCost(entries) < hierarchy_.ExpectedCost())) {
            childBoxes_ = {};  // the voxel walk's; megabytes on a large scene
            return;
        }
        hierarchy_ = ChildHierarchy{};
    }
    std::vector<int> ranges(6 * bounded_.size());
    RunBuildLoopInChunks(bounded_.size(), kChunk, [&](size_t begin, size_t end) {
        for (size_t i = begin; i < end; ++i) voxelRange(i, &ranges[6 * i]);
    });
    if (bounded_.size() > slotCount_) {
        slotCount_ = bounded_.size();
        firstSlot_ = gSlotsAllocated.fetch_add(slotCount_, std::memory_order_relaxed);
    }
    // Two passes: count the entries of each cell, then fill them in, each in slabs of z
    // layers on the build's threads. A slab's task writes only its own cells' counts and
    // entries, visiting the children in order, so every cell lists its children in order
    // whatever runs the tasks.
    const int slabs = std::min(n_[2], kSlabs);
    const auto forEachCellOfSlab = [&](long slab, auto&& visit) {
        const int z0 = static_cast<int>(slab * n_[2] / slabs);
        const int z1 = static_cast<int>((slab + 1) * n_[2] / slabs);  // exclusive
        for (uint32_t i = 0; i < bounded_.size(); ++i) {
            const int* r = &ranges[6 * i];
            for (int z = std::max(r[2], z0); z <= std::min(r[5], z1 - 1); ++z)
                for (int y = r[1]; y <= r[4]; ++y)
                    for (int x = r[0]; x <= r[3]; ++x) visit(i, CellIndex(x, y, z));
        }
    };
    const size_t cellCount = static_cast<size_t>(n_[0]) * n_[1] * n_[2];
    cellStart_.assign(cellCount + 1, 0);
    RunBuildLoop(slabs, [&](long slab) {
        forEachCellOfSlab(slab, [&](uint32_t, int c) { ++cellStart_[c + 1]; });
    });
    for (size_t c = 0; c < cellCount; ++c) cellStart_[c + 1] += cellStart_[c];
    cellItems_.resize(cellStart_[cellCount]);
    std::vector<uint32_t> cursor(cellStart_.begin(), cellStart_.end() - 1);
    RunBuildLoop(slabs, [&](long slab) {
        forEachCellOfSlab(slab, [&](uint32_t i, int c) { cellItems_[cursor[c]++] = i; });
    });
    ComputeEmptyRuns();
}

double GridAggregate::ExpectedVoxelCost(uint64_t entries) const {
    // Lines meeting a convex body uniformly (the surface-area heuristic's rays) cross it
    // along chords of mean length 4·volume / area, whose projection on an axis averages
    // half that: the walk steps through about 1 + sum over the axes of that projection
    // over the voxel size cells, each holding entries / cells entries on average.
    const Vec3 e = gridBox_.Extent();
    const double halfArea = e.x * e.y + e.y * e.z + e.z * e.x;
    const double cells = static_cast<double>(n_[0]) * n_[1] * n_[2];
    const double crossed =
        1 + e.x * e.y * e.z / halfArea * (1 / voxelSize_.x + 1 / voxelSize_.y + 1 / voxelSize_.z);
    return kVoxelStepCost * crossed + kVoxelEntryCost * crossed * static_cast<double>(entries) / cells;
}

void GridAggregate::ComputeEmptyRuns() {
    // The chessboard distance transform by two raster passes over the 26-neighbourhood
    // (exact for this metric): each pass takes the minimum over the 13 neighbours already
    // visited in its order, plus one.
    const int nx = n_[0], ny = n_[1], nz = n_[2];
    emptyRun_.resize(static_cast<size_t>(nx) * ny * nz);
    for (size_t c = 0; c < emptyRun_.size(); ++c)
        emptyRun_[c] = cellStart_[c + 1] > cellStart_[c] ? 0 : kMaxEmptyRun;
    const auto pass = [&](int dir) {
        const int z0 = dir > 0 ? 0 : nz - 1, y0 = dir > 0 ? 0 : ny - 1, x0 = dir > 0 ? 0 : nx - 1;
        for (int z = z0; z >= 0 && z < nz; z += dir) {
            for (int y = y0; y >= 0 && y < ny; y += dir) {
                for (int x = x0; x >= 0 && x < nx; x += dir) {
                    uint8_t& d = emptyRun_[CellIndex(x, y, z)];
                    if (d == 0) continue;
                    int best = d;
                    // Neighbours earlier in this pass's order: the previous slice's nine,
                    // the previous row's three of this slice, the previous cell of this row.
                    for (int dz = 0; dz <= 1; ++dz) {
                        for (int dy = -1; dy <= 1; ++dy) {
                            for (int dx = -1; dx <= 1; ++dx) {
                                if (dz == 0 && (dy < 0 || (dy == 0 && dx <= 0))) continue;
                                const int qx = x - dir * dx, qy = y - dir * dy, qz = z - dir * dz;
                                if (qx < 0 || qx >= nx || qy < 0 || qy >= ny || qz < 0 || qz >= nz)
                                    continue;
                                best = std::min(best, emptyRun_[CellIndex(qx, qy, qz)] + 1);
                            }
                        }
                    }
                    d = static_cast<uint8_t>(best);
                }
            }
        }
    };
    pass(1);
    pass(-1);
}

bool GridAggregate::Intersect(const Ray& ray, double tMin, double& tMax, HitRecord& hit) const {
    bool found = false;
    for (const Object* child : unbounded_) {
        if (child->Intersect(ray, tMin, tMax, hit)) found = true;
    }
    if (bounded_.empty()) return found;
    if (!hierarchy_.IsEmpty()) return hierarchy_.Intersect(ray, tMin, tMax, hit) || found;
    return Walk<false>(ray, tMin, tMax, [&](const Object* child) {
               return child->Intersect(ray, tMin, tMax, hit);
           }) ||
           found;
}

bool GridAggregate::Occluded(const Ray& ray, double tMin, double tMax,
                             const Object** blocker) const {
    for (const Object* child : unbounded_) {
        if (child->Occluded(ray, tMin, tMax, blocker)) return true;
    }
    if (bounded_.empty()) return false;
    if (!hierarchy_.IsEmpty()) return hierarchy_.Occluded(ray, tMin, tMax, blocker);
    return Walk<true>(ray, tMin, tMax,
                      [&](const Object* child) { return child->Occluded(ray, tMin, tMax, blocker); });
}

template <bool kStopAtFirstHit, class Test>
bool GridAggregate::Walk(const Ray& ray, double tMin, double& tMax, Test&& test) const {
    double tEnter = tMin, tExit = tMax;
    if (!gridBox_.ClipRay(ray, tEnter, tExit)) return false;

    // 3-D DDA (Amanatides & Woo): tNext[a] is the t at which the ray leaves the current
    // cell through a face normal to axis a, tDelta[a] the t it takes to cross one cell.
    const Vec3 start = ray.At(tEnter);
    int cell[3], step[3], stop[3];
    double tNext[3], tDelta[3];
    for (int a = 0; a < 3; ++a) {
        cell[a] = VoxelOf(start[a], a);
        const double d = ray.dir[a];
        if (d > 0) {
            step[a] = 1;
            stop[a] = n_[a];
            tNext[a] = (gridBox_.lo[a] + (cell[a] + 1) * voxelSize_[a] - ray.origin[a]) / d;
            tDelta[a] = voxelSize_[a] / d;
        } else if (d < 0) {
            step[a] = -1;
            stop[a] = -1;
            tNext[a] = (gridBox_.lo[a] + cell[a] * voxelSize_[a] - ray.origin[a]) / d;
            tDelta[a] = -voxelSize_[a] / d;
        } else {
            step[a] = 0;
            stop[a] = -1;
            tNext[a] = std::numeric_limits<double>::infinity();
            tDelta[a] = 0;
        }
    }

    // The children's box tests share the reciprocal direction.
    const Vec3 invDir{1 / ray.dir.x, 1 / ray.dir.y, 1 / ray.dir.z};
    bool found = false;
    ThreadMailbox& mailbox = tMailbox;
    const uint32_t stamp = mailbox.NewStamp();
    uint32_t* const marks = mailbox.marks.data() + firstSlot_;  // stays put, see NewStamp
    uint64_t boxTests = 0;
    const uint32_t* const cellItemsData = cellItems_.data();
    const Bounds3* const childBoxesData = childBoxes_.data();
    const Object* const* const boundedData = bounded_.data();
    for (;;) {
        const int c = CellIndex(cell[0], cell[1], cell[2]);
        if (const int run = emptyRun_[c]; run > 1) {
            // Every cell within run − 1 steps is empty: leave that cube in one move. The ray
            // leaves it through axis `exit` at tLeave, entering the cell `run` steps along
            // that axis; along the others it has crossed the boundaries before tLeave.
            const int inside = run - 1;
            double tLeave = std::numeric_limits<double>::infinity();
            int exit = 0;
            for (int a = 0; a < 3; ++a) {
                if (step[a] == 0) continue;
                const double t = tNext[a] + inside * tDelta[a];
                if (t < tLeave) {
                    tLeave = t;
                    exit = a;
                }
            }
            if (tMax <= tLeave) break;  // the segment ends in empty cells
            bool left = false;
            for (int a = 0; a < 3; ++a) {
                if (step[a] == 0) continue;
                int k = run;
                if (a != exit) {
                    const double crossed = std::ceil((tLeave - tNext[a]) / tDelta[a]);
                    k = crossed > 0 ? (crossed < inside ? static_cast<int>(crossed) : inside) : 0;
                }
                cell[a] += step[a] * k;
                tNext[a] += k * tDelta[a];
                left = left || cell[a] < 0 || cell[a] >= n_[a];
            }
            if (left) break;
            continue;
        }
        // The cell's items as a pointer range: the mark stores below could alias the
        // vectors' own fields, which would otherwise be reloaded at every item.
        const uint32_t* const itemsEnd = cellItemsData + cellStart_[c + 1];
        for (const uint32_t* item = cellItemsData + cellStart_[c]; item < itemsEnd; ++item) {
            const uint32_t id = *item;
            uint32_t& mark = marks[id];
            if (mark == stamp) continue;
            mark = stamp;
            // A child whose box the remaining segment misses cannot be hit later either
            // (the segment only shrinks), so marking it tested is exact.
            ++boxTests;
            if (!childBoxesData[id].MeetsSegment(ray, invDir, tMin, tMax)) continue;
            if (!test(boundedData[id])) continue;
            found = true;
            if (kStopAtFirstHit) {
                Count(kBoundsTests, boxTests);
                return true;
            }
        }
        int axis = tNext[0] < tNext[1] ? 0 : 1;
        if (tNext[2] < tNext[axis]) axis = 2;
        // Every point of the ray before this cell's exit has been covered: stop once the
        // nearest hit (or the end of the segment) lies within this cell.
        if (tMax <= tNext[axis]) break;
        cell[axis] += step[axis];
        if (cell[axis] == stop[axis]) break;
        tNext[axis] += tDelta[axis];
    }
    Count(kBoundsTests, boxTests);
    return found;
}

}  // namespace rs
