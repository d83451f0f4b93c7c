#include "libobj/disc.h"

#include <algorithm>
#include <cmath>

#include "libcommon/constants.h"
#include "libobj/canonical_frame.h"

namespace rs {

Disc::Disc(double radius, const Vec3& center, const Vec3& normal)
    : radius_(radius), radiusSquared_(radius * radius), center_(center),
      normal_(Normalize(normal)), offset_(Dot(normal_, center)) {}

std::shared_ptr<Primitive> Disc::Create(ArgReader& args) {
    const double r = args.ReadNumber();
    const Vec3 c = args.ReadVector();
    const Vec3 n = args.ReadVector();
    if (!(r >= kEpsilon)) {
        args.Warn("Degenerate disc (radius below epsilon), discarded.");
        return nullptr;
    }
    if (!(LengthSquared(n) > 0)) {
        args.Warn("Degenerate disc normal, disc discarded.");
        return nullptr;
    }
    return std::make_shared<Disc>(r, c, n);
}

const IntersectionCounters& Disc::Counters() const {
    static const IntersectionCounters counters("Disc");
    return counters;
}

Bounds3 Disc::Bounds() const { return CircleBounds(center_, normal_, radius_); }

bool Disc::Intersect(const Ray& ray, double tMin, double tMax, PrimitiveHit& hit) const {
    const double along = Dot(normal_, ray.dir);
    const double t = (offset_ - Dot(normal_, ray.origin)) / along;
    if (!(t > tMin && t < tMax)) return false;
    if (LengthSquared(ray.At(t) - center_) > radiusSquared_) return false;
    hit.t = t;
    hit.part = along < 0 ? 0 : 1;
    return true;
}

SurfaceNormals Disc::Normal(const Vec3&, const PrimitiveHit&) const {
    return {normal_, normal_, false};
}

SurfaceUV Disc::UV(const Vec3& p, const Vec3&, const PrimitiveHit&) const {
    SurfaceUV out;
    const Vec3 rel = p - center_;
    const double dist = Length(rel);
    double u = 0;
    if (dist > 0) {
        u = std::acos(std::clamp(p.x / dist, -1.0, 1.0)) / (2 * kPi);
        if (p.y < 0) u = 1 - u;
        out.dpdv = rel / dist;
        out.dpdu = Cross(normal_, out.dpdv);
    }
    out.uv = {u, dist / radius_};
    return out;
}

}  // namespace rs
