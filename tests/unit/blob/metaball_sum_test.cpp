// MetaballSum (libobj/metaball_sum.h) with enough balls that it searches them through its
// bounding volume hierarchy, against analytic answers: balls far enough apart that their
// spheres of influence do not overlap are spheres of radius r·sqrt(1 − sqrt(T/s)).
#include "libobj/metaball_sum.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "libcommon/random.h"

namespace rs {
namespace {

constexpr double kThreshold = 0.5, kRadius = 1;

// The surface radius of a lone ball of strength s > T.
double SurfaceRadius(double s) { return kRadius * std::sqrt(1 - std::sqrt(kThreshold / s)); }

// 6 × 6 × 6 balls 2.5 apart (influence radius 1: no overlaps), strengths in [0.8, 2].
std::vector<Metaball> SeparatedBalls(Rng& rng) {
    std::vector<Metaball> balls;
    for (int i = 0; i < 6; ++i)
        for (int j = 0; j < 6; ++j)
            for (int k = 0; k < 6; ++k)
                balls.push_back({{2.5 * i, 2.5 * j, 2.5 * k}, kRadius, 0.8 + 1.2 * rng.Uniform()});
    return balls;
}

// The first t in (tMin, tMax) where the ray meets one of the balls' surface spheres.
double AnalyticFirstHit(const std::vector<Metaball>& balls, const Ray& ray, double tMin,
                        double tMax) {
    double best = std::numeric_limits<double>::infinity();
    const double dd = Dot(ray.dir, ray.dir);
    for (const Metaball& b : balls) {
        const double rs = SurfaceRadius(b.strength);
        const Vec3 oc = ray.origin - b.centre;
        const double tc = -Dot(oc, ray.dir) / dd;
        const double dist2 = LengthSquared(oc + ray.dir * tc);
        if (dist2 >= rs * rs) continue;
        const double h = std::sqrt((rs * rs - dist2) / dd);
        for (double t : {tc - h, tc + h}) {
            if (t > tMin && t < tMax && t < best) best = t;
        }
    }
    return best;
}

Vec3 RandomDirection(Rng& rng) {
    for (;;) {
        Vec3 d{2 * rng.Uniform() - 1, 2 * rng.Uniform() - 1, 2 * rng.Uniform() - 1};
        const double l2 = LengthSquared(d);
        if (l2 > 1e-4 && l2 <= 1) return d / std::sqrt(l2);
    }
}

TEST(MetaballSum, SeparatedBallsAreAnalyticSpheresForRandomRays) {
    Rng rng(17);
    const std::vector<Metaball> balls = SeparatedBalls(rng);
    MetaballSum sum(kThreshold, balls);
    int hits = 0;
    for (int n = 0; n < 4000; ++n) {
        // Origins in and around the lattice (some inside balls: their exits count), aimed
        // at a random point of it.
        const Vec3 origin{16 * rng.Uniform() - 2, 16 * rng.Uniform() - 2, 16 * rng.Uniform() - 2};
        const Vec3 target{12.5 * rng.Uniform(), 12.5 * rng.Uniform(), 12.5 * rng.Uniform()};
        const Ray ray{origin, (target - origin) * (0.5 + rng.Uniform()), 0};  // non-unit
        const double tMax = n % 2 ? 1e9 : 1.0;  // half the rays end at their target
        const double expected = AnalyticFirstHit(balls, ray, 1e-5, tMax);
        const std::optional<double> t = sum.FirstRoot(ray, 1e-5, tMax);
        if (std::isinf(expected)) {
            // A hit is allowed only as a tangency within rounding: on a surface sphere.
            if (t) {
                double gap = std::numeric_limits<double>::infinity();
                for (const Metaball& b : balls) {
                    gap = std::min(gap, std::abs(Length(ray.At(*t) - b.centre) -
                                                 SurfaceRadius(b.strength)));
                }
                EXPECT_LT(gap, 1e-7) << "ray " << n;
            }
            continue;
        }
        ASSERT_TRUE(t.has_value()) << "ray " << n << " expected t " << expected;
        // Positions to 1e-9: the quartic's roots near a simple crossing.
        EXPECT_NEAR(Length(ray.At(*t) - ray.At(expected)), 0, 1e-9) << "ray " << n;
        ++hits;
    }
    EXPECT_GT(hits, 1000);  // the test exercises hits, not just misses
}

TEST(MetaballSum, GradientAndValueAreTheAnalyticOnesOfTheNearestBall) {
    Rng rng(23);
    const std::vector<Metaball> balls = SeparatedBalls(rng);
    MetaballSum sum(kThreshold, balls);
    for (int n = 0; n < 2000; ++n) {
        const Metaball& b = balls[static_cast<size_t>(rng.Uniform() * balls.size())];
        const double rho = 1.2 * rng.Uniform();  // up to beyond the radius: F = 0 there
        const Vec3 offset = RandomDirection(rng) * rho;
        const Vec3 p = b.centre + offset;
        // F = s(1 − ρ²/r²)², ∇F = −(4s/r²)(1 − ρ²/r²)(X − c) inside, 0 beyond r.
        const double q = std::max(0.0, 1 - rho * rho / (kRadius * kRadius));
        const Vec3 gradient = offset * (-4 * b.strength / (kRadius * kRadius) * q);
        EXPECT_NEAR(sum.Value(p), b.strength * q * q, 1e-12) << "point " << n;
        EXPECT_NEAR(Length(sum.Gradient(p) - gradient), 0, 1e-12) << "point " << n;
    }
}

TEST(MetaballSum, NegativeStrengthCarvesAConcentricBall) {
    // s = 2 and s = −1.5 at each centre: one ball of strength 0.5 per site.
    std::vector<Metaball> balls;
    for (int i = 0; i < 12; ++i) {
        balls.push_back({{3.0 * i, 0, 0}, kRadius, 2});
        balls.push_back({{3.0 * i, 0, 0}, kRadius, -1.5});
    }
    MetaballSum sum(kThreshold / 2, balls);  // T/s as for s = 1, T = 0.5 after the carve
    const double expected = SurfaceRadius(1);
    for (int i = 0; i < 12; ++i) {
        const Ray ray{{3.0 * i, -5, 0.1}, {0, 1, 0}, 0};
        const std::optional<double> t = sum.FirstRoot(ray, 1e-5, 1e9);
        ASSERT_TRUE(t.has_value()) << "site " << i;
        EXPECT_NEAR(*t, 5 - std::sqrt(expected * expected - 0.01), 1e-10) << "site " << i;
    }
}

}  // namespace
}  // namespace rs
