// `grid nx ny nz … end` (spec §3.10): a uniform voxel grid over the bounded children,
// traversed front to back with a 3-D DDA, or, when that is expected to be cheaper, the
// hierarchy a list builds over them (the grid's resolution then only bounds its entry
// count, as for voxels). Either finds exactly the hit a list would.
#pragma once

#include <cstdint>
#include <vector>

#include "libobj/aggregate.h"
#include "libobj/child_hierarchy.h"

namespace rs {

class GridAggregate final : public Aggregate {
  public:
    // Resource limits (docs/robustness.md). Voxels: 2^24 (64 MiB of cell offsets), which
    // also keeps CellIndex within int. Voxel entries (one per child per voxel its box
    // overlaps, 4 bytes each): 2^28, 1 GiB; PrepareFrame reports an Abort beyond it.

    // Voxel counts per axis. Counts below 1 are raised to 1 (the parser warns and discards
    // such grids before building one); nx·ny·nz <= Limits().gridVoxels (the parser refuses more).
    // How the bounded children are searched: Automatic chooses, per frame, whichever of
    // the voxels and the hierarchy has the lower surface-area cost estimate (see
    // PrepareFrame); the others force one (tests of either walk).
    enum class Search { Automatic, Voxels, Hierarchy };
    GridAggregate(int nx, int ny, int nz, Search search = Search::Automatic);

    const char* TypeName() const override { return "grid"; }

    // Unbounded children are tested first, then the bounded ones: through the hierarchy, or
    // the voxels the segment (tMin, tMax) crosses, front to back, until the nearest hit so
    // far lies within the current voxel (runs of empty voxels are crossed in one move). In
    // the voxels, each bounded child is considered at most once per call (per-thread
    // mailboxes) and tested only when the remaining segment meets its box. Thread-safe.
    // Requires PrepareFrame to have run.
    bool Intersect(const Ray& ray, double tMin, double& tMax, HitRecord& hit) const override;
    // The same walk, returning at the first hit.
    bool Occluded(const Ray& ray, double tMin, double tMax,
                  const Object** blocker) const override;

    // The box of the bounded children (object space) and whether there are any.
    Bounds3 Bounds() const override { return bounds_; }
    bool IsBounded() const override { return !bounded_.empty(); }

    // Rebuilds the grid from the children's BoundsInParent() for this frame. Throws
    // FatalError (after rs::Report) when the children would need more than Limits().gridEntries
    // voxel entries (whichever search is then chosen).
    void PrepareFrame(double frameTime, double shutter) override;
    // Whether this frame's search walks the voxels (false: the hierarchy).
    bool SearchesVoxels() const { return hierarchy_.IsEmpty(); }

  private:
    // The voxel walk over the bounded children: test(child) searches one child (it may shrink
    // tMax through the caller's state, which the walk reads back) and returns whether it hit.
    // Returns whether any test hit; with kStopAtFirstHit returns at the first.
    template <bool kStopAtFirstHit, class Test>
    bool Walk(const Ray& ray, double tMin, double& tMax, Test&& test) const;
    // The voxel index along `axis` holding coordinate x (clamped to the grid).
    int VoxelOf(double x, int axis) const;
    int CellIndex(int ix, int iy, int iz) const { return (iz * n_[1] + iy) * n_[0] + ix; }
    // Fills emptyRun_ from the cells' contents.
    void ComputeEmptyRuns();

    // The voxels' expected cost for a ray through the grid box, in the hierarchy's units
    // (BoundingVolumeHierarchy::ExpectedCost), given the total count of voxel entries.
    double ExpectedVoxelCost(uint64_t entries) const;
    // A voxel step and a voxel entry (mailbox check and box test) against one hierarchy
    // unit (a four-box node test or an item visit), calibrated on the SPD grid files'
    // render instructions (bench/spd.sh): with these weights the estimate picks the voxels
    // for gears (voxels 0.84x the hierarchy's instructions) and the hierarchy for balls,
    // mount and teapot (0.90x, 0.77x, 0.60x the voxels'), tetra and tree.
    static constexpr double kVoxelStepCost = 0.25, kVoxelEntryCost = 0.25;

    // The build's tasks (RunBuildLoop): children in chunks of kChunk for their
    // voxel ranges, cells in at most kSlabs slabs of z layers for the voxel lists.
    static constexpr size_t kChunk = 4096;
    static constexpr int kSlabs = 16;

    int n_[3];
    Search search_;
    ChildHierarchy hierarchy_;  // this frame's search when built, else the voxels
    Bounds3 bounds_;   // union of the bounded children's boxes
    Bounds3 gridBox_;  // bounds_ padded by kEpsilon: the voxelised region
    Vec3 voxelSize_;
    std::vector<const Object*> bounded_;
    std::vector<const Object*> unbounded_;
    std::vector<Bounds3> childBoxes_;  // bounded_[i]'s box padded by kEpsilon
    // This grid's mailbox slots: firstSlot_ + i is bounded_[i]'s (see grid.cpp).
    size_t firstSlot_ = 0, slotCount_ = 0;
    // Compressed rows: cell c holds bounded_[cellItems_[k]] for cellStart_[c] <= k <
    // cellStart_[c + 1].
    std::vector<uint32_t> cellStart_;
    std::vector<uint32_t> cellItems_;
    // Per cell: 0 when it holds children; otherwise the chessboard distance (in cells, at
    // most kMaxEmptyRun) to the nearest cell that does, so every cell fewer steps away is
    // empty and the walk may cross them in one move.
    static constexpr uint8_t kMaxEmptyRun = 255;
    std::vector<uint8_t> emptyRun_;
};

}  // namespace rs
