// `list … end` (spec §3.10): the nearest hit among the children. The original tests every
// child; with more than a few bounded children we test only those whose boxes the ray
// segment meets, through a bounding volume hierarchy, which finds the same nearest hit.
#pragma once

#include <vector>

#include "libobj/aggregate.h"
#include "libobj/child_hierarchy.h"

namespace rs {

class ListAggregate final : public Aggregate {
  public:
    const char* TypeName() const override { return "list"; }

    // Unbounded children are tested first; the bounded ones only when the remaining ray
    // segment (tMin, tMax) meets the union box of the bounded children. Without unbounded
    // children that box is the owning node's, which Object::Intersect has already tested.
    bool Intersect(const Ray& ray, double tMin, double& tMax, HitRecord& hit) const override;
    // The same children in the same order, returning at the first hit.
    bool Occluded(const Ray& ray, double tMin, double tMax,
                  const Object** blocker) const override;

    // The box of the bounded children (object space) and whether there are any; unbounded
    // children are not described here (Object treats an aggregate holding some as unbounded).
    Bounds3 Bounds() const override { return bounds_; }
    bool IsBounded() const override { return hasBounded_; }

    // Recomputes the box from the children's BoundsInParent(), which Object::PrepareFrame
    // has already brought up to date for this frame.
    void PrepareFrame(double frameTime, double shutter) override;

  private:
    // Below this many bounded children a linear loop beats the hierarchy's overhead.
    static constexpr size_t kHierarchyThreshold = 4;

    Bounds3 bounds_;
    bool hasBounded_ = false;
    std::vector<const Object*> unbounded_, bounded_;
    ChildHierarchy hierarchy_;  // over bounded_ when there are enough, else empty
};

}  // namespace rs
