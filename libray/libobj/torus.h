// `torus R r c n` (spec §3.9): the circle of radius r swept around the axis n̂ through c at
// distance R. Closed. Canonical frame (canonical_frame.h, unit scale): centre at the
// origin, axis +z, implicit f(q) = (|q|² − R² − r²)² + 4R²(q_z² − r²) = 0 (f < 0 inside the
// tube).
#pragma once

#include <memory>

#include "libcommon/arg_reader.h"
#include "libobj/canonical_frame.h"
#include "libobj/primitive.h"

namespace rs {

class Torus final : public Primitive {
  public:
    // Requires R ≥ kEpsilon, r ≥ kEpsilon and a non-zero normal (Create checks).
    Torus(double sweptRadius, double tubeRadius, const Vec3& center, const Vec3& normal);
    // Reads `R r c n`; R or r below kEpsilon or a zero normal warns and returns nullptr.
    static std::shared_ptr<Primitive> Create(ArgReader& args);

    const IntersectionCounters& Counters() const override;
    Bounds3 Bounds() const override;
    bool IsClosed() const override { return true; }
    // Solves the quartic along the part of the ray inside the bounding sphere (radius
    // R + r) and the slab |q_z| ≤ r, with the origin moved to the segment start and the
    // direction made unit length so the coefficients stay well conditioned.
    bool Intersect(const Ray& ray, double tMin, double tMax, PrimitiveHit& hit) const override;
    // From the tube's centre circle to the hit point.
    SurfaceNormals Normal(const Vec3& p, const PrimitiveHit& hit) const override;
    // Intersect records the crossing's direction in hit.part (0 enters, 1 leaves) unless
    // the ray is nearly tangent there (−1: decided by the normal).
    int EntersFromHit(const PrimitiveHit& hit) const override {
        return hit.part < 0 ? -1 : hit.part == 0 ? 1 : 0;
    }
    // Canonical q, ρ = |(q_x, q_y)|: u = acos(q_x/ρ)/(2π), 1 − u when q_y < 0;
    // v = acos(−(ρ − R)/r)/(2π), 1 − v when q_z > 0 (0 on the innermost ring, ½ on the
    // outer equator). ∂P/∂u, ∂P/∂v are the tangents of the two circles, directions of
    // growing u and v.
    SurfaceUV UV(const Vec3& p, const Vec3& facingNormal, const PrimitiveHit& hit) const override;

  private:
    // Canonical unit normal at canonical point q.
    Vec3 CanonicalNormal(const Vec3& q) const;

    double sweptRadius_, tubeRadius_;
    Vec3 center_;
    CanonicalFrame frame_;
};

}  // namespace rs
