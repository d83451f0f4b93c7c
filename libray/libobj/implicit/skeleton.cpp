#include "libobj/implicit/skeleton.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rs {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

template <class... Fs>
struct Overloaded : Fs... {
    using Fs::operator()...;
};
template <class... Fs>
Overloaded(Fs...) -> Overloaded<Fs...>;

Vec3 ClosestOnSegment(const Vec3& a, const Vec3& b, const Vec3& p) {
    Vec3 ab = b - a;
    double len2 = LengthSquared(ab);
    if (len2 == 0) return a;
    double t = std::clamp(Dot(p - a, ab) / len2, 0.0, 1.0);
    return a + ab * t;
}

// Closest point of the filled triangle abc to p, by Voronoi regions of the vertices, edges
// and face (Ericson, Real-Time Collision Detection, §5.1.5). Degenerate (zero-area)
// triangles fall back to the nearest of the three edges.
Vec3 ClosestOnTriangle(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& p) {
    Vec3 ab = b - a, ac = c - a;
    if (LengthSquared(Cross(ab, ac)) == 0) {
        Vec3 q[3] = {ClosestOnSegment(a, b, p), ClosestOnSegment(b, c, p),
                     ClosestOnSegment(c, a, p)};
        Vec3 best = q[0];
        for (const Vec3& x : q) {
            if (LengthSquared(p - x) < LengthSquared(p - best)) best = x;
        }
        return best;
    }
    Vec3 ap = p - a;
    double d1 = Dot(ab, ap), d2 = Dot(ac, ap);
    if (d1 <= 0 && d2 <= 0) return a;
    Vec3 bp = p - b;
    double d3 = Dot(ab, bp), d4 = Dot(ac, bp);
    if (d3 >= 0 && d4 <= d3) return b;
    double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + ab * (d1 / (d1 - d3));
    Vec3 cp = p - c;
    double d5 = Dot(ab, cp), d6 = Dot(ac, cp);
    if (d6 >= 0 && d5 <= d6) return c;
    double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + ac * (d2 / (d2 - d6));
    double va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
        return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
    }
    double denom = 1.0 / (va + vb + vc);
    return a + ab * (vb * denom) + ac * (vc * denom);
}

Vec3 ClosestOnCircle(const CircleSkeleton& s, const Vec3& p) {
    Vec3 v = p - s.center;
    Vec3 q = v - s.normal * Dot(v, s.normal);
    double rho = Length(q);
    if (rho == 0) {  // on the axis: every circle point is closest; pick a fixed one
        Vec3 u, w;
        CoordinateSystem(s.normal, u, w);
        return s.center + u * s.radius;
    }
    return s.center + q * (s.radius / rho);
}

Vec3 ClosestOnCylinder(const CylinderSkeleton& s, const Vec3& p) {
    Vec3 axis = s.b - s.a;
    double len = Length(axis);
    if (len == 0) return s.a;
    Vec3 u = axis / len;
    Vec3 v = p - s.a;
    double h = std::clamp(Dot(v, u), 0.0, len);
    Vec3 q = v - u * Dot(v, u);
    double rho = Length(q);
    Vec3 radial = rho > s.radius ? q * (s.radius / rho) : q;
    return s.a + u * h + radial;
}

Vec3 ClosestPoint(const Skeleton& skeleton, const Vec3& p) {
    return std::visit(
        Overloaded{
            [&](const PointSkeleton& s) { return s.center; },
            [&](const SegmentSkeleton& s) { return ClosestOnSegment(s.a, s.b, p); },
            [&](const PolylineSkeleton& s) {
                Vec3 best = s.points.front();
                double bestD2 = kInf;
                for (size_t i = 0; i + 1 < s.points.size(); ++i) {
                    Vec3 q = ClosestOnSegment(s.points[i], s.points[i + 1], p);
                    double d2 = LengthSquared(p - q);
                    if (d2 < bestD2) {
                        bestD2 = d2;
                        best = q;
                    }
                }
                return best;
            },
            [&](const CircleSkeleton& s) { return ClosestOnCircle(s, p); },
            [&](const TriangleSkeleton& s) { return ClosestOnTriangle(s.a, s.b, s.c, p); },
            [&](const BoxSkeleton& s) {
                return Vec3{std::clamp(p.x, s.lo.x, s.hi.x), std::clamp(p.y, s.lo.y, s.hi.y),
                            std::clamp(p.z, s.lo.z, s.hi.z)};
            },
            [&](const CylinderSkeleton& s) { return ClosestOnCylinder(s, p); },
        },
        skeleton);
}

// Box of a disc of radius r around c with unit normal n: along axis i the disc extends
// r·sqrt(1 − n_i²) (the length of the projection of the disc's plane onto that axis).
Bounds3 DiscBounds(const Vec3& c, const Vec3& n, double r) {
    Vec3 ext{r * std::sqrt(std::max(0.0, 1 - n.x * n.x)),
             r * std::sqrt(std::max(0.0, 1 - n.y * n.y)),
             r * std::sqrt(std::max(0.0, 1 - n.z * n.z))};
    return Bounds3(c - ext, c + ext);
}

bool IsConvexKind(const Skeleton& skeleton) {
    return !std::holds_alternative<PolylineSkeleton>(skeleton) &&
           !std::holds_alternative<CircleSkeleton>(skeleton);
}

double MaxCornerDistance(const Skeleton& skeleton, const Bounds3& box) {
    double m = 0;
    for (int i = 0; i < 8; ++i) m = std::max(m, SkeletonDistance(skeleton, box.Corner(i)));
    return m;
}

}  // namespace

const char* SkeletonKindName(const Skeleton& skeleton) {
    static const char* const kNames[] = {"point",    "segment", "polyline", "circle",
                                         "triangle", "box",     "cylinder"};
    return kNames[skeleton.index()];
}

double SkeletonDistance(const Skeleton& skeleton, const Vec3& p, Vec3& closest) {
    closest = ClosestPoint(skeleton, p);
    return Length(p - closest);
}

double SkeletonDistance(const Skeleton& skeleton, const Vec3& p) {
    Vec3 closest;
    return SkeletonDistance(skeleton, p, closest);
}

Bounds3 SkeletonBounds(const Skeleton& skeleton) {
    return std::visit(
        Overloaded{
            [](const PointSkeleton& s) { return Bounds3(s.center, s.center); },
            [](const SegmentSkeleton& s) { return Bounds3(s.a, s.b); },
            [](const PolylineSkeleton& s) {
                Bounds3 b;
                for (const Vec3& p : s.points) b.Extend(p);
                return b;
            },
            [](const CircleSkeleton& s) { return DiscBounds(s.center, s.normal, s.radius); },
            [](const TriangleSkeleton& s) {
                Bounds3 b(s.a, s.b);
                b.Extend(s.c);
                return b;
            },
            [](const BoxSkeleton& s) { return Bounds3(s.lo, s.hi); },
            [](const CylinderSkeleton& s) {
                Vec3 axis = s.b - s.a;
                double len = Length(axis);
                if (len == 0) return Bounds3(s.a, s.a);
                Vec3 u = axis / len;
                return Union(DiscBounds(s.a, u, s.radius), DiscBounds(s.b, u, s.radius));
            },
        },
        skeleton);
}

double PointBoxDistance(const Vec3& p, const Bounds3& box) {
    Vec3 q{std::clamp(p.x, box.lo.x, box.hi.x), std::clamp(p.y, box.lo.y, box.hi.y),
           std::clamp(p.z, box.lo.z, box.hi.z)};
    return Length(p - q);
}

double BoxBoxDistance(const Bounds3& a, const Bounds3& b) {
    double d2 = 0;
    for (int i = 0; i < 3; ++i) {
        double gap = std::max({0.0, a.lo[i] - b.hi[i], b.lo[i] - a.hi[i]});
        d2 += gap * gap;
    }
    return std::sqrt(d2);
}

DistanceRange SkeletonDistanceRange(const Skeleton& skeleton, const Bounds3& box) {
    DistanceRange r;
    if (const auto* pt = std::get_if<PointSkeleton>(&skeleton)) {
        // Exact: the nearest point of the box, and the farthest corner, which takes the
        // farther face on each axis (the same sums as the largest of the eight corner
        // distances, computed once).
        r.min = PointBoxDistance(pt->center, box);
        const Vec3& p = pt->center;
        Vec3 far{std::max(std::abs(p.x - box.lo.x), std::abs(p.x - box.hi.x)),
                 std::max(std::abs(p.y - box.lo.y), std::abs(p.y - box.hi.y)),
                 std::max(std::abs(p.z - box.lo.z), std::abs(p.z - box.hi.z))};
        r.max = std::max(Length(far), r.min);
        return r;
    }
    Vec3 c = box.Center();
    double b = HalfDiagonal(box);
    double dc = SkeletonDistance(skeleton, c);
    r.min = std::max({0.0, dc - b, BoxBoxDistance(box, SkeletonBounds(skeleton))});
    if (IsConvexKind(skeleton)) {
        r.max = MaxCornerDistance(skeleton, box);
    } else if (const auto* poly = std::get_if<PolylineSkeleton>(&skeleton)) {
        r.max = dc + b;
        for (size_t i = 0; i + 1 < poly->points.size(); ++i) {
            r.max = std::min(r.max, MaxCornerDistance(
                                        SegmentSkeleton{poly->points[i], poly->points[i + 1]},
                                        box));
        }
    } else {
        r.max = dc + b;
    }
    r.max = std::max(r.max, r.min);
    return r;
}

bool SkeletonIsConvex(const Skeleton& skeleton) { return IsConvexKind(skeleton); }

double ExtraDistanceCurvature(const Skeleton& skeleton, const Bounds3& box) {
    if (const auto* circle = std::get_if<CircleSkeleton>(&skeleton)) {
        Vec3 v = box.Center() - circle->center;
        double rhoCentre = Length(v - circle->normal * Dot(v, circle->normal));
        double rhoMin = rhoCentre - HalfDiagonal(box);
        return rhoMin > 0 ? 1.0 / rhoMin : kInf;
    }
    if (const auto* poly = std::get_if<PolylineSkeleton>(&skeleton)) {
        // The segments that may be the nearest somewhere in the box are those whose minimum
        // distance does not exceed the smallest per-segment maximum.
        std::vector<DistanceRange> ranges;
        double bestMax = kInf;
        for (size_t i = 0; i + 1 < poly->points.size(); ++i) {
            ranges.push_back(SkeletonDistanceRange(
                SegmentSkeleton{poly->points[i], poly->points[i + 1]}, box));
            bestMax = std::min(bestMax, ranges.back().max);
        }
        int candidates = 0;
        for (const DistanceRange& sr : ranges) candidates += sr.min <= bestMax ? 1 : 0;
        return candidates > 1 ? kInf : 0.0;
    }
    return 0;
}

}  // namespace rs
