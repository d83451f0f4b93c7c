// `plane p n` (spec §3.9): the infinite plane through p with normal n̂. Unbounded, open.
#pragma once

#include <memory>

#include "libcommon/arg_reader.h"
#include "libobj/primitive.h"

namespace rs {

class Plane final : public Primitive {
  public:
    // Requires a non-zero normal (Create checks); it is normalised here.
    Plane(const Vec3& point, const Vec3& normal);
    // Reads `p n`; a zero normal warns and returns nullptr.
    static std::shared_ptr<Primitive> Create(ArgReader& args);

    const IntersectionCounters& Counters() const override;
    // Planes are unbounded: Bounds() is the empty box and must not be used.
    Bounds3 Bounds() const override { return {}; }
    bool IsBounded() const override { return false; }
    bool Intersect(const Ray& ray, double tMin, double tMax, PrimitiveHit& hit) const override;
    SurfaceNormals Normal(const Vec3& p, const PrimitiveHit& hit) const override;
    // Axes Û, V̂ from the RAY-FACING normal (§3.11.1), u = (X−p)·Û, v = (X−p)·V̂: the
    // mapping is mirrored on the back side, as in the original. ∂P/∂u = Û, ∂P/∂v = V̂.
    SurfaceUV UV(const Vec3& p, const Vec3& facingNormal, const PrimitiveHit& hit) const override;

  private:
    Vec3 point_, normal_;
    double offset_;  // normal·point
};

}  // namespace rs
