// `sphere r c` (spec §3.9): the points at distance r from c. Closed; hit from both sides.
#pragma once

#include <memory>

#include "libcommon/arg_reader.h"
#include "libobj/primitive.h"

namespace rs {

class Sphere final : public Primitive {
  public:
    // Requires radius ≥ kEpsilon (Create checks).
    Sphere(double radius, const Vec3& center);
    // Reads `r c`; a radius below kEpsilon warns and returns nullptr.
    static std::shared_ptr<Primitive> Create(ArgReader& args);

    const IntersectionCounters& Counters() const override;
    Bounds3 Bounds() const override;
    bool IsClosed() const override { return true; }
    bool Intersect(const Ray& ray, double tMin, double tMax, PrimitiveHit& hit) const override;
    SurfaceNormals Normal(const Vec3& p, const PrimitiveHit& hit) const override;
    SurfaceUV UV(const Vec3& p, const Vec3& facingNormal, const PrimitiveHit& hit) const override;
    // Geometric (spec §3.10): the ray enters iff the hit is the near root of the line, i.e.
    // the ray was outside the sphere just before the hit. hit.part is 0 for the near root
    // and 1 for the far root.
    bool Enters(const Ray& ray, const PrimitiveHit& hit, const SurfaceNormals& n) const override;
    int EntersFromHit(const PrimitiveHit& hit) const override { return hit.part == 0 ? 1 : 0; }

  private:
    double radius_, radiusSquared_, invRadius_;
    Vec3 center_;
};

}  // namespace rs
