// Layer 8 of the implicit module: method `patches`, Gascuel's implicit patches (1995). It
// owns everything the method needs: one patch per positive-weight skeleton (patch.h; its
// neighbours automatic or from the blend graph), the contacts that deform them (contact.h),
// one LG octree per patch, made by the first ray reaching the patch (LazyOctree) and, but
// for objects with contacts, grown per cell by the rays (LGOctree's per-cell mode, under
// one budget for the object), and a bounding volume hierarchy over the patch boxes that
// rays walk front to back (above gridMinPatches patches a uniform grid of them instead,
// patch_grid.h).
//
// The octree settings are the object's (its RootSearchSettings and OctreeHeuristics), with
// each patch's depth chosen from its own skeleton under `octree auto` (AutoMinDepth).
// Objects with contacts build every tree whole and at once (the contacts measure with
// them); the others build each tree lazily: whole, or per cell for objects of more than
// kPerCellMinPatches patches, whose automatic neighbour lists are also made per patch by
// the first ray that needs them.
#pragma once

#include <cstddef>
#include <memory>
#include <mutex>
#include <utility>
#include <vector>

#include "libgeom/bvh.h"
#include "libobj/implicit/contact.h"
#include "libobj/implicit/implicit_options.h"
#include "libobj/implicit/intersection_method.h"
#include "libobj/implicit/lazy_octree.h"
#include "libobj/implicit/object_stats.h"
#include "libobj/implicit/patch.h"
#include "libobj/implicit/patch_grid.h"

namespace rs {

class PatchesMethod final : public IntersectionMethod {
  public:
    // `whole` (the object's plain sum) and `stats` must outlive the method; `options`
    // gives the threshold, octree settings, auto depth, blend graph and contacts. Rays walk
    // a PatchGrid of the patches when there are more than `gridMinPatches` (tests lower it),
    // else a bounding volume hierarchy.
    PatchesMethod(const Field& whole, const ImplicitOptions& options,
                  const ImplicitObjectStats& stats,
                  std::size_t gridMinPatches = kGridMinPatches);

    std::optional<double> FirstRoot(const Ray& ray, double tMin, double tMax) const override;
    // The first root of every patch's search, the owning term being the patch's own.
    std::optional<MethodHit> Intersect(const Ray& ray, double tMin, double tMax) const override;
    // −∇ of the owning patch's field (equal to the object's field there), and where it
    // vanishes the direction away from the patch's own skeleton.
    Vec3 Normal(const Field& whole, const Vec3& p, int term) const override;
    // The union of the patch boxes.
    Bounds3 Bounds(const Field&) const override { return bounds_; }

    // The patches; for objects whose neighbour lists are made lazily (see FullPatch), each
    // with its own term alone as member.
    const std::vector<Patch>& Patches() const { return patches_; }
    // What the contacts did to the patches (contact.h; empty without contacts).
    const std::vector<DeformedPatch>& Contacts() const { return contacts_; }

    // The depth of heuristics 3 and 3bis for a patch under `octree auto` (see the .cpp).
    static int AutoMinDepth(const Patch& patch, double threshold);

    // Objects with more patches than this are walked through a PatchGrid: measured in the
    // module README ("Fluids").
    static constexpr std::size_t kGridMinPatches = 2048;
    // Whether the object walks a grid (there is then no hierarchy).
    bool WalksGrid() const { return grid_ != nullptr; }

  private:
    // The per-cell trees of an object keep at most this many times one tree's memory budget
    // (OctreeHeuristics::memoryBudget) of cells between them.
    static constexpr std::size_t kCellBudgetTrees = 4;
    // Objects with more patches than this grow their trees per cell; the others build each
    // patch's whole tree when its first ray reaches it. The crossover measured between
    // 1,000 and 3,000 patches (module README, "Per-cell trees").
    static constexpr std::size_t kPerCellMinPatches = 2048;

    // The octree settings of a patch (the object's, with the auto depth).
    OctreeSettings PatchSettings(const Patch& patch) const;
    // Patch i with its neighbours: patches_[i], or for objects of per-cell trees with
    // automatic neighbours the patch with the member list BuildPatches would give it, made
    // by the first call (AutomaticNeighbours: at a million points the lists were 1.6 of the
    // 3.8 s of serial setup, and rays need a quarter of them). Thread-safe.
    const Patch& FullPatch(int i) const;
    // Tree of patch i, building it on first use. Thread-safe.
    const LGOctree& Tree(int i) const;
    // Calls visit(patch) for the patches the ray's piece may meet, front to back, through
    // the grid or the hierarchy (their common TraverseInEntryOrder contract).
    template <class Visit>
    void WalkPatches(const Ray& ray, double tMin, double& tMax, Visit&& visit) const;
    // The largest distance between a root a search of this method may accept on `ray`
    // and the true root it stands for, in world units (Patch::ClipToOwnRegion's margin).
    double SeamUncertainty(const Ray& ray) const;
    // The patch owning a term's hits (−1 for terms without a patch).
    int PatchOf(int term) const { return term >= 0 ? patchOfTerm_[term] : -1; }

    double threshold_;
    OctreeSettings settings_;
    bool autoDepth_;
    const ImplicitObjectStats& stats_;
    const Field& whole_;
    std::vector<Patch> patches_;
    // The lazily made patches (FullPatch; null for the others).
    struct LazyPatch {
        std::once_flag once;
        std::unique_ptr<const Patch> patch;
    };
    std::unique_ptr<AutomaticNeighbours> neighbours_;
    std::unique_ptr<LazyPatch[]> lazyPatches_;
    std::vector<int> patchOfTerm_;
    // The budget and observer of the per-cell trees (declared before the trees: they
    // release their cells to it).
    std::unique_ptr<LazyCellStore> cellStore_;
    std::unique_ptr<LazyOctree[]> trees_;  // one per patch
    std::vector<DeformedPatch> contacts_;
    Bounds3 bounds_;
    BoundingVolumeHierarchy bvh_;  // over the patch boxes, one item per patch (no grid_)
    std::unique_ptr<const PatchGrid> grid_;  // of the patch boxes (null: bvh_)
    // Patch i's Patch::StaticSupportBall(), or reach kNoBall where it has none (MayHoldRoot
    // is asked then): the walk's first test reads 32 bytes per patch.
    static constexpr double kNoBall = -1;
    std::vector<Patch::SupportBall> supportBalls_;
    // Patch i's MayHoldRoot, from supportBalls_ where it can.
    bool MayHoldRoot(int i, const Ray& ray, double tMin, double tMax) const {
        if (supportBalls_[i].reach != kNoBall) return supportBalls_[i].MayMeet(ray, tMin, tMax);
        return patches_[i].MayHoldRoot(ray, tMin, tMax);
    }
};

}  // namespace rs
