// Numerical hygiene at degenerate input (docs/robustness.md): normals at zero-gradient points
// and distances to degenerate skeletons must be finite. Expected values are analytic.
#include <gtest/gtest.h>

#include <cmath>

#include "libobj/blob.h"
#include "libobj/implicit/skeleton.h"

namespace rs {
namespace {

bool IsUnit(const Vec3& v) { return IsFinite(v) && std::fabs(Length(v) - 1) < 1e-12; }

// Two equal metaballs (s = 1, r = 1) at ±a: by symmetry ∇F = 0 at the midpoint, which lies on
// the surface when T = F(0) = 2(1 − a²)². Normal must still be a unit vector.
TEST(FiniteNormals, BlobNormalAtAPinchPointIsAUnitVector) {
    const double a = std::sqrt(1 - 1 / std::sqrt(2.0));  // F(0) = 2(1 − a²)² = 1
    Blob blob(1, {{{-a, 0, 0}, 1, 1}, {{a, 0, 0}, 1, 1}});
    EXPECT_NEAR(blob.Field({0, 0, 0}), 1, 1e-12);
    const SurfaceNormals n = blob.Normal({0, 0, 0}, PrimitiveHit{});
    EXPECT_TRUE(IsUnit(n.shading));
    EXPECT_TRUE(IsUnit(n.geometric));
}

// At a ball's centre the ball's own gradient vanishes (ρ = 0).
TEST(FiniteNormals, BlobNormalAtACentreAndOutsideEveryBallIsAUnitVector) {
    Blob blob(0.5, {{{0, 0, 0}, 1, 1}});
    EXPECT_TRUE(IsUnit(blob.Normal({0, 0, 0}, PrimitiveHit{}).shading));
    EXPECT_TRUE(IsUnit(blob.Normal({5, 0, 0}, PrimitiveHit{}).shading));
}

// Degenerate skeletons behave as the point or segment they collapse to.
TEST(FiniteNormals, DegenerateSkeletonsGiveFiniteDistances) {
    const Vec3 o{0, 0, 0};
    Vec3 closest;
    // Zero-length segment at the origin: |(3, 4, 0)| = 5, closest point the origin.
    EXPECT_NEAR(SkeletonDistance(SegmentSkeleton{o, o}, {3, 4, 0}, closest), 5, 1e-12);
    EXPECT_TRUE(IsFinite(closest));
    EXPECT_NEAR(Length(closest), 0, 1e-12);
    // On the skeleton itself: distance 0.
    EXPECT_NEAR(SkeletonDistance(SegmentSkeleton{o, o}, o), 0, 1e-12);
    // Triangle collapsed to a point, and a collinear one (the segment from x = 0 to 2).
    EXPECT_NEAR(SkeletonDistance(TriangleSkeleton{o, o, o}, {0, 0, 2}), 2, 1e-12);
    EXPECT_NEAR(SkeletonDistance(TriangleSkeleton{o, {1, 0, 0}, {2, 0, 0}}, {1, 1, 0}), 1, 1e-12);
    EXPECT_NEAR(SkeletonDistance(TriangleSkeleton{o, {1, 0, 0}, {2, 0, 0}}, {3, 0, 0}), 1, 1e-12);
    // Box of zero size, cylinder of zero radius and zero length, polyline repeating points.
    EXPECT_NEAR(SkeletonDistance(BoxSkeleton{o, o}, {0, 3, 4}), 5, 1e-12);
    EXPECT_NEAR(SkeletonDistance(CylinderSkeleton{o, o, 0}, {0, 0, 5}), 5, 1e-12);
    EXPECT_NEAR(SkeletonDistance(PolylineSkeleton{{o, o, {0, 0, 1}, {0, 0, 1}}}, {2, 0, 0.5}), 2,
                1e-12);
}

}  // namespace
}  // namespace rs
