#include "libobj/plane.h"

namespace rs {

Plane::Plane(const Vec3& point, const Vec3& normal)
    : point_(point), normal_(Normalize(normal)), offset_(Dot(normal_, point)) {}

std::shared_ptr<Primitive> Plane::Create(ArgReader& args) {
    const Vec3 p = args.ReadVector();
    const Vec3 n = args.ReadVector();
    if (!(LengthSquared(n) > 0)) {
        args.Warn("Degenerate plane normal, plane discarded.");
        return nullptr;
    }
    return std::make_shared<Plane>(p, n);
}

const IntersectionCounters& Plane::Counters() const {
    static const IntersectionCounters counters("Plane");
    return counters;
}

bool Plane::Intersect(const Ray& ray, double tMin, double tMax, PrimitiveHit& hit) const {
    // A ray parallel to the plane gives ±inf or NaN, which the range test rejects.
    const double t = (offset_ - Dot(normal_, ray.origin)) / Dot(normal_, ray.dir);
    if (!(t > tMin && t < tMax)) return false;
    hit.t = t;
    return true;
}

SurfaceNormals Plane::Normal(const Vec3&, const PrimitiveHit&) const {
    return {normal_, normal_, false};
}

SurfaceUV Plane::UV(const Vec3& p, const Vec3& facingNormal, const PrimitiveHit&) const {
    SurfaceUV out;
    CoordinateSystem(facingNormal, out.dpdu, out.dpdv);
    const Vec3 rel = p - point_;
    out.uv = {Dot(rel, out.dpdu), Dot(rel, out.dpdv)};
    return out;
}

}  // namespace rs
