#include "libobj/torus.h"

#include <algorithm>
#include <cmath>

#include "libcommon/constants.h"
#include "libgeom/polynomial.h"

namespace rs {

Torus::Torus(double sweptRadius, double tubeRadius, const Vec3& center, const Vec3& normal)
    : sweptRadius_(sweptRadius), tubeRadius_(tubeRadius), center_(center),
      frame_(center, Normalize(normal), 1, 1, 1) {}

std::shared_ptr<Primitive> Torus::Create(ArgReader& args) {
    const double sweptRadius = args.ReadNumber();
    const double tubeRadius = args.ReadNumber();
    const Vec3 c = args.ReadVector();
    const Vec3 n = args.ReadVector();
    if (!(sweptRadius >= kEpsilon && tubeRadius >= kEpsilon)) {
        args.Warn("Degenerate torus (a radius below epsilon), discarded.");
        return nullptr;
    }
    if (!(LengthSquared(n) > 0)) {
        args.Warn("Degenerate torus normal, torus discarded.");
        return nullptr;
    }
    return std::make_shared<Torus>(sweptRadius, tubeRadius, c, n);
}

const IntersectionCounters& Torus::Counters() const {
    static const IntersectionCounters counters("Torus");
    return counters;
}

Bounds3 Torus::Bounds() const {
    // The centre circle's box, grown by the tube radius on every side.
    const Vec3 r{tubeRadius_, tubeRadius_, tubeRadius_};
    const Bounds3 ring = CircleBounds(center_, frame_.ZAxis(), sweptRadius_);
    return {ring.lo - r, ring.hi + r};
}

namespace {

// Whether the ray enters (part 0) or leaves (part 1) the solid at the root σ of its quartic
// p (ascending coefficients c): f < 0 inside the tube and p′(σ) = e·∇f, so it enters where
// p′(σ) < 0, the same test as Primitive::Enters (d·Ng < 0, Ng along ∇f) makes with the
// normal. Where |p′(σ)| is below 10⁻⁴ of the size Σ i·|c_i|·σ^(i−1) of its terms, the ray is
// close enough to tangent that the two computations might disagree in sign; part −1 then
// leaves the answer to the normal.
int CrossingPart(const double* c, double sigma) {
    double slope = 4 * c[4], scale = 4 * std::fabs(c[4]);
    for (int i = 3; i >= 1; --i) {
        slope = slope * sigma + i * c[i];
        scale = scale * std::fabs(sigma) + i * std::fabs(c[i]);
    }
    if (!(std::fabs(slope) > 1e-4 * scale)) return -1;
    return slope < 0 ? 0 : 1;
}

}  // namespace

bool Torus::Intersect(const Ray& ray, double tMin, double tMax, PrimitiveHit& hit) const {
    const Vec3 o = frame_.ToCanonicalPoint(ray.origin);
    const Vec3 d = frame_.ToCanonicalVector(ray.dir);  // a rotation: same length as ray.dir

    // Clip to the bounding sphere |q| ≤ R + r (as Sphere::Intersect) ...
    const double a = Dot(d, d);
    const double bound = sweptRadius_ + tubeRadius_;
    const double b = Dot(o, d);
    const Vec3 l = o - d * (b / a);
    const double reduced = bound * bound - Dot(l, l);
    if (reduced < 0) return false;
    const double q = -b - std::copysign(std::sqrt(a * reduced), b);
    double tStart = q / a, tEnd = q != 0 ? (Dot(o, o) - bound * bound) / q : tStart;
    if (tStart > tEnd) std::swap(tStart, tEnd);
    // ... and to the slab |q_z| ≤ r.
    if (d.z != 0) {
        double t0 = (-tubeRadius_ - o.z) / d.z, t1 = (tubeRadius_ - o.z) / d.z;
        if (t0 > t1) std::swap(t0, t1);
        tStart = std::max(tStart, t0);
        tEnd = std::min(tEnd, t1);
    } else if (std::fabs(o.z) > tubeRadius_) {
        return false;
    }
    tStart = std::max(tStart, tMin);
    tEnd = std::min(tEnd, tMax);
    if (!(tStart < tEnd)) return false;

    // f(p + σ·e) with p the segment start, e = d/|d|, σ ∈ [0, (tEnd − tStart)·|d|]:
    // with k = |p|² − R² − r² and g = p·e, |q|² − R² − r² = σ² + 2gσ + k, so
    // f = σ⁴ + 4gσ³ + (4g² + 2k + 4R²e_z²)σ² + (4gk + 8R²p_z e_z)σ + k² + 4R²(p_z² − r²).
    const double length = std::sqrt(a);
    const Vec3 p = o + d * tStart;
    const Vec3 e = d / length;
    const double r2 = sweptRadius_ * sweptRadius_;
    const double g = Dot(p, e);
    const double k = Dot(p, p) - r2 - tubeRadius_ * tubeRadius_;
    const double coeffs[5] = {k * k + 4 * r2 * (p.z * p.z - tubeRadius_ * tubeRadius_),
                              4 * g * k + 8 * r2 * p.z * e.z,
                              4 * g * g + 2 * k + 4 * r2 * e.z * e.z, 4 * g, 1};
    // Roots come nearest first and only as many as needed are computed.
    AscendingRoots roots(coeffs, 4, 0, (tEnd - tStart) * length);
    double sigma;
    while (roots.Next(sigma)) {
        const double t = tStart + sigma / length;
        if (t >= tMax) return false;
        if (t > tMin) {
            hit.t = t;
            hit.part = CrossingPart(coeffs, sigma);
            return true;
        }
    }
    return false;
}

Vec3 Torus::CanonicalNormal(const Vec3& q) const {
    const double rho = std::sqrt(q.x * q.x + q.y * q.y);
    if (rho == 0) return Normalize(q);  // on the axis (only for r ≥ R): no tube centre
    const double s = sweptRadius_ / rho;
    return Normalize(Vec3{q.x - q.x * s, q.y - q.y * s, q.z});
}

SurfaceNormals Torus::Normal(const Vec3& p, const PrimitiveHit&) const {
    const Vec3 n = frame_.FromCanonicalVector(CanonicalNormal(frame_.ToCanonicalPoint(p)));
    return {n, n, false};
}

SurfaceUV Torus::UV(const Vec3& p, const Vec3& facingNormal, const PrimitiveHit&) const {
    const Vec3 q = frame_.ToCanonicalPoint(p);
    const double rho = std::sqrt(q.x * q.x + q.y * q.y);
    SurfaceUV out;
    double u = rho > 0 ? std::acos(std::clamp(q.x / rho, -1.0, 1.0)) / (2 * kPi) : 0;
    if (q.y < 0) u = 1 - u;
    const double cosPsi = std::clamp(-(rho - sweptRadius_) / tubeRadius_, -1.0, 1.0);
    double v = std::acos(cosPsi) / (2 * kPi);
    if (q.z > 0) v = 1 - v;
    out.uv = {u, v};
    if (rho > 0) {
        out.dpdu = Normalize(frame_.FromCanonicalVector({-q.y, q.x, 0}));
        // ∂P/∂v as the original computes it: the ray-facing normal × ∂P/∂u, both already in
        // object space, carried through the canonical-to-object map once more. The second
        // map is a quirk (like the cone's ∂u, spec §3.9) that tilts the bump directions of a
        // torus whose axis is not z; kept because bumped tori (stripe bevels) show it.
        const Vec3 dpdv = frame_.FromCanonicalVector(Cross(facingNormal, out.dpdu));
        if (LengthSquared(dpdv) > 0) out.dpdv = Normalize(dpdv);
    }
    return out;
}

}  // namespace rs
