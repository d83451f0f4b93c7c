#include "libobj/implicit/skeleton.h"

#include <gtest/gtest.h>

#include <cmath>
#include <type_traits>

#include "test_util.h"

namespace rs {
namespace {

using testing::RandomBox;
using testing::RandomInBox;
using testing::RandomSkeleton;

TEST(Skeleton, PointAndSegmentDistances) {
    EXPECT_DOUBLE_EQ(SkeletonDistance(PointSkeleton{{1, 2, 3}}, {1, 2, 6}), 3);
    SegmentSkeleton s{{0, 0, 0}, {2, 0, 0}};
    EXPECT_DOUBLE_EQ(SkeletonDistance(s, {1, 3, 4}), 5);  // perpendicular foot inside
    EXPECT_DOUBLE_EQ(SkeletonDistance(s, {5, 4, 0}), 5);  // beyond the end (3, 4)
    EXPECT_DOUBLE_EQ(SkeletonDistance(s, {-3, 0, 4}), 5);
}

TEST(Skeleton, PolylineIsNearestSegment) {
    PolylineSkeleton p{{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}}};
    EXPECT_DOUBLE_EQ(SkeletonDistance(p, {2, 0.5, 0}), 1);
    EXPECT_DOUBLE_EQ(SkeletonDistance(p, {0.5, -2, 0}), 2);
}

TEST(Skeleton, CircleDistance) {
    CircleSkeleton c{{0, 0, 0}, {0, 0, 1}, 3};
    EXPECT_DOUBLE_EQ(SkeletonDistance(c, {0, 0, 4}), 5);  // on the axis: sqrt(3² + 4²)
    EXPECT_DOUBLE_EQ(SkeletonDistance(c, {5, 0, 0}), 2);
    EXPECT_NEAR(SkeletonDistance(c, {0, 1, 1}), std::sqrt(5.0), 1e-15);
}

TEST(Skeleton, TriangleDistance) {
    TriangleSkeleton t{{0, 0, 0}, {4, 0, 0}, {0, 4, 0}};
    EXPECT_DOUBLE_EQ(SkeletonDistance(t, {1, 1, 2}), 2);          // above the face
    EXPECT_DOUBLE_EQ(SkeletonDistance(t, {-3, -4, 0}), 5);        // vertex region
    EXPECT_NEAR(SkeletonDistance(t, {3, 3, 0}), std::sqrt(2.0), 1e-15);  // hypotenuse
}

TEST(Skeleton, SolidBoxAndCylinderDistances) {
    BoxSkeleton b{{0, 0, 0}, {1, 1, 1}};
    EXPECT_EQ(SkeletonDistance(b, {0.5, 0.5, 0.5}), 0);
    EXPECT_DOUBLE_EQ(SkeletonDistance(b, {4, 5, 0.5}), 5);
    CylinderSkeleton c{{0, 0, 0}, {0, 0, 2}, 1};
    EXPECT_EQ(SkeletonDistance(c, {0.5, 0, 1}), 0);
    EXPECT_DOUBLE_EQ(SkeletonDistance(c, {3, 0, 1}), 2);
    EXPECT_DOUBLE_EQ(SkeletonDistance(c, {0.5, 0, 5}), 3);
    EXPECT_DOUBLE_EQ(SkeletonDistance(c, {4, 0, 6}), 5);  // rim: (3, 4)
}

TEST(Skeleton, ClosestPointIsOnSkeletonAndInsideBounds) {
    for (uint64_t seed = 1; seed <= 200; ++seed) {
        Rng rng(seed);
        Skeleton s = RandomSkeleton(rng, static_cast<int>(seed % testing::kSkeletonKinds));
        Bounds3 bounds = SkeletonBounds(s).Padded(1e-12);
        Vec3 p = testing::RandomPoint(rng, -3, 3);
        Vec3 c;
        double d = SkeletonDistance(s, p, c);
        EXPECT_NEAR(d, Length(p - c), 1e-12) << "seed " << seed;
        EXPECT_LE(SkeletonDistance(s, c), 1e-9) << "seed " << seed;
        EXPECT_TRUE(bounds.Contains(c)) << "seed " << seed << " kind " << SkeletonKindName(s);
    }
}

// A random point of the skeleton's point set.
Vec3 SampleSkeleton(Rng& rng, const Skeleton& s) {
    return std::visit(
        [&rng](const auto& k) -> Vec3 {
            using T = std::decay_t<decltype(k)>;
            double u = rng.Uniform(), v = rng.Uniform(), w = rng.Uniform();
            if constexpr (std::is_same_v<T, PointSkeleton>) {
                return k.center;
            } else if constexpr (std::is_same_v<T, SegmentSkeleton>) {
                return k.a + (k.b - k.a) * u;
            } else if constexpr (std::is_same_v<T, PolylineSkeleton>) {
                size_t i = static_cast<size_t>(v * (k.points.size() - 1));
                return k.points[i] + (k.points[i + 1] - k.points[i]) * u;
            } else if constexpr (std::is_same_v<T, CircleSkeleton>) {
                Vec3 a, b;
                CoordinateSystem(k.normal, a, b);
                double phi = 2 * M_PI * u;
                return k.center + (a * std::cos(phi) + b * std::sin(phi)) * k.radius;
            } else if constexpr (std::is_same_v<T, TriangleSkeleton>) {
                if (u + v > 1) { u = 1 - u; v = 1 - v; }
                return k.a + (k.b - k.a) * u + (k.c - k.a) * v;
            } else if constexpr (std::is_same_v<T, BoxSkeleton>) {
                return {k.lo.x + (k.hi.x - k.lo.x) * u, k.lo.y + (k.hi.y - k.lo.y) * v,
                        k.lo.z + (k.hi.z - k.lo.z) * w};
            } else {
                Vec3 axis = k.b - k.a, a, b;
                CoordinateSystem(Normalize(axis), a, b);
                double phi = 2 * M_PI * v, rad = k.radius * std::sqrt(w);
                return k.a + axis * u + (a * std::cos(phi) + b * std::sin(phi)) * rad;
            }
        },
        s);
}

TEST(Skeleton, DistanceIsNoMoreThanToAnySkeletonSample) {
    for (uint64_t seed = 1; seed <= 140; ++seed) {
        Rng rng(seed);
        Skeleton s = RandomSkeleton(rng, static_cast<int>(seed % testing::kSkeletonKinds));
        for (int i = 0; i < 20; ++i) {
            Vec3 p = testing::RandomPoint(rng, -3, 3);
            double d = SkeletonDistance(s, p);
            for (int j = 0; j < 200; ++j) {
                ASSERT_LE(d, Length(p - SampleSkeleton(rng, s)) + 1e-12)
                    << "seed " << seed << " kind " << SkeletonKindName(s);
            }
        }
    }
}

// The exact distances at the corners and dense random points of random boxes lie in the
// conservative range.
TEST(Skeleton, DistanceRangeContainsSampledDistances) {
    for (uint64_t seed = 1; seed <= 700; ++seed) {
        Rng rng(seed);
        Skeleton s = RandomSkeleton(rng, static_cast<int>(seed % testing::kSkeletonKinds));
        Bounds3 box = RandomBox(rng, -2, 1.5, 1.5);
        DistanceRange r = SkeletonDistanceRange(s, box);
        ASSERT_LE(r.min, r.max);
        for (int i = 0; i < 300; ++i) {
            Vec3 p = i < 8 ? box.Corner(i) : RandomInBox(rng, box);
            double d = SkeletonDistance(s, p);
            ASSERT_GE(d, r.min - 1e-12) << "seed " << seed << " kind " << SkeletonKindName(s);
            ASSERT_LE(d, r.max + 1e-12) << "seed " << seed << " kind " << SkeletonKindName(s);
        }
    }
}

TEST(Skeleton, PointRangeIsExact) {
    Bounds3 box({1, 0, 0}, {2, 1, 1});
    DistanceRange r = SkeletonDistanceRange(PointSkeleton{{0, 0, 0}}, box);
    EXPECT_DOUBLE_EQ(r.min, 1);
    EXPECT_DOUBLE_EQ(r.max, std::sqrt(6.0));
}

TEST(Skeleton, ConvexityAndExtraCurvature) {
    EXPECT_TRUE(SkeletonIsConvex(CylinderSkeleton{{0, 0, 0}, {0, 0, 1}, 1}));
    EXPECT_FALSE(SkeletonIsConvex(CircleSkeleton{{0, 0, 0}, {0, 0, 1}, 1}));
    CircleSkeleton c{{0, 0, 0}, {0, 0, 1}, 2};
    EXPECT_TRUE(std::isinf(ExtraDistanceCurvature(c, Bounds3({-0.1, -0.1, 1}, {0.1, 0.1, 2}))));
    // Box at distance >= 1 from the axis: X <= 1/(ρmin) with ρmin >= 1 − (bound slack).
    double x = ExtraDistanceCurvature(c, Bounds3({1.4, -0.1, 0}, {1.6, 0.1, 0.2}));
    EXPECT_GT(x, 0);
    EXPECT_LE(x, 1.0);
}

}  // namespace
}  // namespace rs
