#include "libobj/polygon.h"

#include <algorithm>
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
    vertexCount_ = static_cast<uint32_t>(vertices.size());
    double* projected = inlineProjected_;
    if (vertexCount_ > kInlineVertices) {
        heapProjected_ = std::make_unique<double[]>(2 * vertexCount_);
        projected = heapProjected_.get();
    }
    for (size_t i = 0; i < vertexCount_; ++i) {
        projected[2 * i] = vertices[i][axisU_];
        projected[2 * i + 1] = vertices[i][axisV_];
    }
    projected_ = projected;
    if (vertexCount_ > kBandedEdges) BuildBands();
}

int Polygon::Bands::Of(double v) const {
    // Non-decreasing in v: the subtraction and the multiplication by a positive constant
    // are rounded monotonically, floor and the clamp keep the order.
    const double f = std::floor((v - lo) * scale);
    if (!(f > 0)) return 0;
    return f >= count - 1 ? count - 1 : static_cast<int>(f);
}

void Polygon::BuildBands() {
    const size_t count = vertexCount_;
    auto bands = std::make_unique<Bands>();
    bands->lo = bands->hi = projected_[1];
    for (size_t i = 0; i < count; ++i) {
        bands->lo = std::min(bands->lo, projected_[2 * i + 1]);
        bands->hi = std::max(bands->hi, projected_[2 * i + 1]);
    }
    // About four edges per band; a flat range (no edge can be crossed) keeps one band.
    const bool flat = !(bands->hi > bands->lo);
    bands->count = flat ? 1 : static_cast<int>(count / 4);
    bands->scale = flat ? 0 : bands->count / (bands->hi - bands->lo);
    const auto edgeBands = [&](size_t e, int& first, int& last) {
        const double v0 = projected_[2 * ((e + count - 1) % count) + 1], v1 = projected_[2 * e + 1];
        first = bands->Of(std::min(v0, v1));
        last = bands->Of(std::max(v0, v1));
    };
    // Two passes: count the entries of each band, then fill them in.
    std::vector<uint32_t>& start = bands->start;
    start.assign(bands->count + 1, 0);
    for (size_t e = 0; e < count; ++e) {
        int first, last;
        edgeBands(e, first, last);
        for (int b = first; b <= last; ++b) ++start[b + 1];
    }
    for (int b = 0; b < bands->count; ++b) start[b + 1] += start[b];
    bands->edges.resize(start[bands->count]);
    std::vector<uint32_t> cursor(start.begin(), start.end() - 1);
    for (size_t e = 0; e < count; ++e) {
        int first, last;
        edgeBands(e, first, last);
        for (int b = first; b <= last; ++b) bands->edges[cursor[b]++] = static_cast<uint32_t>(e);
    }
    bands_ = std::move(bands);
}

inline int Polygon::Crossing(size_t e, double pu, double pv) const {
    // Upward crossings of the horizontal line through the point that pass to its right
    // count +1, downward ones passing to its left −1.
    const size_t count = vertexCount_;
    const size_t j = e == 0 ? count - 1 : e - 1;
    const double u0 = projected_[2 * j], v0 = projected_[2 * j + 1];
    const double u1 = projected_[2 * e], v1 = projected_[2 * e + 1];
    const double side = (u1 - u0) * (pv - v0) - (pu - u0) * (v1 - v0);
    if (v0 <= pv) return v1 > pv && side > 0 ? 1 : 0;
    return v1 <= pv && side < 0 ? -1 : 0;
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
    // Winding number of the projected outline around (pu, pv); non-zero means inside. With
    // bands, only the edges of the point's band can cross (none outside the v range).
    int winding = 0;
    if (!bands_) {
        for (size_t e = 0; e < vertexCount_; ++e) winding += Crossing(e, pu, pv);
    } else {
        const Bands& bands = *bands_;
        if (!(pv >= bands.lo && pv < bands.hi)) return false;
        const int b = bands.Of(pv);
        for (uint32_t k = bands.start[b]; k < bands.start[b + 1]; ++k) winding += Crossing(bands.edges[k], pu, pv);
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
