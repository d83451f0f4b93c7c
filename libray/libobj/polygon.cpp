#include "libobj/polygon.h"

#include <cmath>
#include <utility>

namespace rs {

Vec3 Polygon::NewellNormal(const std::vector<Vec3>& v) {
    Vec3 n;
    const size_t count = v.size();
    for (size_t i = 0; i < count; ++i) {
        const Vec3& prev = v[(i + count - 1) % count];
        const Vec3& cur = v[i];
        n.x += (prev.y - cur.y) * (prev.z + cur.z);
        n.y += (prev.z - cur.z) * (prev.x + cur.x);
        n.z += (prev.x - cur.x) * (prev.y + cur.y);
    }
    return n;
}

Polygon::Polygon(const std::vector<Vec3>& vertices, bool flip) {
    normal_ = Normalize(NewellNormal(vertices));
    if (flip) normal_ = -normal_;
    Vec3 centroid;
    for (const Vec3& v : vertices) {
        centroid += v;
        bounds_.Extend(v);
    }
    offset_ = Dot(normal_, centroid / static_cast<double>(vertices.size()));

    const double ax = std::fabs(normal_.x), ay = std::fabs(normal_.y), az = std::fabs(normal_.z);
    if (ax > ay && ax > az) {
        axisU_ = 1;
        axisV_ = 2;
    } else if (ay > az) {
        axisU_ = 2;
        axisV_ = 0;
    } else {
        axisU_ = 0;
        axisV_ = 1;
    }
    projected_.reserve(2 * vertices.size());
    for (const Vec3& v : vertices) {
        projected_.push_back(v[axisU_]);
        projected_.push_back(v[axisV_]);
    }
}

std::shared_ptr<Primitive> Polygon::Create(ArgReader& args) {
    // Reused from polygon to polygon (large scenes have hundreds of thousands).
    thread_local std::vector<Vec3> vertices;
    vertices.clear();
    while (args.PeekNumber()) vertices.push_back(args.ReadVector());
    if (vertices.size() < 3) args.Fail("A polygon needs at least three vertices.");
    if (!(LengthSquared(NewellNormal(vertices)) > 0)) {
        args.Warn("Degenerate polygon (no area), discarded.");
        return nullptr;
    }
    return std::make_shared<Polygon>(vertices, args.FlipNormals());
}

const IntersectionCounters& Polygon::Counters() const {
    static const IntersectionCounters counters("Polygon");
    return counters;
}

bool Polygon::Intersect(const Ray& ray, double tMin, double tMax, PrimitiveHit& hit) const {
    const double t = (offset_ - Dot(normal_, ray.origin)) / Dot(normal_, ray.dir);
    if (!(t > tMin && t < tMax)) return false;
    const Vec3 x = ray.At(t);
    const double pu = x[axisU_], pv = x[axisV_];
    // Winding number of the projected outline around (pu, pv): count upward crossings of
    // the horizontal line through the point that pass to its right (+1) and downward ones
    // passing to its left (−1); non-zero means inside.
    int winding = 0;
    const size_t count = projected_.size() / 2;
    for (size_t i = 0, j = count - 1; i < count; j = i++) {
        const double u0 = projected_[2 * j], v0 = projected_[2 * j + 1];
        const double u1 = projected_[2 * i], v1 = projected_[2 * i + 1];
        const double side = (u1 - u0) * (pv - v0) - (pu - u0) * (v1 - v0);
        if (v0 <= pv) {
            if (v1 > pv && side > 0) ++winding;
        } else if (v1 <= pv && side < 0) {
            --winding;
        }
    }
    if (winding == 0) return false;
    hit.t = t;
    return true;
}

SurfaceNormals Polygon::Normal(const Vec3&, const PrimitiveHit&) const {
    return {normal_, normal_, false};
}

SurfaceUV Polygon::UV(const Vec3& p, const Vec3&, const PrimitiveHit&) const {
    SurfaceUV out;
    out.uv = {p.x, p.y};
    return out;
}

}  // namespace rs
