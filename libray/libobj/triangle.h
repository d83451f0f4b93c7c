// `triangle p1 p2 p3`, `triangle p1 n1 p2 n2 p3 n3` and `triangleuv p1 n1 uv1 p2 n2 uv2
// p3 n3 uv3` (spec §3.9). Open; hit from both sides.
//
// Geometric normal N = normalize((p2 − p1) × (p3 − p2)): counter-clockwise vertices face
// the viewer. `-f` (flip) negates N and the vertex normals. With vertex normals (the Phong
// forms), when not flipping and n1·N < 0, N is reversed to agree with the vertex normals.
// The hit payload holds the barycentrics: PrimitiveHit a, b, c = b1, b2, b3 (the weights
// of vertices 1, 2, 3), so nothing per-hit is stored in the shared triangle.
#pragma once

#include <array>
#include <memory>

#include "libcommon/arg_reader.h"
#include "libobj/primitive.h"

namespace rs {

class Triangle final : public Primitive {
  public:
    using Points = std::array<Vec3, 3>;
    using UVs = std::array<Vec2, 3>;

    // Flat triangle. Requires non-zero area (IsDegenerate false).
    Triangle(const Points& p, bool flip);
    // Phong triangle. Requires non-zero area and non-zero vertex normals (normalised here).
    Triangle(const Points& p, const Points& normals, bool flip);
    // Phong triangle with per-vertex texture coordinates (`triangleuv`).
    Triangle(const Points& p, const Points& normals, const UVs& uv, bool flip);

    // `triangle`: 3 vectors, or 6 (p n p n p n) when a 4th vector follows. Zero area:
    // advisory, nullptr; a zero vertex normal: warning, nullptr; inconsistent vertex
    // normals (see above): advisory, the triangle is kept with N reversed.
    static std::shared_ptr<Primitive> Create(ArgReader& args);
    // `triangleuv`: (p n u v) × 3, with the same checks as the Phong form.
    static std::shared_ptr<Primitive> CreateUV(ArgReader& args);

    // True when the vertices span no area ((p2 − p1) × (p3 − p2) = 0).
    static bool IsDegenerate(const Points& p);

    const IntersectionCounters& Counters() const override;
    Bounds3 Bounds() const override;
    bool Intersect(const Ray& ray, double tMin, double tMax, PrimitiveHit& hit) const override;
    // Flat: N both. Phong: shading normalize(Σ b_i·n_i), geometric N, smooth.
    SurfaceNormals Normal(const Vec3& p, const PrimitiveHit& hit) const override;
    // Without uv: v = b3, u = b2/(b1 + b2) (u = 0 when v is within ε of 1); ∂P/∂u along
    // p1→p2, ∂P/∂v along X→p1. With uv: Σ b_i·uv_i, and ∂P/∂u, ∂P/∂v from the uv layout
    // (the object-space directions in which u, resp. v, grow with the other fixed).
    SurfaceUV UV(const Vec3& p, const Vec3& facingNormal, const PrimitiveHit& hit) const override;

  private:
    // The Phong forms; uv is null for `triangle p n p n p n`.
    Triangle(const Points& p, const Points& normals, const UVs* uv, bool flip);

    // Vertex normals and texture coordinates of the Phong forms, kept apart so flat
    // triangles stay small and the data Intersect reads stays together.
    struct Shading {
        Points normals;  // unit, already flipped
        bool hasUV = false;
        UVs uv;
        Vec3 dpdu, dpdv;
    };

    // Intersection data first: p1, N and the dual basis of the edges e2 = p2 − p1,
    // e3 = p3 − p1 in the plane (for X in the plane, b2 = (X − p1)·dual2_ and
    // b3 = (X − p1)·dual3_).
    Vec3 p1_, normal_, dual2_, dual3_;
    Vec3 p2_, p3_;
    std::unique_ptr<const Shading> shading_;  // null for flat triangles
};

}  // namespace rs
