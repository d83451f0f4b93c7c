#include "libobj/cylinder.h"

#include <algorithm>
#include <cmath>

#include "libcommon/constants.h"

namespace rs {

Cylinder::Cylinder(double radius, const Vec3& base, const Vec3& top)
    : radius_(radius), base_(base), top_(top) {
    const Vec3 axis = top - base;
    const double length = Length(axis);
    frame_ = CanonicalFrame(base, axis / length, radius, radius, length);
}

std::shared_ptr<Primitive> Cylinder::Create(ArgReader& args) {
    const double r = args.ReadNumber();
    const Vec3 b = args.ReadVector();
    const Vec3 t = args.ReadVector();
    return CreateChecked(args, r, b, t);
}

std::shared_ptr<Primitive> Cylinder::CreateChecked(ArgReader& args, double radius,
                                                   const Vec3& base, const Vec3& top) {
    if (!(radius > 0)) {
        args.Warn("Invalid cylinder radius, cylinder discarded.");
        return nullptr;
    }
    if (!(Length(top - base) >= kEpsilon)) {
        args.Warn("Degenerate cylinder axis, cylinder discarded.");
        return nullptr;
    }
    return std::make_shared<Cylinder>(radius, base, top);
}

const IntersectionCounters& Cylinder::Counters() const {
    static const IntersectionCounters counters("Cylinder");
    return counters;
}

Bounds3 Cylinder::Bounds() const {
    return Union(CircleBounds(base_, frame_.ZAxis(), radius_),
                 CircleBounds(top_, frame_.ZAxis(), radius_));
}

bool Cylinder::Intersect(const Ray& ray, double tMin, double tMax, PrimitiveHit& hit) const {
    // In canonical space (same t): (o_x + t·d_x)² + (o_y + t·d_y)² = 1, 0 ≤ z ≤ 1.
    const Vec3 o = frame_.ToCanonicalPoint(ray.origin);
    const Vec3 d = frame_.ToCanonicalVector(ray.dir);
    const double a = d.x * d.x + d.y * d.y;
    if (a == 0) return false;  // parallel to the axis: never crosses the wall
    const double b = o.x * d.x + o.y * d.y;
    const double c = o.x * o.x + o.y * o.y - 1;
    const double disc = b * b - a * c;
    if (disc < 0) return false;
    const double q = -b - std::copysign(std::sqrt(disc), b);
    double t0 = q / a, t1 = q != 0 ? c / q : t0;
    if (t0 > t1) std::swap(t0, t1);
    for (double t : {t0, t1}) {
        if (!(t > tMin && t < tMax)) continue;
        const double z = o.z + t * d.z;
        if (z >= 0 && z <= 1) {
            hit.t = t;
            hit.part = a * t + b < 0 ? 0 : 1;  // d·∇f / 2 in canonical space
            return true;
        }
    }
    return false;
}

SurfaceNormals Cylinder::Normal(const Vec3& p, const PrimitiveHit&) const {
    const Vec3 q = frame_.ToCanonicalPoint(p);
    const Vec3 n = Normalize(frame_.FromCanonicalNormal({q.x, q.y, 0}));
    return {n, n, false};
}

SurfaceUV Cylinder::UV(const Vec3& p, const Vec3&, const PrimitiveHit&) const {
    const Vec3 q = frame_.ToCanonicalPoint(p);
    SurfaceUV out;
    double u = std::acos(std::clamp(q.x, -1.0, 1.0)) / (2 * kPi);
    if (q.y < 0) u = 1 - u;
    out.uv = {u, q.z};
    out.dpdu = Normalize(frame_.FromCanonicalVector({-q.y, q.x, 0}));
    out.dpdv = frame_.ZAxis();
    return out;
}

}  // namespace rs
