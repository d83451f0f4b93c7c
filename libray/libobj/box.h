// `box a b` (spec §3.9): the axis-aligned box with opposite corners a and b. Closed; hit
// from both sides. No uv parameterisation (the defaults: (0,0), x̂, ŷ).
#pragma once

#include <memory>

#include "libcommon/arg_reader.h"
#include "libobj/primitive.h"

namespace rs {

class Box final : public Primitive {
  public:
    // Requires every extent |a_i − b_i| ≥ kEpsilon (Create checks).
    Box(const Vec3& cornerA, const Vec3& cornerB);
    // Reads `a b`; an extent below kEpsilon on any axis warns and returns nullptr.
    static std::shared_ptr<Primitive> Create(ArgReader& args);

    const IntersectionCounters& Counters() const override;
    Bounds3 Bounds() const override { return bounds_; }
    bool IsClosed() const override { return true; }
    bool Intersect(const Ray& ray, double tMin, double tMax, PrimitiveHit& hit) const override;
    // The face whose plane lies within kEpsilon of p, tested in the order +x, −x, +y, −y,
    // +z, −z (the original's order, which decides edges and corners); if none is that
    // close (round-off on huge boxes), the nearest face.
    SurfaceNormals Normal(const Vec3& p, const PrimitiveHit& hit) const override;
    // Geometric (spec §3.10): entering iff the hit is where the ray's line enters the slab
    // intersection (hit.part 0), i.e. the ray was outside the box just before the hit.
    bool Enters(const Ray& ray, const PrimitiveHit& hit, const SurfaceNormals& n) const override;
    int EntersFromHit(const PrimitiveHit& hit) const override { return hit.part == 0 ? 1 : 0; }

  private:
    Bounds3 bounds_;
};

}  // namespace rs
