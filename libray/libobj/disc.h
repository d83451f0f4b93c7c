// `disc r c n` (spec §3.9): the points X of the plane through c with normal n̂ and
// |X − c| ≤ r. Open, one-sided in geometry but hit from both sides.
#pragma once

#include <memory>

#include "libcommon/arg_reader.h"
#include "libobj/primitive.h"

namespace rs {

class Disc final : public Primitive {
  public:
    // Requires radius ≥ kEpsilon and a non-zero normal (Create checks).
    Disc(double radius, const Vec3& center, const Vec3& normal);
    // Reads `r c n`; a radius below kEpsilon or a zero normal warns and returns nullptr.
    static std::shared_ptr<Primitive> Create(ArgReader& args);

    const IntersectionCounters& Counters() const override;
    Bounds3 Bounds() const override;
    bool Intersect(const Ray& ray, double tMin, double tMax, PrimitiveHit& hit) const override;
    SurfaceNormals Normal(const Vec3& p, const PrimitiveHit& hit) const override;
    // v = |X − c| / r; u = acos(X_x / |X − c|)/(2π), 1 − u when X_y < 0, with the ABSOLUTE
    // object-space X_x, X_y as in the original (meaningful for discs centred at the origin
    // in the xy-plane). ∂P/∂v is the radial direction, ∂P/∂u = n̂ × radial.
    SurfaceUV UV(const Vec3& p, const Vec3& facingNormal, const PrimitiveHit& hit) const override;
    // Intersect records in hit.part whether the ray meets the disc against its normal (0,
    // entering) or along it (1): the default Enters test d·n < 0, without the normal call.
    int EntersFromHit(const PrimitiveHit& hit) const override { return hit.part == 0 ? 1 : 0; }

  private:
    double radius_, radiusSquared_;
    Vec3 center_, normal_;
    double offset_;  // normal·center
};

}  // namespace rs
