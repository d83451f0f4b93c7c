// `cone r1 p1 r2 p2` (spec §3.9): the truncated cone whose radius varies linearly from r1
// at p1 to r2 at p2; no end caps. Open. Canonical frame (canonical_frame.h):
// x² + y² = z², s ≤ z ≤ 1, apex at the origin, the larger radius R at z = 1 and
// s = r_small / R (the ends are swapped internally so z grows toward the larger radius).
#pragma once

#include <memory>

#include "libcommon/arg_reader.h"
#include "libobj/canonical_frame.h"
#include "libobj/primitive.h"

namespace rs {

class Cone final : public Primitive {
  public:
    // Requires r1, r2 ≥ 0, |r1 − r2| ≥ kEpsilon and |p2 − p1| ≥ kEpsilon (Create checks).
    Cone(double r1, const Vec3& p1, double r2, const Vec3& p2);
    // Reads `r1 p1 r2 p2`. |r1 − r2| < kEpsilon returns a Cylinder of radius r1 instead;
    // a negative radius or |p2 − p1| < kEpsilon warns and returns nullptr.
    static std::shared_ptr<Primitive> Create(ArgReader& args);

    const IntersectionCounters& Counters() const override;
    Bounds3 Bounds() const override;
    bool Intersect(const Ray& ray, double tMin, double tMax, PrimitiveHit& hit) const override;
    // The outward lateral normal.
    SurfaceNormals Normal(const Vec3& p, const PrimitiveHit& hit) const override;
    // Canonical q: v = (q_z − s)/(1 − s) (0 at the smaller end); u = acos(q_x/q_z)/(2π),
    // 1 − u when q_y < 0 (u = 0 when q_z < ε). ∂P/∂u is the azimuthal tangent, ∂P/∂v the
    // generator direction from the apex.
    SurfaceUV UV(const Vec3& p, const Vec3& facingNormal, const PrimitiveHit& hit) const override;
    // Intersect records in hit.part whether the ray enters (0) or leaves (1), from the sign
    // of d·∇f along the ray (f = x² + y² − z² in canonical space), which is the sign of d·n
    // the default Enters computes from the normal. Saves CSG the normal.
    int EntersFromHit(const PrimitiveHit& hit) const override { return hit.part == 0 ? 1 : 0; }

  private:
    double smallRadius_, largeRadius_;
    Vec3 smallEnd_, largeEnd_;
    double start_;  // s
    CanonicalFrame frame_;
};

}  // namespace rs
