// MetaballSum (libgeom/metaball_sum.h) against analytic answers, through each of its search
// structures: balls far enough apart that their spheres of influence do not overlap are
// spheres of radius r·sqrt(1 − sqrt(T/s)).
#include "libgeom/metaball_sum.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "libcommon/random.h"

namespace rs {
namespace {

constexpr double kThreshold = 0.5;

// The surface radius of a lone ball of strength s > T.
double SurfaceRadius(const Metaball& b) {
    return b.radius * std::sqrt(1 - std::sqrt(kThreshold / b.strength));
}

// 6 × 6 × 6 balls of radius 1 on a lattice of step 2.5 (no overlaps) from `origin`,
// strengths in [0.8, 2].
std::vector<Metaball> SeparatedBalls(Rng& rng, const Vec3& origin = {0, 0, 0}) {
    std::vector<Metaball> balls;
    for (int i = 0; i < 6; ++i)
        for (int j = 0; j < 6; ++j)
            for (int k = 0; k < 6; ++k)
                balls.push_back({origin + Vec3{2.5 * i, 2.5 * j, 2.5 * k}, 1, 0.8 + 1.2 * rng.Uniform()});
    return balls;
}

// The first t in (tMin, tMax) where the ray meets one of the balls' surface spheres.
double AnalyticFirstHit(const std::vector<Metaball>& balls, const Ray& ray, double tMin,
                        double tMax) {
    double best = std::numeric_limits<double>::infinity();
    const double dd = Dot(ray.dir, ray.dir);
    for (const Metaball& b : balls) {
        const double rs = SurfaceRadius(b);
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

// FirstRoot against AnalyticFirstHit on one ray: positions to `tolerance`; a hit where none
// is expected only as a tangency within rounding (on a surface sphere). Returns whether the
// ray hit.
bool ExpectFirstHit(const MetaballSum& sum, const std::vector<Metaball>& balls, const Ray& ray,
                    double tMax, double tolerance, int n) {
    const double expected = AnalyticFirstHit(balls, ray, 1e-5, tMax);
    const std::optional<double> t = sum.FirstRoot(ray, 1e-5, tMax);
    if (std::isinf(expected)) {
        if (t) {
            double gap = std::numeric_limits<double>::infinity();
            for (const Metaball& b : balls) {
                gap = std::min(gap, std::abs(Length(ray.At(*t) - b.centre) - SurfaceRadius(b)));
            }
            EXPECT_LT(gap, 1e-7) << "ray " << n;
        }
        return false;
    }
    EXPECT_TRUE(t.has_value()) << "ray " << n << " expected t " << expected;
    if (t) {
        EXPECT_NEAR(Length(ray.At(*t) - ray.At(expected)), 0, tolerance) << "ray " << n;
    }
    return true;
}

Vec3 RandomDirection(Rng& rng) {
    for (;;) {
        Vec3 d{2 * rng.Uniform() - 1, 2 * rng.Uniform() - 1, 2 * rng.Uniform() - 1};
        const double l2 = LengthSquared(d);
        if (l2 > 1e-4 && l2 <= 1) return d / std::sqrt(l2);
    }
}

// Random rays from in and around a box (some inside balls: their exits count) to random
// points of it, half of them ending there; hits at positions within 1e-9 (simple crossings).
int CheckRandomRays(const MetaballSum& sum, const std::vector<Metaball>& balls,
                    const Bounds3& box, Rng& rng, int rays) {
    const Vec3 extent = box.Extent();
    int hits = 0;
    for (int n = 0; n < rays; ++n) {
        const Vec3 origin = box.lo - extent * 0.2 +
                            Vec3{rng.Uniform() * extent.x, rng.Uniform() * extent.y,
                                 rng.Uniform() * extent.z} * 1.4;
        const Vec3 target = box.lo + Vec3{rng.Uniform() * extent.x, rng.Uniform() * extent.y,
                                          rng.Uniform() * extent.z};
        const Ray ray{origin, (target - origin) * (0.5 + rng.Uniform()), 0};  // non-unit
        hits += ExpectFirstHit(sum, balls, ray, n % 2 ? 1e9 : 1.0, 1e-9, n);
    }
    return hits;
}

TEST(MetaballSum, GridFindsTheAnalyticSpheresForRandomRays) {
    Rng rng(17);
    const std::vector<Metaball> balls = SeparatedBalls(rng);
    MetaballSum sum(kThreshold, balls);
    ASSERT_EQ(sum.SearchStructure(), MetaballSum::Search::Grid);
    EXPECT_GT(CheckRandomRays(sum, balls, sum.Bounds(), rng, 4000), 1000);
}

// Rays along the axes (direction components exactly 0) through the lattice's rows and
// between them, and from very far away (the walk's first point and cell boundaries are
// rounded at the origin's magnitude).
TEST(MetaballSum, GridWalksAxisRaysAndFarCameras) {
    Rng rng(29);
    const std::vector<Metaball> balls = SeparatedBalls(rng);
    MetaballSum sum(kThreshold, balls);
    ASSERT_EQ(sum.SearchStructure(), MetaballSum::Search::Grid);
    int n = 0, hits = 0;
    for (int axis = 0; axis < 3; ++axis) {
        for (double distance : {5.0, 1e3, 1e6}) {
            for (int row = 0; row < 24; ++row) {
                // Offsets across the row: through centres, beside them, between rows.
                Vec3 origin{0.3 * row + 0.05, 0.45 * row - 0.2, 0.6 * row + 0.1};
                origin[axis] = -distance;
                Vec3 dir{0, 0, 0};
                dir[axis] = 1;
                const double tolerance = 1e-9 + 64 * distance * 2.2e-16;
                hits += ExpectFirstHit(sum, balls, Ray{origin, dir, 0}, 1e12, tolerance, n++);
                origin[axis] = 12.5 + distance;
                dir[axis] = -1;
                hits += ExpectFirstHit(sum, balls, Ray{origin, dir, 0}, 1e12, tolerance, n++);
            }
        }
    }
    EXPECT_GT(hits, 100);
}

// A chain of overlapping skeletons along a persistent random walk, radius 1, strengths in
// [0.7, 1.3]: points 0.6 apart, or segments of length 1.5 end to end (the skeletons of the
// POV-Ray kit's chains). Rays cross intervals with several active balls, which the grid
// walk must all have found.
std::vector<Metaball> Chain(Rng& rng, int count, bool segments) {
    const double step = segments ? 1.5 : 0.6;
    std::vector<Metaball> balls;
    Vec3 p{0, 0, 0}, d{1, 0, 0};
    for (int i = 0; i < count; ++i) {
        d = Normalize(d + RandomDirection(rng) * 0.5);
        const double strength = 0.7 + 0.6 * rng.Uniform();
        balls.push_back({p, 1, strength, segments ? d * step : Vec3{0, 0, 0}});
        p += d * step;
    }
    return balls;
}

// The squared distance from p to a ball's skeleton (its centre, or the segment from
// centre to centre + axis), written out here independently of MetaballSum.
double SkeletonDistance2(const Metaball& b, const Vec3& p) {
    const double length2 = LengthSquared(b.axis);
    const double u = length2 > 0 ? std::clamp(Dot(p - b.centre, b.axis) / length2, 0.0, 1.0) : 0;
    return LengthSquared(p - (b.centre + b.axis * u));
}

// The first crossing of F = T along the ray beyond tMin, by sampling F (summed here from
// its definition) every `step` over the part of the ray inside some ball's bounding sphere
// and bisecting the first sign change to 1e-13; +∞ when no sample is inside. Independent
// of MetaballSum; misses only features thinner than `step`. The ray starts outside every
// ball.
double SampledFirstCrossing(const std::vector<Metaball>& balls, const Ray& ray, double tMin,
                            double step) {
    std::vector<const Metaball*> near;  // the balls whose bounding sphere the line meets
    const double dd = Dot(ray.dir, ray.dir);
    double tStart = std::numeric_limits<double>::infinity(), tEnd = tMin;
    for (const Metaball& b : balls) {
        const double reach = b.radius + 0.5 * Length(b.axis);
        const Vec3 oc = ray.origin - (b.centre + b.axis * 0.5);
        const double tc = -Dot(oc, ray.dir) / dd;
        const double dist2 = LengthSquared(oc + ray.dir * tc);
        if (dist2 >= reach * reach) continue;
        near.push_back(&b);
        const double h = std::sqrt((reach * reach - dist2) / dd);
        tStart = std::min(tStart, tc - h);
        tEnd = std::max(tEnd, tc + h);
    }
    const auto g = [&](double t) {
        const Vec3 p = ray.At(t);
        double f = 0;
        for (const Metaball* b : near) {
            const double q = 1 - SkeletonDistance2(*b, p) / (b->radius * b->radius);
            if (q > 0) f += b->strength * q * q;
        }
        return f - kThreshold;
    };
    for (double a = std::max(tMin, tStart); a < tEnd;) {
        const double b = std::min(a + step, tEnd);
        if (g(b) > 0) {
            double lo = a, hi = b;  // g(lo) <= 0 < g(hi)
            while (hi - lo > 1e-13) {
                const double mid = 0.5 * (lo + hi);
                if (mid <= lo || mid >= hi) break;
                (g(mid) > 0 ? hi : lo) = mid;
            }
            return hi;
        }
        a = b;
    }
    return std::numeric_limits<double>::infinity();
}

// Random rays from outside the chain's box towards points near its balls' centres (within
// 0.8 of one), against the sampled crossing (positions within 1e-8).
int CheckAgainstSampledField(const MetaballSum& sum, const std::vector<Metaball>& balls,
                             const Bounds3& box, Rng& rng, int rays) {
    const double far = Length(box.Extent());
    int hits = 0;
    for (int n = 0; n < rays; ++n) {
        const Vec3 origin = box.Center() + RandomDirection(rng) * far;
        const Metaball& aim = balls[static_cast<size_t>(rng.Uniform() * balls.size())];
        const Vec3 target = aim.centre + RandomDirection(rng) * (0.8 * rng.Uniform());
        const Ray ray{origin, Normalize(target - origin), 0};
        const double expected = SampledFirstCrossing(balls, ray, 1e-5, 1e-4);
        const std::optional<double> t = sum.FirstRoot(ray, 1e-5, 1e9);
        if (std::isinf(expected)) {
            EXPECT_FALSE(t.has_value()) << "ray " << n << " t " << *t;
            continue;
        }
        ++hits;
        EXPECT_TRUE(t.has_value()) << "ray " << n << " expected t " << expected;
        if (t) {
            EXPECT_NEAR(*t, expected, 1e-8) << "ray " << n;
        }
    }
    return hits;
}

TEST(MetaballSum, GridFindsEveryOverlappingBallOfAnInterval) {
    Rng rng(53);
    for (bool segments : {false, true}) {
        const std::vector<Metaball> balls = Chain(rng, segments ? 200 : 300, segments);
        MetaballSum sum(kThreshold, balls);
        ASSERT_EQ(sum.SearchStructure(), MetaballSum::Search::Grid);
        EXPECT_GT(CheckAgainstSampledField(sum, balls, sum.Bounds(), rng, 300), 150) << segments;
    }
}

TEST(MetaballSum, CapsulesThroughTheLoopMatchTheSampledField) {
    Rng rng(67);
    const std::vector<Metaball> few = Chain(rng, 6, true);
    MetaballSum small(kThreshold, few);
    ASSERT_EQ(small.SearchStructure(), MetaballSum::Search::Loop);
    EXPECT_GT(CheckAgainstSampledField(small, few, small.Bounds(), rng, 200), 100);
}

// A lone capsule is the analytic capsule of radius r·sqrt(1 − sqrt(T/s)) around its
// segment: rays along and across the axis, and from inside, hit it where a cylinder and
// sphere computation says; its gradient points away from the segment.
TEST(MetaballSum, LoneCapsuleIsTheAnalyticCapsule) {
    const Metaball capsule{{1, 2, 3}, 1, 1, {2, 0, 0}};  // segment (1,2,3)-(3,2,3)
    MetaballSum sum(kThreshold, std::span(&capsule, 1));
    const double r = SurfaceRadius(capsule);
    struct Case {
        Ray ray;
        double t;
    };
    const Case cases[] = {
        {{{2, -5, 3}, {0, 1, 0}, 0}, 7 - r},                         // across the middle
        {{{2.5, 2, 10}, {0, 0, -2}, 0}, (7 - r) / 2},                // across, non-unit d
        {{{-5, 2, 3}, {1, 0, 0}, 0}, 6 - r},                         // along the axis: cap
        {{{10, 2.1, 3}, {-1, 0, 0}, 0}, 7 - std::sqrt(r * r - 0.01)},  // along, off axis
        {{{2, 2, 3}, {0, 0, 1}, 0}, r},                              // from inside: exit
        {{{0.5, 2, -5}, {0, 0, 1}, 0}, 8 - std::sqrt(r * r - 0.25)},   // through a cap
    };
    for (const Case& c : cases) {
        const std::optional<double> t = sum.FirstRoot(c.ray, 1e-5, 1e9);
        ASSERT_TRUE(t.has_value()) << c.ray.origin.x << " " << c.ray.origin.z;
        EXPECT_NEAR(*t, c.t, 1e-10) << c.ray.origin.x << " " << c.ray.origin.z;
        const Vec3 p = c.ray.At(*t);
        const Vec3 outward = Normalize(p - Vec3{std::clamp(p.x, 1.0, 3.0), 2, 3});
        EXPECT_NEAR(Length(Normalize(-sum.Gradient(p)) - outward), 0, 1e-9);
        EXPECT_EQ(sum.Predominant(p), 0);
    }
    EXPECT_FALSE(sum.FirstRoot({{2, -5, 3 + 1.001 * r}, {0, 1, 0}, 0}, 1e-5, 1e9).has_value());
}

// A ray along a row of capsules crosses three pieces of each (cap, axis, cap): nine spans
// from three capsules, which the search must hold (one span per ball would not do).
TEST(MetaballSum, RayAlongARowOfCapsulesCrossesEveryPiece) {
    std::vector<Metaball> row;
    for (int i = 0; i < 3; ++i) row.push_back({{4.0 * i, 0, 0}, 1, 1, {3, 0, 0}});
    for (int copies : {1, 4}) {  // the loop, and the grid (a copy of the row far away)
        std::vector<Metaball> balls;
        for (int c = 0; c < copies; ++c) {
            for (Metaball b : row) {
                b.centre.y += 10.0 * c;
                balls.push_back(b);
            }
        }
        MetaballSum sum(kThreshold, balls);
        const double r = SurfaceRadius(row[0]);
        // Rightwards, from inside the first capsule: the gaps of 1 between capsules are
        // bridged (each side gives (1 − 0.5²)² > T/2 at their middle), so the ray leaves at
        // the last capsule's cap, x = 11 + r.
        const std::optional<double> exit = sum.FirstRoot({{1, 0, 0}, {1, 0, 0}, 0}, 1e-5, 1e9);
        ASSERT_TRUE(exit.has_value()) << copies;
        EXPECT_NEAR(*exit, 10 + r, 1e-10) << copies;
        // Leftwards from beyond the row: the last capsule's cap.
        const std::optional<double> hit = sum.FirstRoot({{20, 0, 0}, {-1, 0, 0}, 0}, 1e-5, 1e9);
        ASSERT_TRUE(hit.has_value()) << copies;
        EXPECT_NEAR(*hit, 20 - (11 + r), 1e-10) << copies;
        // Along the axis line but past every capsule's support: nothing.
        EXPECT_FALSE(sum.FirstRoot({{20, 0, 0}, {1, 0, 0}, 0}, 1e-5, 1e9).has_value());
    }
}

// Balls crowded into a small part of their box (a cluster and one ball far away): the
// hierarchy, with the same answers.
TEST(MetaballSum, CrowdedBallsUseTheHierarchyWithTheSameAnswers) {
    Rng rng(41);
    std::vector<Metaball> balls = SeparatedBalls(rng);
    balls.push_back({{1000, 1000, 1000}, 1, 1.5});
    MetaballSum sum(kThreshold, balls);
    ASSERT_EQ(sum.SearchStructure(), MetaballSum::Search::Hierarchy);
    const Bounds3 cluster({-1, -1, -1}, {13.5, 13.5, 13.5});
    EXPECT_GT(CheckRandomRays(sum, balls, cluster, rng, 2000), 500);
    // Overlapping balls too.
    std::vector<Metaball> chain = Chain(rng, 300, false);
    const Bounds3 chainBox = MetaballSum(kThreshold, chain).Bounds();
    chain.push_back({{1000, 1000, 1000}, 1, 1.5});
    MetaballSum crowded(kThreshold, chain);
    ASSERT_EQ(crowded.SearchStructure(), MetaballSum::Search::Hierarchy);
    chain.pop_back();  // aim at the chain
    EXPECT_GT(CheckAgainstSampledField(crowded, chain, chainBox, rng, 200), 100);
}

// Balls 1e300 apart (their box's volume overflows): no grid, answers still exact.
TEST(MetaballSum, AstronomicalSpreadFallsBackToTheHierarchy) {
    std::vector<Metaball> balls;
    for (int i = 0; i < 10; ++i) {
        balls.push_back({{2.5 * i, 0, 0}, 1, 1});
        balls.push_back({{1e300, 1e300 * (i + 1), -1e300}, 1, 1});
    }
    MetaballSum sum(kThreshold, balls);
    EXPECT_EQ(sum.SearchStructure(), MetaballSum::Search::Hierarchy);
    const double r = SurfaceRadius(balls[0]);
    for (int i = 0; i < 10; ++i) {
        const std::optional<double> t = sum.FirstRoot({{2.5 * i, -5, 0}, {0, 1, 0}, 0}, 1e-5, 1e9);
        ASSERT_TRUE(t.has_value()) << i;
        EXPECT_NEAR(*t, 5 - r, 1e-12) << i;
    }
    EXPECT_FALSE(sum.FirstRoot({{0, -5, 100}, {0, 1, 0}, 0}, 1e-5, 1e9).has_value());
}

TEST(MetaballSum, GradientAndValueAreTheAnalyticOnesOfTheNearestBall) {
    Rng rng(23);
    for (const Vec3& far : {Vec3{0, 0, 0}, Vec3{1000, 1000, 1000}}) {
        std::vector<Metaball> balls = SeparatedBalls(rng);
        if (far.x != 0) balls.push_back({far, 1, 1.5});  // crowds: the hierarchy
        MetaballSum sum(kThreshold, balls);
        for (int n = 0; n < 2000; ++n) {
            const Metaball& b = balls[static_cast<size_t>(rng.Uniform() * balls.size())];
            const double rho = 1.2 * rng.Uniform();  // up to beyond the radius: F = 0 there
            const Vec3 offset = RandomDirection(rng) * rho;
            const Vec3 p = b.centre + offset;
            // F = s(1 − ρ²/r²)², ∇F = −(4s/r²)(1 − ρ²/r²)(X − c) inside, 0 beyond r.
            const double q = std::max(0.0, 1 - rho * rho);
            const Vec3 gradient = offset * (-4 * b.strength * q);
            EXPECT_NEAR(sum.Value(p), b.strength * q * q, 1e-12) << "point " << n;
            EXPECT_NEAR(Length(sum.Gradient(p) - gradient), 0, 1e-12) << "point " << n;
            const int own = static_cast<int>(&b - balls.data());
            EXPECT_EQ(sum.Predominant(p), q > 0 ? own : -1) << "point " << n;
        }
    }
}

TEST(MetaballSum, NegativeStrengthCarvesAConcentricBall) {
    // s = 2 and s = −1.5 at each centre: one ball of strength 0.5 per site.
    std::vector<Metaball> balls;
    for (int i = 0; i < 12; ++i) {
        balls.push_back({{3.0 * i, 0, 0}, 1, 2});
        balls.push_back({{3.0 * i, 0, 0}, 1, -1.5});
    }
    MetaballSum sum(kThreshold / 2, balls);  // T/s as for s = 1, T = 0.5 after the carve
    const double expected = SurfaceRadius({{0, 0, 0}, 1, 1});
    for (int i = 0; i < 12; ++i) {
        const Ray ray{{3.0 * i, -5, 0.1}, {0, 1, 0}, 0};
        const std::optional<double> t = sum.FirstRoot(ray, 1e-5, 1e9);
        ASSERT_TRUE(t.has_value()) << "site " << i;
        EXPECT_NEAR(*t, 5 - std::sqrt(expected * expected - 0.01), 1e-10) << "site " << i;
    }
}

}  // namespace
}  // namespace rs
