// `poly p1 … pk` / `polygon` (spec §3.9): a planar polygon with k ≥ 3 vertices in order,
// any (non-convex, self-intersecting) shape, filled by the non-zero winding rule. Open.
// Normal by Newell's method, negated by `-f`. uv = (X_x, X_y) with ∂P/∂u = x̂, ∂P/∂v = ŷ.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "libcommon/arg_reader.h"
#include "libobj/primitive.h"

namespace rs {

class Polygon final : public Primitive {
  public:
    // Requires ≥ 3 vertices and a non-zero Newell normal (NewellNormal).
    Polygon(const std::vector<Vec3>& vertices, bool flip);
    Polygon(const Polygon&) = delete;  // projected_ may point into the object itself
    Polygon& operator=(const Polygon&) = delete;
    // Reads vectors while a number follows. Fewer than 3: args.Fail; a zero Newell normal
    // (no area): warning, nullptr.
    static std::shared_ptr<Primitive> Create(ArgReader& args);

    // Σ over the cyclic edges (v_{i−1}, v_i) of (y_{i−1} − y_i)(z_{i−1} + z_i), etc.: twice
    // the signed vector area; not normalised.
    static Vec3 NewellNormal(const std::vector<Vec3>& vertices);

    const IntersectionCounters& Counters() const override;
    Bounds3 Bounds() const override { return bounds_; }
    bool Intersect(const Ray& ray, double tMin, double tMax, PrimitiveHit& hit) const override;
    SurfaceNormals Normal(const Vec3& p, const PrimitiveHit& hit) const override;
    SurfaceUV UV(const Vec3& p, const Vec3& facingNormal, const PrimitiveHit& hit) const override;

  private:
    Vec3 normal_;
    double offset_;  // normal·(vertex centroid)
    // The vertices projected by dropping the normal's dominant axis: coordinates axisU_,
    // axisV_ of vertex i at projected_[2i], projected_[2i + 1], used for the winding-number
    // test (the vertices themselves are not kept). Outlines of up to kInlineVertices
    // vertices (triangles and quadrilaterals: most polygons of large scenes) are kept in
    // the object, longer ones on the heap, so most polygons cost one allocation.
    static constexpr size_t kInlineVertices = 4;
    uint8_t axisU_, axisV_;
    uint32_t vertexCount_;     // a polygon of 2^32 vertices would not fit in memory
    const double* projected_;  // inlineProjected_ or heapProjected_
    double inlineProjected_[2 * kInlineVertices];
    std::unique_ptr<double[]> heapProjected_;
    Bounds3 bounds_;

    // Outlines of more than kBandedEdges edges (gear faces: 144) are cut into horizontal
    // bands of the projected v range, each listing the edges whose v range overlaps it, so
    // a point's winding number adds only the edges of its band. An edge can cross the
    // line v = pv only if min(v0, v1) <= pv < max(v0, v1); Of() is non-decreasing in v,
    // so such an edge is listed in band Of(pv). Held apart (null for small outlines):
    // most polygons of a large mesh are triangles, and their size is setup time.
    static constexpr size_t kBandedEdges = 12;
    struct Bands {
        double lo = 0, hi = 0, scale = 0;  // v range; bands per unit of v
        int count = 0;
        // Band b lists edges[k] for start[b] <= k < start[b + 1].
        std::vector<uint32_t> start, edges;
        int Of(double v) const;
    };
    // Edge e runs from vertex e - 1 (cyclically) to vertex e; +1, -1 or 0 to the winding
    // number of the projected outline around (pu, pv).
    int Crossing(size_t e, double pu, double pv) const;
    void BuildBands();
    std::unique_ptr<const Bands> bands_;
};

}  // namespace rs
