// `list … end` (spec §3.10): every child is tested and the nearest hit kept.
#pragma once

#include "libobj/aggregate.h"

namespace rs {

class ListAggregate final : public Aggregate {
  public:
    const char* TypeName() const override { return "list"; }

    // Unbounded children are tested first; the bounded ones only when the remaining ray
    // segment (tMin, tMax) meets the union box of the bounded children.
    bool Intersect(const Ray& ray, double tMin, double& tMax, HitRecord& hit) const override;

    // The box of the bounded children (object space) and whether there are any; unbounded
    // children are not described here (Object treats an aggregate holding some as unbounded).
    Bounds3 Bounds() const override { return bounds_; }
    bool IsBounded() const override { return hasBounded_; }

    // Recomputes the box from the children's BoundsInParent(), which Object::PrepareFrame
    // has already brought up to date for this frame.
    void PrepareFrame(double frameTime, double shutter) override;

  private:
    Bounds3 bounds_;
    bool hasBounded_ = false;
};

}  // namespace rs
