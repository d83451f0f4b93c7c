// `cylinder r b t` (spec §3.9): the points at distance r from the axis b→t lying between b
// and t; no end caps. Open. Canonical frame (canonical_frame.h): x² + y² = 1, 0 ≤ z ≤ 1,
// scaled by (r, r, |t − b|), origin b.
#pragma once

#include <memory>

#include "libcommon/arg_reader.h"
#include "libobj/canonical_frame.h"
#include "libobj/primitive.h"

namespace rs {

class Cylinder final : public Primitive {
  public:
    // Requires radius > 0 and |top − base| ≥ kEpsilon (Create checks).
    Cylinder(double radius, const Vec3& base, const Vec3& top);
    // Reads `r b t`; r ≤ 0 or |t − b| < kEpsilon warns and returns nullptr.
    static std::shared_ptr<Primitive> Create(ArgReader& args);
    // The checks of Create for already-read arguments (the cone's r1 ≈ r2 case uses it).
    static std::shared_ptr<Primitive> CreateChecked(ArgReader& args, double radius,
                                                    const Vec3& base, const Vec3& top);

    const IntersectionCounters& Counters() const override;
    Bounds3 Bounds() const override;
    bool Intersect(const Ray& ray, double tMin, double tMax, PrimitiveHit& hit) const override;
    // Radial, outward.
    SurfaceNormals Normal(const Vec3& p, const PrimitiveHit& hit) const override;
    // Canonical q: v = q_z, u = acos(q_x)/(2π), 1 − u when q_y < 0. ∂P/∂u is the azimuthal
    // tangent, ∂P/∂v the axis direction.
    SurfaceUV UV(const Vec3& p, const Vec3& facingNormal, const PrimitiveHit& hit) const override;
    // Intersect records in hit.part whether the ray enters (0) or leaves (1) the wall, from
    // the sign of the radial field's derivative along the ray, d·∇f, which is the sign of
    // d·n the default Enters computes from the normal. Saves CSG the normal.
    int EntersFromHit(const PrimitiveHit& hit) const override { return hit.part == 0 ? 1 : 0; }

  private:
    double radius_;
    Vec3 base_, top_;
    CanonicalFrame frame_;
};

}  // namespace rs
