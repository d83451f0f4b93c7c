// `blob T s1 r1 c1 [s2 r2 c2 ...]`: the original's metaballs (spec §3.9). Each ball adds
// s·(1 − |X−c|²/r²)² inside its radius r; the surface is where the sum equals T.
//
// Intersection follows the original (clip the ray against every sphere of influence, sort
// the boundaries, solve the quartic of each interval with a constant active set) without
// its two precision defects (research note §8), through MetaballSum (metaball_sum.h):
//  * each interval's quartic is formed relative to the interval's start point, not the ray
//    origin, so no digits are lost when the camera is far away;
//  * every root of an interval is considered and the smallest one beyond tMin is taken,
//    so a ray starting a hair outside the surface still finds the exit root.
#pragma once

#include <memory>
#include <vector>

#include "libcommon/arg_reader.h"
#include "libgeom/metaball_sum.h"
#include "libobj/primitive.h"

namespace rs {

class Blob final : public Primitive {
  public:
    // Requires at least one ball, every strength and radius ≥ ε.
    Blob(double threshold, std::vector<Metaball> balls);

    static std::shared_ptr<Primitive> Create(ArgReader& args);

    const IntersectionCounters& Counters() const override;
    Bounds3 Bounds() const override { return sum_.Bounds(); }
    bool IsClosed() const override { return true; }
    bool Intersect(const Ray& ray, double tMin, double tMax, PrimitiveHit& hit) const override;
    SurfaceNormals Normal(const Vec3& p, const PrimitiveHit& hit) const override;

    // The field Σ s(1 − ρ²/r²)² at p (exposed for tests).
    double Field(const Vec3& p) const { return sum_.Value(p); }

  private:
    MetaballSum sum_;
};

}  // namespace rs
