#include "libobj/implicit/patch.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <variant>

#include "test_util.h"

namespace rs {
namespace {

FieldTerm Point(const std::string& name, Vec3 c, double weight = 1) {
    return {name, PointSkeleton{c}, Kernel::GascuelQuadratic(0.5, 2, 1.5), weight};
}

TEST(Patch, AutomaticNeighboursAreOverlappingSupports) {
    std::vector<FieldTerm> terms{Point("a", {0, 0, 0}), Point("b", {1, 0, 0}),
                                 Point("c", {10, 0, 0})};
    std::vector<Patch> patches = BuildPatches(Field(terms), BlendMode::Automatic);
    ASSERT_EQ(patches.size(), 3u);
    EXPECT_EQ(patches[0].Members(), (std::vector<int>{0, 1}));
    EXPECT_EQ(patches[1].Members(), (std::vector<int>{1, 0}));
    EXPECT_EQ(patches[2].Members(), (std::vector<int>{2}));
    EXPECT_TRUE(patches[2].Box().Contains({11.4, 0, 0}));
    EXPECT_FALSE(patches[2].Box().Contains({11.6, 0, 0}));
}

TEST(Patch, ExplicitModeBlendsDeclaredPairsOnly) {
    std::vector<FieldTerm> terms{Point("a", {0, 0, 0}), Point("b", {1, 0, 0}),
                                 Point("c", {0.5, 0.5, 0})};
    std::vector<Patch> patches = BuildPatches(Field(terms), BlendMode::Explicit, {{0, 2}});
    ASSERT_EQ(patches.size(), 3u);
    EXPECT_EQ(patches[0].Members(), (std::vector<int>{0, 2}));
    EXPECT_EQ(patches[1].Members(), (std::vector<int>{1}));
    EXPECT_EQ(patches[2].Members(), (std::vector<int>{2, 0}));
}

TEST(Patch, NegativeTermsOwnNoPatchButAreNeighbours) {
    std::vector<FieldTerm> terms{Point("a", {0, 0, 0}), Point("hole", {0.3, 0, 0}, -1)};
    std::vector<Patch> patches = BuildPatches(Field(terms), BlendMode::Automatic);
    ASSERT_EQ(patches.size(), 1u);
    EXPECT_EQ(patches[0].Members(), (std::vector<int>{0, 1}));
}

TEST(Patch, PredominanceBreaksTiesByLowestIndex) {
    std::vector<FieldTerm> terms{Point("a", {-1, 0, 0}), Point("b", {1, 0, 0})};
    std::vector<Patch> patches = BuildPatches(Field(terms), BlendMode::Automatic);
    Vec3 mid{0, 0.3, 0};  // equidistant: exact tie
    EXPECT_TRUE(patches[0].Predominates(mid));
    EXPECT_FALSE(patches[1].Predominates(mid));
    EXPECT_TRUE(patches[1].Predominates({0.1, 0.3, 0}));
    EXPECT_FALSE(patches[0].Predominates({0.1, 0.3, 0}));
    // Coincident skeletons: only the first ever predominates.
    std::vector<FieldTerm> same{Point("a", {0, 0, 0}), Point("b", {0, 0, 0})};
    std::vector<Patch> twins = BuildPatches(Field(same), BlendMode::Automatic);
    EXPECT_TRUE(twins[0].Predominates({0.2, 0, 0}));
    EXPECT_FALSE(twins[1].Predominates({0.2, 0, 0}));
}

TEST(Patch, PatchFieldIsOwnPlusNeighbours) {
    std::vector<FieldTerm> terms{Point("a", {0, 0, 0}), Point("b", {1, 0, 0}),
                                 Point("c", {10, 0, 0})};
    std::vector<Patch> patches = BuildPatches(Field(terms), BlendMode::Automatic);
    Vec3 p{0.4, 0.1, 0};
    Field all(terms);
    EXPECT_DOUBLE_EQ(patches[0].GetField().Value(p), all.Value(p));
}

// Property (seeded): the grid-accelerated neighbour search finds exactly the terms whose
// support boxes overlap, in increasing order, for skeletons of mixed sizes and radii.
TEST(Patch, AutomaticNeighboursMatchAllPairsOnRandomTerms) {
    std::mt19937 rng(20261122);
    std::uniform_real_distribution<double> coord(-6, 6), radius(0.3, 2.5), unit(0, 1);
    std::vector<FieldTerm> terms;
    for (int i = 0; i < 150; ++i) {
        Vec3 a{coord(rng), coord(rng), coord(rng)};
        FieldTerm t{std::to_string(i), PointSkeleton{a},
                    Kernel::GascuelQuadratic(0.2, 1, radius(rng)), unit(rng) < 0.1 ? -1.0 : 1.0};
        if (i % 5 == 0) t.skeleton = SegmentSkeleton{a, a + Vec3{coord(rng), 0, 1} * 0.5};
        terms.push_back(t);
    }
    const Field field(terms);
    std::vector<Patch> patches = BuildPatches(field, BlendMode::Automatic);
    const AutomaticNeighbours lazy(field);  // the lists one patch at a time, as PatchesMethod
    size_t next = 0;
    for (int i = 0; i < static_cast<int>(terms.size()); ++i) {
        if (!(terms[i].weight > 0)) continue;
        ASSERT_LT(next, patches.size());
        std::vector<int> expected{i};
        const Bounds3 own = TermSupportBounds(terms[i]);
        for (int j = 0; j < static_cast<int>(terms.size()); ++j) {
            const Bounds3 other = TermSupportBounds(terms[j]);
            bool overlap = own.lo.x <= other.hi.x && other.lo.x <= own.hi.x &&
                           own.lo.y <= other.hi.y && other.lo.y <= own.hi.y &&
                           own.lo.z <= other.hi.z && other.lo.z <= own.hi.z;
            if (j != i && overlap) expected.push_back(j);
        }
        EXPECT_EQ(patches[next++].Members(), expected) << "term " << i;
        EXPECT_EQ(lazy.Members(i), expected) << "term " << i;
    }
    EXPECT_EQ(next, patches.size());
}

// Supports far apart (1e64) put the neighbour grid's cell coordinates beyond every
// integer type; they are clamped (under UBSan an unclamped conversion fails this test),
// and overlapping supports out there still find each other.
TEST(Patch, AutomaticNeighboursAtAbsurdCoordinates) {
    std::vector<FieldTerm> terms{Point("near", {0, 0, 0}), Point("far", {1e64, 0, 0}),
                                 Point("far2", {1e64, 1, 0}), Point("farther", {8.9e64, 0, 0})};
    std::vector<Patch> patches = BuildPatches(Field(terms), BlendMode::Automatic);
    ASSERT_EQ(patches.size(), 4u);
    EXPECT_EQ(patches[0].Members(), (std::vector<int>{0}));
    EXPECT_EQ(patches[1].Members(), (std::vector<int>{1, 2}));
    EXPECT_EQ(patches[2].Members(), (std::vector<int>{2, 1}));
    EXPECT_EQ(patches[3].Members(), (std::vector<int>{3}));
}

// MayHoldRoot is false only for ray pieces where the own term is 0 at every sampled point
// (so no root can be accepted there), and it passes most pieces that enter the support;
// for a point's ball and a segment's capsule.
TEST(Patch, MayHoldRootFalseOnlyWhereTheOwnTermVanishes) {
    const Kernel kernel = Kernel::GascuelQuadratic(0.5, 2, 1.5);
    for (const Skeleton& own : {Skeleton{PointSkeleton{{0.2, -0.1, 0.3}}},
                                Skeleton{SegmentSkeleton{{-0.7, 0.4, 0.1}, {0.9, -0.2, 0.6}}}}) {
        Rng rng(3);
        std::vector<FieldTerm> terms{{"a", own, kernel, 1}, Point("b", {1, 0, 0})};
        std::vector<Patch> patches = BuildPatches(Field(terms), BlendMode::Automatic);
        const Patch& patch = patches[0];
        int skipped = 0, entering = 0;
        for (int i = 0; i < 20000; ++i) {
            Ray ray{testing::RandomPoint(rng, -4, 4),
                    testing::RandomUnit(rng) * testing::Uniform(rng, 0.1, 3)};
            const double tMin = testing::Uniform(rng, -2, 2);
            const double tMax = tMin + testing::Uniform(rng, 0, 6);
            bool ownSomewhere = false;
            for (int k = 0; k <= 2000 && !ownSomewhere; ++k) {
                const Vec3 p = ray.At(tMin + (tMax - tMin) * k / 2000);
                ownSomewhere = patch.GetField().TermValue(patch.Own(), p) > 0;
            }
            if (!patch.MayHoldRoot(ray, tMin, tMax)) {
                ++skipped;
                ASSERT_FALSE(ownSomewhere) << "ray " << i;
            } else if (ownSomewhere) {
                ++entering;
            }
        }
        EXPECT_GT(skipped, 3000);
        EXPECT_GT(entering, 1000);
    }
    // Grazing a point's ball: rays passing its surface at R(1 ± 1e-3) on either side.
    const Vec3 c{0.2, -0.1, 0.3};
    std::vector<Patch> patches = BuildPatches(Field({Point("a", c)}), BlendMode::Automatic);
    const double radius = Point("a", c).kernel.Radius();
    for (double f : {1 - 1e-3, 1 + 1e-3}) {
        Ray ray{c + Vec3{-5, radius * f, 0}, {1, 0, 0}};
        EXPECT_EQ(patches[0].MayHoldRoot(ray, 0, 10), f < 1) << f;
        EXPECT_FALSE(patches[0].MayHoldRoot(ray, 6, 10));  // the chord lies near t = 5
    }
    // Grazing a segment's capsule from the side, parallel and crossing its axis.
    std::vector<Patch> capsule = BuildPatches(
        Field({{"s", SegmentSkeleton{{0, 0, 0}, {2, 0, 0}}, Point("x", c).kernel, 1}}),
        BlendMode::Automatic);
    for (double f : {1 - 1e-3, 1 + 1e-3}) {
        Ray along{{-5, radius * f, 0}, {1, 0, 0}}, across{{1, -5, radius * f}, {0, 1, 0}};
        EXPECT_EQ(capsule[0].MayHoldRoot(along, 0, 20), f < 1) << f;
        EXPECT_EQ(capsule[0].MayHoldRoot(across, 0, 20), f < 1) << f;
    }
}

// A static point patch's support ball answers exactly as MayHoldRoot, on random rays and
// on rays grazing the ball's enlarged radius; other skeletons have no ball.
TEST(Patch, StaticSupportBallAnswersAsMayHoldRoot) {
    const Vec3 c{0.2, -0.1, 0.3};
    std::vector<Patch> patches =
        BuildPatches(Field({Point("a", c), Point("b", {1, 0, 0})}), BlendMode::Automatic);
    const std::optional<Patch::SupportBall> ball = patches[0].StaticSupportBall();
    ASSERT_TRUE(ball.has_value());
    const double radius = Point("a", c).kernel.Radius();
    Rng rng(11);
    int passed = 0;
    for (int i = 0; i < 20000; ++i) {
        Ray ray{testing::RandomPoint(rng, -4, 4),
                testing::RandomUnit(rng) * testing::Uniform(rng, 0.1, 3)};
        if (i % 4 == 0) {
            // Aimed at the ball's rim: closest approach within 1e-5 of R(1 + margin).
            const Vec3 d = testing::RandomUnit(rng);
            Vec3 side = Normalize(Cross(d, testing::RandomUnit(rng)));
            const double miss = radius * (1 + Patch::kSupportMargin) * (1 + testing::Uniform(rng, -1e-5, 1e-5));
            ray = Ray{c + side * miss - d * 5, d};
        }
        const double tMin = testing::Uniform(rng, -2, 2);
        const double tMax = tMin + testing::Uniform(rng, 0, 8);
        const bool expected = patches[0].MayHoldRoot(ray, tMin, tMax);
        ASSERT_EQ(ball->MayMeet(ray, tMin, tMax), expected) << "ray " << i;
        passed += expected;
    }
    EXPECT_GT(passed, 1000);  // both answers occur
    EXPECT_LT(passed, 19000);
    std::vector<Patch> capsule = BuildPatches(
        Field({{"s", SegmentSkeleton{{0, 0, 0}, {2, 0, 0}}, Point("x", c).kernel, 1}}),
        BlendMode::Automatic);
    EXPECT_FALSE(capsule[0].StaticSupportBall().has_value());
}

// ClipToOwnRegion keeps every sampled point of the ray's piece where the own term is
// positive and may predominate (the seam rule at a tolerance-sized uncertainty), the
// points where a root may be accepted, and cuts most of the rest;
// a neighbour of another weight cuts nothing.
TEST(Patch, ClipToOwnRegionKeepsWhereTheOwnTermMayPredominate) {
    Rng rng(5);
    std::vector<FieldTerm> terms{Point("a", {0, 0, 0}), Point("b", {0.6, 0, 0}),
                                 Point("c", {-0.3, 0.5, 0.1}), Point("d", {0.1, -0.4, -0.5}),
                                 Point("e", {0.2, 0.3, 0.6}, 0.7)};
    std::vector<Patch> patches = BuildPatches(Field(terms), BlendMode::Automatic);
    const Patch& patch = patches[0];
    ASSERT_EQ(patch.Members().size(), 5u);
    const double uncertainty = 1e-6;
    double kept = 0, whole = 0;
    for (int i = 0; i < 5000; ++i) {
        Ray ray{testing::RandomPoint(rng, -3, 3),
                testing::RandomUnit(rng) * testing::Uniform(rng, 0.2, 2)};
        double b0 = 0, b1 = 10;
        if (!patch.Box().ClipRay(ray, b0, b1)) continue;
        double t0 = 0, t1 = 10;
        const bool some = patch.ClipToOwnRegion(ray, uncertainty, t0, t1);
        whole += b1 - b0;
        if (some) kept += t1 - t0;
        for (int k = 0; k <= 1000; ++k) {
            const double t = b0 + (b1 - b0) * k / 1000;
            // Roots need the own term positive (F = T > 0 and it is the largest).
            const Vec3 p = ray.At(t);
            if (!(patch.GetField().TermValue(patch.Own(), p) > 0) ||
                !patch.PredominatesNear(p, uncertainty)) {
                continue;
            }
            ASSERT_TRUE(some && t >= t0 && t <= t1) << "ray " << i << " t " << t;
        }
    }
    EXPECT_LT(kept, 0.5 * whole);
    // Along the axis of a and b: the piece ends near their bisector x = 0.3: the cut is
    // d_a² − d_b² <= δ(2R + δ), i.e. x <= 0.3 + δ(2R + δ)/1.2 with δ = 10⁻³R plus the
    // uncertainty; the box starts at x = −R. The neighbour of weight 0.7 alone cuts
    // nothing.
    const double radius = terms[0].kernel.Radius();
    const double delta = 1e-3 * radius + uncertainty;
    Ray axis{{-5, 0, 0}, {1, 0, 0}};
    std::vector<Patch> pair = BuildPatches(Field({terms[0], terms[1]}), BlendMode::Automatic);
    double t0 = 0, t1 = 20;
    ASSERT_TRUE(pair[0].ClipToOwnRegion(axis, uncertainty, t0, t1));
    EXPECT_NEAR(t0, 5 - radius, 1e-12);
    EXPECT_NEAR(t1, 5.3 + delta * (2 * radius + delta) / 1.2, 1e-6);
    std::vector<Patch> lone = BuildPatches(Field({terms[0], terms[4]}), BlendMode::Automatic);
    t0 = 0, t1 = 20;
    ASSERT_TRUE(lone[0].ClipToOwnRegion(axis, uncertainty, t0, t1));
    EXPECT_NEAR(t0, 5 - radius, 1e-12);
    EXPECT_NEAR(t1, 5 + radius, 1e-12);
}

// The largest |p − c| over sampled points p of the patch's own solid (the patch field at
// least `threshold` where the own term predominates), c its point skeleton: along `rays`
// random directions and the six axis directions from c, 400 steps to R.
double LargestOwnSolidRadius(const Patch& patch, double threshold, Rng& rng, int rays) {
    const FieldTerm& own = patch.GetField().Terms()[patch.Own()];
    const Vec3 c = std::get<PointSkeleton>(own.skeleton).center;
    const double radius = own.kernel.Radius();
    double largest = 0;
    for (int i = 0; i < rays + 6; ++i) {
        Vec3 u{0, 0, 0};
        if (i < 6) {
            u[i / 2] = i % 2 ? -1 : 1;
        } else {
            u = testing::RandomUnit(rng);
        }
        for (int k = 1; k <= 400; ++k) {
            const double r = radius * k / 400;
            const Vec3 p = c + u * r;
            if (patch.Predominates(p) && patch.GetField().Value(p) >= threshold) {
                largest = std::max(largest, r);
            }
        }
    }
    return largest;
}

// LimitToSurface's ball holds the own solid of every patch of random small fluids (points
// of two kernels, a negative term and a segment among them), against dense sampling.
TEST(Patch, SurfaceReachHoldsTheOwnSolid) {
    Rng rng(19);
    const Kernel linear = Kernel::GascuelLinear(0.45, 2, 1), blob = Kernel::Blob(1, 1);
    int bounded = 0;
    double reachSum = 0;
    for (int fluid = 0; fluid < 12; ++fluid) {
        const bool isBlob = fluid % 2;
        const double threshold = isBlob ? 0.6 : 1;
        std::vector<FieldTerm> terms;
        const double spread = testing::Uniform(rng, 0.6, 1.6);
        for (int i = 0; i < 8; ++i) {
            terms.push_back({std::string(1, static_cast<char>('a' + i)),
                             PointSkeleton{testing::RandomPoint(rng, -spread, spread)},
                             isBlob ? blob : linear, testing::Uniform(rng, 0.7, 1.3)});
        }
        if (fluid % 3 == 0) terms[3].weight = -0.5;
        if (fluid % 4 == 1) {
            terms.push_back({"s", SegmentSkeleton{{-0.5, 0, 0}, {0.5, 0.2, 0}}, terms[0].kernel, 1});
        }
        std::vector<Patch> patches = BuildPatches(Field(terms), BlendMode::Automatic);
        for (Patch& patch : patches) {
            if (!std::holds_alternative<PointSkeleton>(
                    patch.GetField().Terms()[patch.Own()].skeleton)) {
                continue;
            }
            patch.LimitToSurface(threshold);
            const double reach = patch.SurfaceReach();
            ASSERT_LE(reach, patch.GetField().Terms()[patch.Own()].kernel.Radius());
            EXPECT_LE(LargestOwnSolidRadius(patch, threshold, rng, 300), reach)
                << "fluid " << fluid << " patch " << patch.Own();
            ++bounded;
            reachSum += reach;
        }
    }
    EXPECT_GT(bounded, 80);
    EXPECT_LT(reachSum, 0.95 * bounded);  // it bounds something: below R = 1 on average
}

// Where the bound is attained the reach is the solid's radius (within 1 %, so the test
// above fails for a reach 5 % smaller): a lone point (its lone surface, f(r) = T), and a
// pair at distance 2ρ with 2·f(ρ) = T, whose lower-index patch reaches the tie point
// midway, where both terms equal f(ρ).
TEST(Patch, SurfaceReachIsTightWhereTheBoundIsAttained) {
    Rng rng(7);
    const Kernel linear = Kernel::GascuelLinear(0.45, 2, 1);
    const double threshold = 1;
    std::vector<Patch> lone =
        BuildPatches(Field({{"a", PointSkeleton{{0, 0, 0}}, linear, 1}}), BlendMode::Automatic);
    lone[0].LimitToSurface(threshold);
    EXPECT_NEAR(lone[0].SurfaceReach(), 0.45, 1e-4);
    EXPECT_GT(LargestOwnSolidRadius(lone[0], threshold, rng, 50), 0.99 * lone[0].SurfaceReach());
    // f(ρ) = 1/2 on the linear kernel's outer piece: find ρ by bisection.
    double lo = 0.45, hi = 1;
    for (int i = 0; i < 60; ++i) ((linear.Value(0.5 * (lo + hi)) > 0.5) ? lo : hi) = 0.5 * (lo + hi);
    const double rho = 0.5 * (lo + hi);
    std::vector<Patch> pair =
        BuildPatches(Field({{"a", PointSkeleton{{0, 0, 0}}, linear, 1},
                            {"b", PointSkeleton{{2 * rho, 0, 0}}, linear, 1}}),
                     BlendMode::Automatic);
    pair[0].LimitToSurface(threshold);
    EXPECT_NEAR(pair[0].SurfaceReach(), rho, 1e-4);
    EXPECT_GT(LargestOwnSolidRadius(pair[0], threshold, rng, 50), 0.99 * pair[0].SurfaceReach());
}

// After LimitToSurface, ClipToOwnRegion also cuts to the reach ball (grown by the margin).
TEST(Patch, ClipToOwnRegionCutsToTheSurfaceReach) {
    const Kernel linear = Kernel::GascuelLinear(0.45, 2, 1);
    std::vector<Patch> lone =
        BuildPatches(Field({{"a", PointSkeleton{{0, 0, 0}}, linear, 1}}), BlendMode::Automatic);
    lone[0].LimitToSurface(1);
    const double uncertainty = 1e-6, reach = lone[0].SurfaceReach();
    const double margin = 1e-3 + uncertainty;
    Ray axis{{-5, 0, 0}, {1, 0, 0}};
    double t0 = 0, t1 = 20;
    ASSERT_TRUE(lone[0].ClipToOwnRegion(axis, uncertainty, t0, t1));
    EXPECT_NEAR(t0, 5 - reach - margin, 1e-7);
    EXPECT_NEAR(t1, 5 + reach + margin, 1e-7);
    Ray past{{-5, reach + 2 * margin, 0}, {1, 0, 0}};
    t0 = 0, t1 = 20;
    EXPECT_FALSE(lone[0].ClipToOwnRegion(past, uncertainty, t0, t1));
}

}  // namespace
}  // namespace rs
