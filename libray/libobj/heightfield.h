// `heightfield file`: a height field over the unit square (spec §3.9, §3.14).
//
// For an N×N grid, vertex (i, j) is (j/(N−1), i/(N−1), h[i][j]). Cell (x, y) holds two
// triangles split along the diagonal from (x+1, y) to (x, y+1); triangles touching a
// height ≤ −1000 are absent. Rays walk the cells they cross in the xy projection, front to
// back (2-D DDA), skipping a cell when the ray's height range over it misses the cell's
// [min, max] height, so the first triangle hit is the nearest.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "libcommon/arg_reader.h"
#include "libobj/primitive.h"

namespace rs {

class HeightField final : public Primitive {
  public:
    // `heights` holds n·n values, row i (y) after row i−1. Requires n ≥ 2.
    HeightField(int n, std::vector<float> heights);

    // Reads `heightfield FILE`; Fails with a located message for unreadable or malformed
    // files.
    static std::shared_ptr<Primitive> Create(ArgReader& args);

    const IntersectionCounters& Counters() const override;
    Bounds3 Bounds() const override { return bounds_; }
    bool Intersect(const Ray& ray, double tMin, double tMax, PrimitiveHit& hit) const override;
    SurfaceNormals Normal(const Vec3& p, const PrimitiveHit& hit) const override;
    SurfaceUV UV(const Vec3& p, const Vec3& facingNormal, const PrimitiveHit& hit) const override;

  private:
    // Heights at or below this mark missing points (spec §3.14).
    static constexpr float kMissing = -1000.0f;

    Vec3 Vertex(int x, int y) const {
        return {x * cellSize_, y * cellSize_, heights_[static_cast<size_t>(y) * n_ + x]};
    }
    // Nearest hit with the triangles of cell (x, y) inside (tMin, tMax).
    bool IntersectCell(const Ray& ray, int x, int y, double tMin, double tMax,
                       PrimitiveHit& hit) const;

    int n_;
    double cellSize_;
    std::vector<float> heights_;
    std::vector<float> cellMin_, cellMax_;  // per cell, over its present vertices
    Bounds3 bounds_;
};

// Reads a height-field file: a 32-bit native-endian integer N ≥ 2, then N·N 32-bit floats.
// Returns false with `error` set when the file is unreadable, short, or N is absurd.
bool ReadHeightFieldFile(const std::string& path, int& n, std::vector<float>& heights,
                         std::string& error);

}  // namespace rs
