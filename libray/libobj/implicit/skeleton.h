// Layer 2 of the implicit module: skeleton elements and their distance functions.
//
// A skeleton is one of a closed set of kinds held in a std::variant (static dispatch; no
// virtual call per field evaluation). For every kind this layer provides
//   - the exact Euclidean distance from a point to the skeleton, with the closest point
//     (so (p − closest)/r is the unit gradient of the distance when r > 0);
//   - an axis-aligned box containing the skeleton;
//   - a conservative range [min, max] of the distance from the skeleton to the points of
//     an axis-aligned box (every true distance lies inside it);
//   - what the field layer needs for its second-derivative bound G: whether the kind is
//     convex, and for the others a bound on the extra curvature of the distance function
//     over a box (SkeletonIsConvex, ExtraDistanceCurvature).
// Solid kinds (box, cylinder) have distance 0 inside. Everything is in one (object) space.
#pragma once

#include <variant>
#include <vector>

#include "libcommon/bounds.h"

namespace rs {

struct PointSkeleton {
    Vec3 center;
};

struct SegmentSkeleton {
    Vec3 a, b;
};

// An open chain of segments through `points` (at least two points).
struct PolylineSkeleton {
    std::vector<Vec3> points;
};

// The circle (a curve, not a disc) of radius `radius` around `center` in the plane with
// unit normal `normal`.
struct CircleSkeleton {
    Vec3 center;
    Vec3 normal;
    double radius = 0;
};

// The filled triangle abc.
struct TriangleSkeleton {
    Vec3 a, b, c;
};

// The solid axis-aligned box [lo, hi].
struct BoxSkeleton {
    Vec3 lo, hi;
};

// The solid cylinder of radius `radius` around the segment ab, with flat caps.
struct CylinderSkeleton {
    Vec3 a, b;
    double radius = 0;
};

using Skeleton = std::variant<PointSkeleton, SegmentSkeleton, PolylineSkeleton, CircleSkeleton,
                              TriangleSkeleton, BoxSkeleton, CylinderSkeleton>;

// The keyword of the kind ("point", "segment", ...), for messages.
const char* SkeletonKindName(const Skeleton& skeleton);

// Exact distance from `p` to the skeleton; `closest` receives a closest skeleton point.
double SkeletonDistance(const Skeleton& skeleton, const Vec3& p, Vec3& closest);
double SkeletonDistance(const Skeleton& skeleton, const Vec3& p);

// The smallest axis-aligned box containing the skeleton (circle and cylinder boxes use the
// exact extent r·sqrt(1 − n_i²) of a disc of radius r with unit normal n along axis i).
Bounds3 SkeletonBounds(const Skeleton& skeleton);

struct DistanceRange {
    double min = 0, max = 0;
};

// [min, max] with min <= d(p) <= max for every p in `box` (conservative, never exact-only).
// Derivation: d is 1-Lipschitz, so d(C) ± b (C the box centre, b its half diagonal) bound
// it; the distance between the box and the skeleton's bounding box is also a lower bound.
// For convex kinds (point, segment, triangle, solid box, solid cylinder) d is convex, so
// its maximum over the box is at a corner and is computed exactly. For the polyline, the
// minimum over segments of their corner maxima is an upper bound.
DistanceRange SkeletonDistanceRange(const Skeleton& skeleton, const Bounds3& box);

// True for the kinds whose point set is convex (point, segment, triangle, solid box, solid
// cylinder). The distance to a convex set is convex and C¹ off the set, and its Hessian is
// positive semi-definite with ∇²d ∇d = 0 and eigenvalues in [0, 1/d].
bool SkeletonIsConvex(const Skeleton& skeleton);

// For the non-convex kinds, a bound X on the |eigenvalues| of ∇²d over `box` beyond the
// convex bound 1/d: every eigenvalue satisfies |λ| <= max(1/d, X). 0 for convex kinds.
//   - Circle: the azimuthal eigenvalue is (ρ − R)/(dρ), ρ the distance to the circle's
//     axis; since d >= |ρ − R|, |(ρ − R)/(dρ)| <= 1/ρ, so X = 1/ρmin, infinite when the box
//     may touch the axis, where d has a conical kink.
//   - Polyline: d is the minimum of per-segment distances and has kinks where two segments
//     are equally near; X is infinite when two or more segments may be the nearest in the
//     box, else 0.
double ExtraDistanceCurvature(const Skeleton& skeleton, const Bounds3& box);

// The half diagonal of a box.
inline double HalfDiagonal(const Bounds3& box) { return 0.5 * Length(box.Extent()); }

// Exact Euclidean distance between a point and a box (0 inside).
double PointBoxDistance(const Vec3& p, const Bounds3& box);

// Exact Euclidean distance between two boxes (0 when they overlap).
double BoxBoxDistance(const Bounds3& a, const Bounds3& b);

}  // namespace rs
