// Layer 8 of the implicit module, beside patches_method: a uniform grid of item lists (the
// patches of an object with very many of them), walked along a ray cell by cell in entry
// order with a 3-D DDA (Amanatides and Woo 1987). PatchesMethod uses it instead of its
// bounding volume hierarchy above kGridMinPatches patches (module README, "Fluids").
//
// Each item is listed in every cell its box meets (the box grown by kBinMargin of a cell
// edge, so a point the walk places in a neighbouring cell by rounding is still covered).
// The walk stops at the first cell entered beyond tMax, which the visits may lower (the
// best hit so far): every point of an item's box before tMax lies in a cell entered before
// tMax, so no item whose box meets (tMin, tMax) is left unvisited. An item listed in
// several cells the walk crosses is visited once as long as the walk has met at most
// kVisitedItems distinct items (a hash set on the walk's stack, kept at most half full
// so a lookup probes a few slots); beyond, items it could not record are visited again,
// which costs time only. Build and walk are deterministic (no thread
// count or order enters) and the grid is immutable after construction.
#pragma once

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "libcommon/bounds.h"

namespace rs {

class PatchGrid {
  public:
    // The cell edge, in units of the items' mean box edge (module README, "Fluids").
    static constexpr double kCellEdgePerItemEdge = 0.5;
    // At most this many cells per item (objects spread thinly over a large box).
    static constexpr double kMaxCellsPerItem = 8;
    static constexpr double kBinMargin = 1e-6;
    static constexpr int kVisitedSlots = 256;  // a power of two
    static constexpr int kVisitedItems = kVisitedSlots / 2;

    // Bins items 0..boxes.size()−1 by their boxes (non-empty, finite; fewer than 2^31).
    explicit PatchGrid(const std::vector<Bounds3>& boxes);

    const Bounds3& Bounds() const { return bounds_; }
    // Cells along each axis and list entries in all (for tests and the README).
    int Cells(int axis) const { return dims_[axis]; }
    std::size_t Entries() const { return entries_.size(); }

    // Calls visit(item) for every item listed in a cell the ray's piece (tMin, tMax)
    // crosses, cell by cell in entry order, until the next cell is entered beyond tMax
    // (which visit may lower); visit returns whether it found a hit. Returns whether any
    // visit did. The same contract as BoundingVolumeHierarchy::TraverseInEntryOrder.
    template <class Visit>
    bool TraverseInEntryOrder(const Ray& ray, double tMin, double& tMax, Visit&& visit) const;

  private:
    // The cell of coordinate x along `axis`, clamped to the grid.
    int CellOf(int axis, double x) const {
        const double c = std::floor((x - bounds_.lo[axis]) * invEdge_[axis]);
        if (!(c >= 0)) return 0;
        return c >= dims_[axis] ? dims_[axis] - 1 : static_cast<int>(c);
    }
    std::size_t Index(int x, int y, int z) const {
        return (static_cast<std::size_t>(z) * dims_[1] + y) * dims_[0] + x;
    }

    Bounds3 bounds_;
    Vec3 edge_, invEdge_;
    int dims_[3] = {1, 1, 1};
    // Cell c lists items entries_[cellStart_[c] .. cellStart_[c + 1]), in increasing order.
    std::vector<std::uint32_t> cellStart_;
    std::vector<std::uint32_t> entries_;
};

template <class Visit>
bool PatchGrid::TraverseInEntryOrder(const Ray& ray, double tMin, double& tMax,
                                     Visit&& visit) const {
    const Vec3 invDir{1 / ray.dir.x, 1 / ray.dir.y, 1 / ray.dir.z};
    double entry = tMin, exit = tMax;
    if (entries_.empty() || !bounds_.ClipSegment(ray, invDir, entry, exit)) return false;
    const Vec3 start = ray.At(entry);
    int cell[3], step[3];
    double next[3], delta[3];
    for (int a = 0; a < 3; ++a) {
        cell[a] = CellOf(a, start[a]);
        const double d = ray.dir[a];
        step[a] = d > 0 ? 1 : -1;
        if (d == 0 || std::isnan(d)) {
            next[a] = delta[a] = std::numeric_limits<double>::infinity();
            continue;
        }
        const double plane = bounds_.lo[a] + (cell[a] + (d > 0 ? 1 : 0)) * edge_[a];
        next[a] = (plane - ray.origin[a]) * invDir[a];
        delta[a] = edge_[a] * std::abs(invDir[a]);
    }
    // Open addressing with linear probing; item ids are below 2^31, so kFree is none.
    constexpr std::uint32_t kFree = 0xffffffffu;
    std::uint32_t visited[kVisitedSlots];
    std::fill(visited, visited + kVisitedSlots, kFree);
    int visitedCount = 0;
    const auto firstVisit = [&](std::uint32_t item) {
        // Fibonacci hashing: the top bits of item·2^32/φ spread consecutive ids apart.
        constexpr int kShift = 32 - std::countr_zero(static_cast<unsigned>(kVisitedSlots));
        std::uint32_t slot = (item * 2654435769u) >> kShift;
        while (true) {
            if (visited[slot] == item) return false;
            if (visited[slot] == kFree) {
                if (visitedCount < kVisitedItems) {
                    visited[slot] = item;
                    ++visitedCount;
                }
                return true;
            }
            slot = (slot + 1) & (kVisitedSlots - 1);
        }
    };
    bool found = false;
    while (true) {
        const std::size_t c = Index(cell[0], cell[1], cell[2]);
        for (std::uint32_t k = cellStart_[c]; k < cellStart_[c + 1]; ++k) {
            const std::uint32_t item = entries_[k];
            if (firstVisit(item)) found |= visit(static_cast<int>(item));
        }
        const int a = next[0] < next[1] ? (next[0] < next[2] ? 0 : 2) : (next[1] < next[2] ? 1 : 2);
        entry = next[a];
        if (!(entry <= tMax) || !(entry <= exit)) break;
        cell[a] += step[a];
        if (cell[a] < 0 || cell[a] >= dims_[a]) break;
        next[a] += delta[a];
    }
    return found;
}

}  // namespace rs
