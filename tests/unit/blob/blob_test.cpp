#include "libobj/blob.h"

#include <gtest/gtest.h>

#include <cmath>

#include "libcommon/random.h"

namespace rs {
namespace {

// A single metaball is a sphere of radius r·sqrt(1 − sqrt(T/s)).
constexpr double kStrength = 1, kRadius = 1, kThreshold = 0.5;
const double kSurfaceRadius = kRadius * std::sqrt(1 - std::sqrt(kThreshold / kStrength));

Blob SingleBall(const Vec3& centre) { return Blob(kThreshold, {{centre, kRadius, kStrength}}); }

// Nearest t > 0 where the ray o + t·d (unit d) meets the sphere |X − c| = R, offset b from
// the centre line: t = D − sqrt(R² − b²) for a ray aimed past the centre at distance b.
TEST(Blob, SingleBallIsTheAnalyticSphereFromNearAndFarCameras) {
    const Vec3 centre{0.25, -0.5, 0.75};
    Blob blob = SingleBall(centre);
    for (double distance : {3.0, 10.0, 1e2, 1e3, 1e4, 1e5, 1e6}) {
        for (double offset : {0.0, 0.3, 0.5}) {
            Ray ray{centre + Vec3{offset, -distance, 0}, {0, 1, 0}, 0};
            PrimitiveHit hit;
            ASSERT_TRUE(blob.Intersect(ray, 1e-5, 1e14, hit))
                << "distance " << distance << " offset " << offset;
            double expected = distance - std::sqrt(kSurfaceRadius * kSurfaceRadius - offset * offset);
            // Error scales with the floating-point spacing at the camera distance.
            double tolerance = 1e-9 + 64 * distance * 2.2e-16;
            EXPECT_NEAR(hit.t, expected, tolerance) << "distance " << distance << " offset " << offset;
        }
        Ray miss{centre + Vec3{kSurfaceRadius * 1.001, -distance, 0}, {0, 1, 0}, 0};
        PrimitiveHit hit;
        EXPECT_FALSE(blob.Intersect(miss, 1e-5, 1e14, hit)) << "distance " << distance;
    }
}

TEST(Blob, SecondaryRayStartingJustOutsideFindsTheExit) {
    // The original loses these (its smallest root of the interval falls below mindist).
    Blob blob = SingleBall({0, 0, 0});
    for (double gap : {1e-9, 1e-8, 1e-7}) {
        Ray ray{{0, 0, kSurfaceRadius + gap}, {0, 0, -1}, 0};
        PrimitiveHit hit;
        ASSERT_TRUE(blob.Intersect(ray, 1e-5, 1e14, hit)) << "gap " << gap;
        // The entry root lies below tMin, so the first root beyond it is the far side.
        EXPECT_NEAR(hit.t, 2 * kSurfaceRadius + gap, 1e-9) << "gap " << gap;
    }
}

TEST(Blob, RaysFromInsideFindTheExitChord) {
    Blob blob = SingleBall({0, 0, 0});
    Rng rng(11);
    for (int i = 0; i < 1000; ++i) {
        Vec3 d = Normalize(Vec3{rng.Uniform() - 0.5, rng.Uniform() - 0.5, rng.Uniform() - 0.5});
        PrimitiveHit hit;
        ASSERT_TRUE(blob.Intersect({{0, 0, 0}, d * 2.0, 0}, 1e-5, 1e14, hit));  // non-unit d
        EXPECT_NEAR(hit.t * 2.0, kSurfaceRadius, 1e-10);
    }
}

TEST(Blob, NormalIsRadialOnASingleBall) {
    Blob blob = SingleBall({1, 2, 3});
    Vec3 p = Vec3{1, 2, 3} + Normalize(Vec3{1, 1, -1}) * kSurfaceRadius;
    SurfaceNormals n = blob.Normal(p, {});
    Vec3 expected = Normalize(Vec3{1, 1, -1});
    EXPECT_NEAR(Dot(n.geometric, expected), 1, 1e-12);
}

TEST(Blob, TwoBallsHitWhereTheFieldEqualsTheThreshold) {
    Blob blob(0.6, {{{-0.45, 0, 0}, 1, 1}, {{0.45, 0, 0}, 1, 1}});
    Rng rng(5);
    int hits = 0;
    for (int i = 0; i < 500; ++i) {
        Vec3 o{rng.Uniform() * 6 - 3, -5, rng.Uniform() * 2 - 1};
        Vec3 target{rng.Uniform() - 0.5, 0, rng.Uniform() - 0.5};
        Ray ray{o, Normalize(target - o), 0};
        PrimitiveHit hit;
        if (!blob.Intersect(ray, 1e-5, 1e14, hit)) continue;
        ++hits;
        EXPECT_NEAR(blob.Field(ray.At(hit.t)), 0.6, 1e-9);
        // Nothing before the hit is inside: sample the segment.
        for (int k = 1; k < 50; ++k) ASSERT_LT(blob.Field(ray.At(hit.t * k / 50.0)), 0.6);
    }
    EXPECT_GT(hits, 100);
}

TEST(Blob, GrazingRaysHitFromNearAndFarCameras) {
    // Rays passing the centre at 1 − 10⁻⁶ of the surface radius: the field peaks only
    // ~10⁻⁶ above the threshold along them, yet they must hit where the sphere says.
    const Vec3 centre{0.25, -0.5, 0.75};
    Blob blob = SingleBall(centre);
    const double offset = kSurfaceRadius * (1 - 1e-6);
    const double halfChord = std::sqrt(kSurfaceRadius * kSurfaceRadius - offset * offset);
    for (double distance : {3.0, 1e2, 1e4, 1e6}) {
        Ray ray{centre + Vec3{0, -distance, offset}, {0, 1, 0}, 0};
        PrimitiveHit hit;
        ASSERT_TRUE(blob.Intersect(ray, 1e-5, 1e14, hit)) << "distance " << distance;
        EXPECT_NEAR(hit.t, distance - halfChord, 1e-6 * halfChord + 64 * distance * 2.2e-16)
            << "distance " << distance;
    }
}

TEST(Blob, GrazingRaysThroughTheSaddleOfTwoBalls) {
    // Balls s = r = 1 at x = ±a, threshold T: on the plane x = 0 both are at ρ² = a² + y² + z²,
    // so a ray along y at height z meets the surface where 2(1 − ρ²)² = T, i.e.
    // y² = 1 − sqrt(T/2) − a² − z², and misses above z* = sqrt(1 − sqrt(T/2) − a²). Rays a
    // relative 10⁻⁶ below z* hit (the field peaks only ~10⁻⁶ above T on them); rays as far
    // above miss, so the field-bound rejection neither loses the one nor accepts the other.
    constexpr double a = 0.45, kT = 0.6, kStart = 5;
    Blob blob(kT, {{{-a, 0, 0}, 1, 1}, {{a, 0, 0}, 1, 1}});
    const double reach2 = 1 - std::sqrt(kT / 2) - a * a;  // z*²
    for (double relative : {1e-6, 1e-4, 1e-2}) {
        const double below = std::sqrt(reach2) * (1 - relative);
        Ray ray{{0, -kStart, below}, {0, 1, 0}, 0};
        PrimitiveHit hit;
        ASSERT_TRUE(blob.Intersect(ray, 1e-5, 1e14, hit)) << "relative " << relative;
        EXPECT_NEAR(hit.t, kStart - std::sqrt(reach2 - below * below), 1e-8)
            << "relative " << relative;
        Ray above{{0, -kStart, std::sqrt(reach2) * (1 + relative)}, {0, 1, 0}, 0};
        EXPECT_FALSE(blob.Intersect(above, 1e-5, 1e14, hit)) << "relative " << relative;
    }
}

}  // namespace
}  // namespace rs
