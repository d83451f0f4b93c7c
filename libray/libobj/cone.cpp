#include "libobj/cone.h"

#include <algorithm>
#include <cmath>

#include "libcommon/constants.h"
#include "libobj/cylinder.h"

namespace rs {

Cone::Cone(double r1, const Vec3& p1, double r2, const Vec3& p2) {
    const bool firstIsSmall = r1 < r2;
    smallRadius_ = firstIsSmall ? r1 : r2;
    largeRadius_ = firstIsSmall ? r2 : r1;
    smallEnd_ = firstIsSmall ? p1 : p2;
    largeEnd_ = firstIsSmall ? p2 : p1;
    const Vec3 axis = largeEnd_ - smallEnd_;
    const double length = Length(axis);
    const Vec3 unitAxis = axis / length;
    // The radius grows by (R − r)/length per unit length, so the apex lies r·length/(R − r)
    // before the small end and the full cone is `total` long from apex to large end.
    const double apexGap = smallRadius_ * length / (largeRadius_ - smallRadius_);
    const double total = apexGap + length;
    start_ = apexGap / total;
    frame_ = CanonicalFrame(smallEnd_ - unitAxis * apexGap, unitAxis, largeRadius_, largeRadius_,
                            total);
}

std::shared_ptr<Primitive> Cone::Create(ArgReader& args) {
    const double r1 = args.ReadNumber();
    const Vec3 p1 = args.ReadVector();
    const double r2 = args.ReadNumber();
    const Vec3 p2 = args.ReadVector();
    if (std::fabs(r1 - r2) < kEpsilon) return Cylinder::CreateChecked(args, r1, p1, p2);
    if (!(r1 >= 0 && r2 >= 0)) {
        args.Warn("Negative cone radius, cone discarded.");
        return nullptr;
    }
    if (!(Length(p2 - p1) >= kEpsilon)) {
        args.Warn("Degenerate cone axis, cone discarded.");
        return nullptr;
    }
    return std::make_shared<Cone>(r1, p1, r2, p2);
}

const IntersectionCounters& Cone::Counters() const {
    static const IntersectionCounters counters("Cone");
    return counters;
}

Bounds3 Cone::Bounds() const {
    return Union(CircleBounds(smallEnd_, frame_.ZAxis(), smallRadius_),
                 CircleBounds(largeEnd_, frame_.ZAxis(), largeRadius_));
}

bool Cone::Intersect(const Ray& ray, double tMin, double tMax, PrimitiveHit& hit) const {
    // In canonical space (same t): x² + y² − z² = 0 along o + t·d, with s ≤ z ≤ 1.
    const Vec3 o = frame_.ToCanonicalPoint(ray.origin);
    const Vec3 d = frame_.ToCanonicalVector(ray.dir);
    const double a = d.x * d.x + d.y * d.y - d.z * d.z;
    const double b = o.x * d.x + o.y * d.y - o.z * d.z;
    const double c = o.x * o.x + o.y * o.y - o.z * o.z;
    double roots[2];
    int n = 0;
    if (std::fabs(a) < kEpsilon * LengthSquared(d)) {
        // Direction (nearly) along a generator: the quadratic degenerates to 2bt + c = 0
        // (the original's single linear root, with its ε taken relative to |d|²).
        if (b == 0) return false;
        roots[n++] = -0.5 * c / b;
    } else {
        const double disc = b * b - a * c;
        if (disc < 0) return false;
        const double q = -b - std::copysign(std::sqrt(disc), b);
        roots[0] = q / a;
        roots[1] = q != 0 ? c / q : roots[0];
        if (roots[0] > roots[1]) std::swap(roots[0], roots[1]);
        n = 2;
    }
    for (int i = 0; i < n; ++i) {
        const double t = roots[i];
        if (!(t > tMin && t < tMax)) continue;
        const double z = o.z + t * d.z;
        if (z >= start_ && z <= 1) {
            hit.t = t;
            hit.part = a * t + b < 0 ? 0 : 1;  // d·∇f / 2 in canonical space
            return true;
        }
    }
    return false;
}

SurfaceNormals Cone::Normal(const Vec3& p, const PrimitiveHit&) const {
    const Vec3 q = frame_.ToCanonicalPoint(p);
    // ∇(x² + y² − z²)/2, outward for the nappe z > 0.
    const Vec3 n = Normalize(frame_.FromCanonicalNormal({q.x, q.y, -q.z}));
    return {n, n, false};
}

SurfaceUV Cone::UV(const Vec3& p, const Vec3&, const PrimitiveHit&) const {
    const Vec3 q = frame_.ToCanonicalPoint(p);
    SurfaceUV out;
    double u = 0;
    if (q.z >= kEpsilon) {
        const double ratio = q.x / q.z;
        if (ratio >= 1) {
            u = 0;
        } else if (ratio <= -1) {
            u = 0.5;
        } else {
            u = std::acos(ratio) / (2 * kPi);
            if (q.y < 0) u = 1 - u;
        }
    }
    out.uv = {u, (q.z - start_) / (1 - start_)};
    const Vec3 dpdu = Normalize(frame_.FromCanonicalVector({-q.y, q.x, 0}));
    if (LengthSquared(dpdu) > 0) out.dpdu = dpdu;
    const Vec3 dpdv = Normalize(frame_.FromCanonicalVector(q));
    if (LengthSquared(dpdv) > 0) out.dpdv = dpdv;
    return out;
}

}  // namespace rs
