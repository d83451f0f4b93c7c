#include "libobj/triangle.h"

#include <cmath>

#include "libcommon/constants.h"

namespace rs {

namespace {

Vec3 EdgeCross(const Triangle::Points& p) { return Cross(p[1] - p[0], p[2] - p[1]); }

}  // namespace

bool Triangle::IsDegenerate(const Triangle::Points& p) {
    return !(LengthSquared(EdgeCross(p)) > 0);
}

Triangle::Triangle(const Points& p, bool flip) : p1_(p[0]), p2_(p[1]), p3_(p[2]) {
    // (p2 − p1) × (p3 − p2) = e2 × e3 with e2 = p2 − p1, e3 = p3 − p1. For X − p1 =
    // b2·e2 + b3·e3: b2 = (X − p1)·(e3 × m)/|m|², b3 = (X − p1)·(m × e2)/|m|², m = e2 × e3.
    const Vec3 m = EdgeCross(p);
    const double m2 = LengthSquared(m);
    const Vec3 e2 = p[1] - p[0], e3 = p[2] - p[0];
    dual2_ = Cross(e3, m) / m2;
    dual3_ = Cross(m, e2) / m2;
    normal_ = Normalize(m);
    if (flip) normal_ = -normal_;
}

Triangle::Triangle(const Points& p, const Points& normals, bool flip)
    : Triangle(p, normals, nullptr, flip) {}

Triangle::Triangle(const Points& p, const Points& normals, const UVs& uv, bool flip)
    : Triangle(p, normals, &uv, flip) {}

Triangle::Triangle(const Points& p, const Points& normals, const UVs* uv, bool flip)
    : Triangle(p, flip) {
    auto shading = std::make_unique<Shading>();
    for (int i = 0; i < 3; ++i) {
        shading->normals[i] = Normalize(normals[i]);
        if (flip) shading->normals[i] = -shading->normals[i];
    }
    // Trust the vertex normals over the vertex order.
    if (!flip && Dot(shading->normals[0], normal_) < 0) normal_ = -normal_;
    if (uv) {
        shading->hasUV = true;
        shading->uv = *uv;
        // Solve e2 = du2·∂P/∂u + dv2·∂P/∂v, e3 = du3·∂P/∂u + dv3·∂P/∂v; when the uv
        // triangle is degenerate fall back to the plain triangle's edge directions.
        const Vec3 e2 = p[1] - p[0], e3 = p[2] - p[0];
        const double du2 = (*uv)[1].u - (*uv)[0].u, dv2 = (*uv)[1].v - (*uv)[0].v;
        const double du3 = (*uv)[2].u - (*uv)[0].u, dv3 = (*uv)[2].v - (*uv)[0].v;
        const double det = du2 * dv3 - du3 * dv2;
        if (std::fabs(det) > kEpsilon * kEpsilon) {
            shading->dpdu = Normalize((e2 * dv3 - e3 * dv2) / det);
            shading->dpdv = Normalize((e3 * du2 - e2 * du3) / det);
        } else {
            shading->dpdu = Normalize(e2);
            shading->dpdv = Normalize(Cross(normal_, shading->dpdu));
        }
    }
    shading_ = std::move(shading);
}

namespace {

// Checks shared by both Phong forms; returns false (after reporting) when discarding.
bool CheckPhong(ArgReader& args, const Triangle::Points& p, const Triangle::Points& n) {
    if (Triangle::IsDegenerate(p)) {
        args.Advise("Degenerate triangle, discarded.");
        return false;
    }
    for (const Vec3& v : n) {
        if (!(LengthSquared(v) > 0)) {
            args.Warn("Degenerate triangle vertex normal, triangle discarded.");
            return false;
        }
    }
    if (!args.FlipNormals() && Dot(n[0], EdgeCross(p)) < 0) {
        args.Advise("Inconsistent triangle normals.");
    }
    return true;
}

}  // namespace

std::shared_ptr<Primitive> Triangle::Create(ArgReader& args) {
    const Vec3 v1 = args.ReadVector(), v2 = args.ReadVector(), v3 = args.ReadVector();
    if (!args.PeekNumber()) {
        const Points p{v1, v2, v3};
        if (IsDegenerate(p)) {
            args.Advise("Degenerate triangle, discarded.");
            return nullptr;
        }
        return std::make_shared<Triangle>(p, args.FlipNormals());
    }
    const Vec3 v4 = args.ReadVector(), v5 = args.ReadVector(), v6 = args.ReadVector();
    const Points p{v1, v3, v5}, n{v2, v4, v6};
    if (!CheckPhong(args, p, n)) return nullptr;
    return std::make_shared<Triangle>(p, n, args.FlipNormals());
}

std::shared_ptr<Primitive> Triangle::CreateUV(ArgReader& args) {
    Points p, n;
    UVs uv;
    for (int i = 0; i < 3; ++i) {
        p[i] = args.ReadVector();
        n[i] = args.ReadVector();
        const double u = args.ReadNumber();
        uv[i] = {u, args.ReadNumber()};
    }
    if (!CheckPhong(args, p, n)) return nullptr;
    return std::make_shared<Triangle>(p, n, uv, args.FlipNormals());
}

const IntersectionCounters& Triangle::Counters() const {
    static const IntersectionCounters counters("Triangle");
    return counters;
}

Bounds3 Triangle::Bounds() const {
    Bounds3 b(p1_, p2_);
    b.Extend(p3_);
    return b;
}

bool Triangle::Intersect(const Ray& ray, double tMin, double tMax, PrimitiveHit& hit) const {
    // Plane first (parallel rays give ±inf or NaN, rejected by the range test), then the
    // barycentrics of the plane point; all three must lie in [0, 1].
    const double t = Dot(normal_, p1_ - ray.origin) / Dot(normal_, ray.dir);
    if (!(t > tMin && t < tMax)) return false;
    const Vec3 x = ray.origin + ray.dir * t - p1_;
    const double b2 = Dot(x, dual2_);
    if (b2 < 0 || b2 > 1) return false;
    const double b3 = Dot(x, dual3_);
    if (b3 < 0 || b2 + b3 > 1) return false;
    hit.t = t;
    hit.a = 1 - b2 - b3;
    hit.b = b2;
    hit.c = b3;
    return true;
}

SurfaceNormals Triangle::Normal(const Vec3&, const PrimitiveHit& hit) const {
    if (!shading_) return {normal_, normal_, false};
    const Points& n = shading_->normals;
    const Vec3 shading = Normalize(n[0] * hit.a + n[1] * hit.b + n[2] * hit.c);
    return {shading, normal_, true};
}

SurfaceUV Triangle::UV(const Vec3& p, const Vec3&, const PrimitiveHit& hit) const {
    SurfaceUV out;
    if (shading_ && shading_->hasUV) {
        const UVs& uv = shading_->uv;
        out.uv = {hit.a * uv[0].u + hit.b * uv[1].u + hit.c * uv[2].u,
                  hit.a * uv[0].v + hit.b * uv[1].v + hit.c * uv[2].v};
        out.dpdu = shading_->dpdu;
        out.dpdv = shading_->dpdv;
        return out;
    }
    const double v = hit.c;
    const double u = std::fabs(v - 1) < kEpsilon ? 0.0 : hit.b / (hit.a + hit.b);
    out.uv = {u, v};
    out.dpdu = Normalize(p2_ - p1_);
    const Vec3 toFirst = Normalize(p1_ - p);
    if (LengthSquared(toFirst) > 0) out.dpdv = toFirst;
    return out;
}

}  // namespace rs
