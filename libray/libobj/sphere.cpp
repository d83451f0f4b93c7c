#include "libobj/sphere.h"

#include <algorithm>
#include <cmath>

#include "libcommon/constants.h"

namespace rs {

Sphere::Sphere(double radius, const Vec3& center)
    : radius_(radius), radiusSquared_(radius * radius), invRadius_(1 / radius),
      center_(center) {}

std::shared_ptr<Primitive> Sphere::Create(ArgReader& args) {
    const double r = args.ReadNumber();
    const Vec3 c = args.ReadVector();
    if (!(r >= kEpsilon)) {
        args.Warn("Degenerate sphere (radius below epsilon), discarded.");
        return nullptr;
    }
    return std::make_shared<Sphere>(r, c);
}

const IntersectionCounters& Sphere::Counters() const {
    static const IntersectionCounters counters("Sphere");
    return counters;
}

Bounds3 Sphere::Bounds() const {
    const Vec3 e{radius_, radius_, radius_};
    return {center_ - e, center_ + e};
}

bool Sphere::Intersect(const Ray& ray, double tMin, double tMax, PrimitiveHit& hit) const {
    // |oc + t·d|² = r² with a = d·d, b = oc·d (half the linear coefficient). The
    // discriminant b² − a·c is formed as a·(r² − |l|²), l = oc − (b/a)·d the closest
    // approach, which keeps its precision for distant ray origins.
    const Vec3 oc = ray.origin - center_;
    const double a = Dot(ray.dir, ray.dir);
    const double b = Dot(oc, ray.dir);
    const Vec3 l = oc - ray.dir * (b / a);
    const double reduced = radiusSquared_ - Dot(l, l);
    if (reduced < 0) return false;
    const double c = Dot(oc, oc) - radiusSquared_;
    // Stable roots: q has the sign of −b; t = q/a and c/q.
    const double q = -b - std::copysign(std::sqrt(a * reduced), b);
    double tNear = q / a, tFar = q != 0 ? c / q : tNear;
    if (tNear > tFar) std::swap(tNear, tFar);
    return AcceptNearerCrossing(tNear, tFar, tMin, tMax, hit);
}

SurfaceNormals Sphere::Normal(const Vec3& p, const PrimitiveHit&) const {
    const Vec3 n = Normalize((p - center_) * invRadius_);
    return {n, n, false};
}

SurfaceUV Sphere::UV(const Vec3& p, const Vec3&, const PrimitiveHit&) const {
    const Vec3 n = Normalize(p - center_);
    SurfaceUV out;
    const double v = std::acos(std::clamp(-n.z, -1.0, 1.0)) / kPi;
    double u = 0;
    if (v >= kEpsilon && v <= 1 - kEpsilon) {
        u = std::acos(std::clamp(n.x / std::sin(kPi * v), -1.0, 1.0)) / (2 * kPi);
        if (!(n.y > 0)) u = 1 - u;
    }
    out.uv = {u, v};
    const Vec3 dpdu = Normalize(Vec3{-n.y, n.x, 0});
    if (LengthSquared(dpdu) > 0) {
        out.dpdu = dpdu;
        out.dpdv = Cross(n, dpdu);
    }
    return out;
}

bool Sphere::Enters(const Ray&, const PrimitiveHit& hit, const SurfaceNormals&) const {
    return hit.part == 0;
}

}  // namespace rs
