// Layer 8 of the implicit module: method `kb89`, Kalra and Barr's search (1989): one LG
// octree over the object's plain sum with their heuristics only (OctreeHeuristics::Kb89(),
// the declared depth), built by the first ray that needs it. No patches: hits carry no
// owning term, blend and contact statements are ignored (README.md, "Methods").
#pragma once

#include "libobj/implicit/intersection_method.h"
#include "libobj/implicit/lazy_octree.h"
#include "libobj/implicit/object_stats.h"

namespace rs {

class Kb89Method final : public IntersectionMethod {
  public:
    // `whole` and `stats` must outlive the method.
    Kb89Method(const Field& whole, double threshold, const OctreeSettings& settings,
               const ImplicitObjectStats& stats);
    std::optional<double> FirstRoot(const Ray& ray, double tMin, double tMax) const override;
    // The union of the positive terms' support boxes: the surface lies where some
    // positive term is positive (F = T > 0).
    Bounds3 Bounds(const Field&) const override { return box_; }

  private:
    const Field& whole_;
    double threshold_;
    OctreeSettings settings_;
    const ImplicitObjectStats& stats_;
    Bounds3 box_;
    mutable LazyOctree tree_;
};

}  // namespace rs
