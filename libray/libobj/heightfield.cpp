#include "libobj/heightfield.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>

#include "libcommon/constants.h"

namespace rs {

namespace {

// Largest accepted grid side: 16384² floats is 1 GiB, beyond any sensible terrain here.
constexpr int32_t kMaxSide = 16384;

// Möller–Trumbore on triangle (a, b, c); t in (tMin, tMax). Returns barycentrics (u, v) of
// b and c.
bool HitTriangle(const Ray& ray, const Vec3& a, const Vec3& b, const Vec3& c, double tMin,
                 double tMax, double& t) {
    Vec3 e1 = b - a, e2 = c - a;
    Vec3 pv = Cross(ray.dir, e2);
    double det = Dot(e1, pv);
    if (det == 0) return false;
    double inv = 1 / det;
    Vec3 tv = ray.origin - a;
    double u = Dot(tv, pv) * inv;
    if (u < 0 || u > 1) return false;
    Vec3 qv = Cross(tv, e1);
    double v = Dot(ray.dir, qv) * inv;
    if (v < 0 || u + v > 1) return false;
    double tt = Dot(e2, qv) * inv;
    if (!(tt > tMin && tt < tMax)) return false;
    t = tt;
    return true;
}

}  // namespace

bool ReadHeightFieldFile(const std::string& path, int& n, std::vector<float>& heights,
                         std::string& error) {
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        error = "cannot open height field '" + path + "': " + std::strerror(errno);
        return false;
    }
    int32_t side = 0;
    if (!in.read(reinterpret_cast<char*>(&side), sizeof side)) {
        error = "height field '" + path + "' is too short to hold its size";
        return false;
    }
    if (side < 2 || side > kMaxSide) {
        error = "height field '" + path + "' has an invalid size " + std::to_string(side) +
                " (must be 2.." + std::to_string(kMaxSide) + ")";
        return false;
    }
    heights.resize(static_cast<size_t>(side) * side);
    if (!in.read(reinterpret_cast<char*>(heights.data()),
                 static_cast<std::streamsize>(heights.size() * sizeof(float)))) {
        error = "height field '" + path + "' is truncated (expected " + std::to_string(side) + "x" +
                std::to_string(side) + " heights)";
        return false;
    }
    for (float h : heights) {
        if (!std::isfinite(h)) {
            error = "height field '" + path + "' contains a non-finite height";
            return false;
        }
    }
    n = side;
    return true;
}

HeightField::HeightField(int n, std::vector<float> heights)
    : n_(n), cellSize_(1.0 / (n - 1)), heights_(std::move(heights)) {
    const int cells = n_ - 1;
    cellMin_.assign(static_cast<size_t>(cells) * cells, 0);
    cellMax_.assign(static_cast<size_t>(cells) * cells, 0);
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (int y = 0; y < cells; ++y) {
        for (int x = 0; x < cells; ++x) {
            float mn = std::numeric_limits<float>::infinity(), mx = -mn;
            for (int k = 0; k < 4; ++k) {
                float h = heights_[static_cast<size_t>(y + k / 2) * n_ + x + k % 2];
                if (h <= kMissing) continue;
                mn = std::min(mn, h);
                mx = std::max(mx, h);
            }
            cellMin_[y * cells + x] = mn;
            cellMax_[y * cells + x] = mx;
            if (mn <= mx) {
                lo = std::min<double>(lo, mn);
                hi = std::max<double>(hi, mx);
            }
        }
    }
    if (lo > hi) lo = hi = 0;  // every point missing: an empty but valid box
    bounds_ = Bounds3({0, 0, lo}, {1, 1, hi});
}

std::shared_ptr<Primitive> HeightField::Create(ArgReader& args) {
    std::string path = args.ReadDataFilename();
    int n = 0;
    std::vector<float> heights;
    std::string error;
    if (!ReadHeightFieldFile(path, n, heights, error)) args.Fail(error);
    return std::make_shared<HeightField>(n, std::move(heights));
}

const IntersectionCounters& HeightField::Counters() const {
    static const IntersectionCounters counters("Heightfield");
    return counters;
}

bool HeightField::IntersectCell(const Ray& ray, int x, int y, double tMin, double tMax,
                                PrimitiveHit& hit) const {
    auto present = [&](int i, int j) { return heights_[static_cast<size_t>(j) * n_ + i] > kMissing; };
    bool found = false;
    double t = 0;
    // T1 = (x,y),(x+1,y),(x,y+1); T2 = (x+1,y),(x+1,y+1),(x,y+1).
    if (present(x, y) && present(x + 1, y) && present(x, y + 1) &&
        HitTriangle(ray, Vertex(x, y), Vertex(x + 1, y), Vertex(x, y + 1), tMin, tMax, t)) {
        tMax = t;
        hit.t = t;
        hit.part = 2 * (y * (n_ - 1) + x);
        found = true;
    }
    if (present(x + 1, y) && present(x + 1, y + 1) && present(x, y + 1) &&
        HitTriangle(ray, Vertex(x + 1, y), Vertex(x + 1, y + 1), Vertex(x, y + 1), tMin, tMax, t)) {
        hit.t = t;
        hit.part = 2 * (y * (n_ - 1) + x) + 1;
        found = true;
    }
    return found;
}

bool HeightField::Intersect(const Ray& ray, double tMin, double tMax, PrimitiveHit& hit) const {
    // Hits nearer than ε are ignored (spec §3.9).
    tMin = std::max(tMin, kEpsilon);
    double t0 = tMin, t1 = tMax;
    if (!bounds_.Padded(kEpsilon).ClipRay(ray, t0, t1)) return false;

    const int cells = n_ - 1;
    Vec3 p = ray.At(t0);
    int cx = std::clamp(static_cast<int>(p.x / cellSize_), 0, cells - 1);
    int cy = std::clamp(static_cast<int>(p.y / cellSize_), 0, cells - 1);
    const int stepX = ray.dir.x > 0 ? 1 : -1, stepY = ray.dir.y > 0 ? 1 : -1;
    const double inf = std::numeric_limits<double>::infinity();
    // Ray parameter at which the walk crosses the next cell boundary in x and in y.
    auto nextCrossing = [&](double origin, double dir, int cell, int step) {
        if (dir == 0) return inf;
        double boundary = (cell + (step > 0 ? 1 : 0)) * cellSize_;
        return (boundary - origin) / dir;
    };
    double nextX = nextCrossing(ray.origin.x, ray.dir.x, cx, stepX);
    double nextY = nextCrossing(ray.origin.y, ray.dir.y, cy, stepY);
    const double deltaX = ray.dir.x != 0 ? cellSize_ / std::fabs(ray.dir.x) : inf;
    const double deltaY = ray.dir.y != 0 ? cellSize_ / std::fabs(ray.dir.y) : inf;

    double cellEnter = t0;
    for (;;) {
        double cellExit = std::min({nextX, nextY, t1});
        // Skip cells whose height range the ray's z range over the cell misses.
        float mn = cellMin_[cy * cells + cx], mx = cellMax_[cy * cells + cx];
        if (mn <= mx) {
            double z0 = ray.origin.z + ray.dir.z * cellEnter, z1 = ray.origin.z + ray.dir.z * cellExit;
            if (std::max(z0, z1) >= mn - kEpsilon && std::min(z0, z1) <= mx + kEpsilon &&
                IntersectCell(ray, cx, cy, tMin, tMax, hit))
                return true;  // cells are visited front to back: the first hit is the nearest
        }
        if (cellExit >= t1) return false;
        if (nextX < nextY) {
            cx += stepX;
            cellEnter = nextX;
            nextX += deltaX;
        } else {
            cy += stepY;
            cellEnter = nextY;
            nextY += deltaY;
        }
        if (cx < 0 || cy < 0 || cx >= cells || cy >= cells) return false;
    }
}

SurfaceNormals HeightField::Normal(const Vec3&, const PrimitiveHit& hit) const {
    int cell = hit.part / 2, x = cell % (n_ - 1), y = cell / (n_ - 1);
    Vec3 a, b, c;
    if (hit.part % 2 == 0) {
        a = Vertex(x, y);
        b = Vertex(x + 1, y);
        c = Vertex(x, y + 1);
    } else {
        a = Vertex(x + 1, y);
        b = Vertex(x + 1, y + 1);
        c = Vertex(x, y + 1);
    }
    Vec3 n = Normalize(Cross(b - a, c - a));
    return {n, n, false};
}

SurfaceUV HeightField::UV(const Vec3& p, const Vec3&, const PrimitiveHit&) const {
    SurfaceUV uv;
    uv.uv = {p.x, p.y};
    return uv;
}

}  // namespace rs
