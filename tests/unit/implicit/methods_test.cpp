// The baseline intersection methods (march, sphere, segment, polynomial, exact) against
// analytic surfaces: a lone point skeleton is a sphere of radius e (Gascuel kernels) or
// R·sqrt(1 − sqrt(T/s)) (blob kernel), a lone segment a capsule of radius e, a lone solid
// box, cylinder, triangle or circle the set at distance e from it. Property tests are seeded
// and print the seed and the ray on failure.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "libcommon/random.h"
#include "libobj/implicit/exact_method.h"
#include "libobj/implicit/march_method.h"
#include "libobj/implicit/method_registry.h"
#include "libobj/implicit/polynomial_method.h"
#include "libobj/implicit/sphere_method.h"
#include "test_util.h"

namespace rs {
namespace {

using rs::testing::RandomUnit;
using rs::testing::Uniform;

constexpr uint64_t kSeed = 20261122;

std::unique_ptr<IntersectionMethod> Make(ImplicitMethod method, const Field& field,
                                         double tolerance, double threshold = 1,
                                         double step = 0) {
    static const ImplicitObjectStats stats;
    ImplicitOptions options;
    options.threshold = threshold;
    options.search.tolerance = tolerance;
    options.marchStep = step;
    return MethodEntryOf(method).create(field, options, stats);
}

Field OnePoint(const Kernel& kernel, Vec3 c = {0, 0, 0}) {
    return Field({{"p", PointSkeleton{c}, kernel, 1}});
}

// The entry (or, from inside, exit) of a unit-direction ray into the sphere (c, r), or
// nothing when |b| >= r.
std::optional<double> SphereRoot(const Vec3& o, const Vec3& d, const Vec3& c, double r) {
    Vec3 q = o - c;
    double b = Dot(q, d);
    Vec3 perp = q - d * b;
    double h2 = r * r - LengthSquared(perp);
    if (h2 <= 0) return std::nullopt;
    double h = std::sqrt(h2);
    double tNear = -b - h, tFar = -b + h;
    if (tNear > 0) return tNear;
    if (tFar > 0) return tFar;
    return std::nullopt;
}

// A ray from distance `dist` of the centre with impact parameter b·r (b in [0, bMax]).
Ray RandomRay(Rng& rng, const Vec3& c, double r, double dist, double bMax) {
    Vec3 axis = RandomUnit(rng);
    Vec3 side = Normalize(Cross(axis, RandomUnit(rng)));
    double b = Uniform(rng, 0, bMax) * r;
    Vec3 o = c + axis * dist + side * b;
    return Ray{o, -axis};
}

const ImplicitMethod kBaselines[] = {ImplicitMethod::March, ImplicitMethod::Sphere,
                                     ImplicitMethod::Segment, ImplicitMethod::Exact};

// Every method's tolerance bounds the error of non-grazing hits (impact parameter below
// 0.95·r), from outside and from inside the sphere.
TEST(ImplicitMethods, PointSkeletonSphereWithinTolerance) {
    const double e = 0.8;
    Field field = OnePoint(Kernel::GascuelQuadratic(e, 1, 2));
    for (ImplicitMethod m : kBaselines) {
        for (double tol : {1e-3, 1e-6, 1e-9}) {
            auto method = Make(m, field, tol);
            Rng rng(kSeed);
            for (int i = 0; i < 200; ++i) {
                bool inside = i % 4 == 3;
                Ray ray = RandomRay(rng, {0, 0, 0}, e, inside ? 0.3 : 5, 0.95);
                std::optional<double> expect = SphereRoot(ray.origin, ray.dir, {0, 0, 0}, e);
                ASSERT_TRUE(expect);
                std::optional<double> got = method->FirstRoot(ray, 0, 1e9);
                ASSERT_TRUE(got) << ImplicitMethodName(m) << " tol " << tol << " seed " << kSeed
                                 << " ray " << i;
                double allowed = m == ImplicitMethod::Exact ? 1e-12 * *expect : tol * (1 + 1e-6);
                EXPECT_LE(std::abs(*got - *expect), allowed + 1e-15)
                    << ImplicitMethodName(m) << " tol " << tol << " seed " << kSeed << " ray " << i;
            }
        }
    }
}

// Rays passing outside by a margin miss with every method (no false hits).
TEST(ImplicitMethods, RaysOutsideMiss) {
    const double e = 0.8;
    Field field = OnePoint(Kernel::GascuelLinear(e, 1, 2));
    for (ImplicitMethod m : kBaselines) {
        auto method = Make(m, field, 1e-6);
        Rng rng(kSeed + 1);
        for (int i = 0; i < 100; ++i) {
            Vec3 axis = RandomUnit(rng);
            Vec3 side = Normalize(Cross(axis, RandomUnit(rng)));
            double b = e * Uniform(rng, 1.001, 3);
            Ray ray{axis * 5 + side * b, -axis};
            EXPECT_FALSE(method->FirstRoot(ray, 0, 1e9))
                << ImplicitMethodName(m) << " seed " << kSeed + 1 << " ray " << i;
        }
    }
}

TEST(ImplicitMethods, SegmentSkeletonCapsule) {
    const double e = 0.5;
    const Vec3 a{-1, 0, 0}, b{1, 0, 0};
    Field field({{"s", SegmentSkeleton{a, b}, Kernel::GascuelQuadratic(e, 1.5, 1.5), 1}});
    for (ImplicitMethod m : kBaselines) {
        const double tol = 1e-7;
        auto method = Make(m, field, tol);
        Rng rng(kSeed + 2);
        for (int i = 0; i < 100; ++i) {
            // Perpendicular to the axis through the cylindrical part: entry at
            // 4 − sqrt(e² − h²) for a ray at height h above the axis.
            double x = Uniform(rng, -0.9, 0.9), h = Uniform(rng, -0.9, 0.9) * e;
            double angle = Uniform(rng, 0, 6.283185307179586);
            Vec3 dir{0, std::cos(angle), std::sin(angle)};
            Vec3 up{0, -std::sin(angle), std::cos(angle)};
            Ray ray{Vec3{x, 0, 0} - dir * 4 + up * h, dir};
            double expect = 4 - std::sqrt(e * e - h * h);
            std::optional<double> got = method->FirstRoot(ray, 0, 1e9);
            ASSERT_TRUE(got) << ImplicitMethodName(m) << " seed " << kSeed + 2 << " ray " << i;
            double allowed = m == ImplicitMethod::Exact ? 1e-12 * expect : tol;
            EXPECT_LE(std::abs(*got - expect), allowed + 1e-15)
                << ImplicitMethodName(m) << " seed " << kSeed + 2 << " ray " << i;
        }
        // Along the axis: the cap at x = −1 − e.
        std::optional<double> got = method->FirstRoot(Ray{{-5, 0, 0}, {1, 0, 0}}, 0, 1e9);
        ASSERT_TRUE(got) << ImplicitMethodName(m);
        EXPECT_NEAR(*got, 4 - e, m == ImplicitMethod::Exact ? 1e-12 : tol);
    }
}

// Blob kernel s(1 − r²/R²)²: a lone point is a sphere of radius R·sqrt(1 − sqrt(T/s)).
TEST(ImplicitMethods, BlobSphereAllMethodsIncludingPolynomial) {
    const double s = 2, radius = 1.5, threshold = 0.5;
    const double r = radius * std::sqrt(1 - std::sqrt(threshold / s));
    const Vec3 c{0.3, -0.2, 0.1};
    Field field = OnePoint(Kernel::Blob(s, radius), c);
    EXPECT_TRUE(CheckPolynomialTerms(field.Terms()).empty());
    const ImplicitMethod methods[] = {ImplicitMethod::March, ImplicitMethod::Sphere,
                                      ImplicitMethod::Segment, ImplicitMethod::Polynomial,
                                      ImplicitMethod::Exact};
    for (ImplicitMethod m : methods) {
        const double tol = 1e-8;
        auto method = Make(m, field, tol, threshold);
        Rng rng(kSeed + 3);
        for (int i = 0; i < 200; ++i) {
            Ray ray = RandomRay(rng, c, r, i % 5 == 4 ? 0.2 : 4, 0.95);
            std::optional<double> expect = SphereRoot(ray.origin, ray.dir, c, r);
            ASSERT_TRUE(expect);
            std::optional<double> got = method->FirstRoot(ray, 0, 1e9);
            ASSERT_TRUE(got) << ImplicitMethodName(m) << " seed " << kSeed + 3 << " ray " << i;
            double allowed = m == ImplicitMethod::Exact        ? 1e-12 * *expect
                             : m == ImplicitMethod::Polynomial ? 1e-10
                                                               : tol;
            EXPECT_LE(std::abs(*got - *expect), allowed + 1e-15)
                << ImplicitMethodName(m) << " seed " << kSeed + 3 << " ray " << i;
        }
    }
}

// Far cameras: the polynomial method forms its quartic at the interval start (no loss).
TEST(ImplicitMethods, PolynomialFarCamera) {
    const double s = 1, radius = 1, threshold = 0.5;
    const double r = radius * std::sqrt(1 - std::sqrt(threshold / s));
    Field field = OnePoint(Kernel::Blob(s, radius));
    auto method = Make(ImplicitMethod::Polynomial, field, 1e-7, threshold);
    for (double dist : {1e2, 1e4, 1e6}) {
        const double b = 0.3;
        std::optional<double> got = method->FirstRoot(Ray{{-dist, b, 0}, {1, 0, 0}}, 0, 1e12);
        ASSERT_TRUE(got) << dist;
        EXPECT_NEAR(*got, dist - std::sqrt(r * r - b * b), 4 * dist * 2.2e-16) << dist;
    }
}

TEST(ImplicitMethods, PolynomialRejectsOtherKernelsAndSkeletons) {
    std::vector<FieldTerm> gascuel = {{"g", PointSkeleton{}, Kernel::GascuelQuadratic(1, 1, 2), 1}};
    std::vector<FieldTerm> triangle = {{"t", TriangleSkeleton{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}},
                                        Kernel::Blob(1, 1), 1}};
    std::vector<FieldTerm> segment = {{"s", SegmentSkeleton{{0, 0, 0}, {1, 0, 0}},
                                       Kernel::Blob(1, 1), 1}};
    EXPECT_NE(CheckPolynomialTerms(gascuel).find("'g'"), std::string::npos);
    EXPECT_NE(CheckPolynomialTerms(triangle).find("'t' is a triangle"), std::string::npos);
    EXPECT_EQ(CheckPolynomialTerms(segment), "");  // a capsule: piecewise quartic too
    EXPECT_EQ(MethodEntryOf(ImplicitMethod::Polynomial).check(gascuel),
              CheckPolynomialTerms(gascuel));
}

TEST(ImplicitMethods, RegistryNamesRoundTrip) {
    for (const MethodEntry& e : MethodRegistry()) {
        ImplicitMethod m;
        ASSERT_TRUE(ParseImplicitMethod(e.name, m)) << e.name;
        EXPECT_EQ(m, e.method);
        EXPECT_STREQ(ImplicitMethodName(m), e.name);
        // No factory: only auto (a rule resolving to another method).
        EXPECT_EQ(e.create == nullptr, m == ImplicitMethod::Auto) << e.name;
        // The method run while moving has a factory and is its own method while moving.
        const MethodEntry& moving = MethodEntryOf(e.whenMoving);
        EXPECT_EQ(moving.create == nullptr, m == ImplicitMethod::Auto) << e.name;
        EXPECT_EQ(moving.whenMoving, moving.method) << e.name;
    }
    EXPECT_EQ(MethodEntryOf(ImplicitMethod::Polynomial).whenMoving, ImplicitMethod::Kb89);
    ImplicitMethod m;
    EXPECT_FALSE(ParseImplicitMethod("bisection", m));
    EXPECT_EQ(ImplicitMethodNames(),
              "patches, kb89, march, sphere, segment, polynomial, exact, auto");
}

// Auto runs polynomial exactly when it searches the surface patches would: every term a
// blob-kernel point or segment and no blend or contact statements.
TEST(ImplicitMethods, AutoIsPolynomialOnlyForBlobPointsAndSegmentsThatAllBlend) {
    const std::vector<FieldTerm> blobs{{"a", PointSkeleton{{0, 0, 0}}, Kernel::Blob(1, 1), 1},
                                       {"b", PointSkeleton{{1, 0, 0}}, Kernel::Blob(1, 1), -1}};
    EXPECT_EQ(ResolveAutoMethod(blobs, false), ImplicitMethod::Polynomial);
    EXPECT_EQ(ResolveAutoMethod(blobs, true), ImplicitMethod::Patches);
    std::vector<FieldTerm> withSegment = blobs;
    withSegment.push_back({"s", SegmentSkeleton{{0, 0, 0}, {1, 0, 0}}, Kernel::Blob(1, 1), 1});
    EXPECT_EQ(ResolveAutoMethod(withSegment, false), ImplicitMethod::Polynomial);
    std::vector<FieldTerm> withCircle = blobs;
    withCircle.push_back(
        {"c", CircleSkeleton{{0, 0, 0}, {0, 0, 1}, 1}, Kernel::Blob(1, 1), 1});
    EXPECT_EQ(ResolveAutoMethod(withCircle, false), ImplicitMethod::Patches);
    std::vector<FieldTerm> withGascuel = blobs;
    withGascuel.push_back({"g", PointSkeleton{{0, 0, 0}}, Kernel::GascuelQuadratic(0.5, 2, 1.2), 1});
    EXPECT_EQ(ResolveAutoMethod(withGascuel, false), ImplicitMethod::Patches);
}

// The exact solver reports the double root of a ray tangent to the sphere (|b| = e exactly
// in binary: e = 0.75), at the tangent point.
TEST(ImplicitMethods, ExactFindsTangency) {
    const double e = 0.75;
    Field field = OnePoint(Kernel::GascuelQuadratic(e, 1, 2));
    auto exact = Make(ImplicitMethod::Exact, field, 1e-7);
    for (const Ray& ray : {Ray{{-5, e, 0}, {1, 0, 0}}, Ray{{0, -4, -e}, {0, 2, 0}}}) {
        std::optional<double> got = exact->FirstRoot(ray, 0, 1e9);
        ASSERT_TRUE(got);
        Vec3 p = ray.At(*got);
        // The tangent point is (0, e, 0) or (0, 0, −e); τ ≈ 3e-17 locates it to ~1e-8.
        EXPECT_LT(Length(p - Vec3{0, ray.origin.y == e ? e : 0, ray.origin.z}), 1e-6);
    }
    // Outside by one part in 1e12: no root.
    EXPECT_FALSE(exact->FirstRoot(Ray{{-5, e * (1 + 1e-12), 0}, {1, 0, 0}}, 0, 1e9));
}

// Grazing just inside (a chord far longer than the tolerance): the bound-based methods and
// the exact solver hit, within tolerance of the analytic entry.
TEST(ImplicitMethods, GrazingInsideHitsWithBoundMethods) {
    const double e = 0.8, tol = 1e-9;
    Field field = OnePoint(Kernel::GascuelQuadratic(e, 1, 2));
    for (ImplicitMethod m :
         {ImplicitMethod::Sphere, ImplicitMethod::Segment, ImplicitMethod::Exact}) {
        auto method = Make(m, field, tol);
        for (double rel : {1e-2, 1e-4, 1e-6}) {
            const double b = e * (1 - rel);
            std::optional<double> got = method->FirstRoot(Ray{{-5, b, 0}, {1, 0, 0}}, 0, 1e9);
            ASSERT_TRUE(got) << ImplicitMethodName(m) << " rel " << rel;
            const double allowed = m == ImplicitMethod::Exact ? 1e-12 : tol;
            EXPECT_NEAR(*got, 5 - std::sqrt(e * e - b * b), allowed)
                << ImplicitMethodName(m) << " rel " << rel;
        }
    }
}

// Grazing the concave crease of an L-shaped polyline, where the field's G is infinite (two
// segments equally near) and the exact solver prunes by its enclosures only. In the plane
// x = −y the distance to both segments is sqrt(s² + z²) for the point (−s, s, z), s in
// (0, 2), so the ray (−s0, s0, z0) + t(−1, 1, −1) meets d = e where
// 2t² + 2(s0 − z0)t + s0² + z0² − e² = 0, i.e. t = (z0 − s0 − sqrt(2e² − (s0 + z0)²))/2
// (evaluated in long double; s0 + z0 is exact there). Inside by 1e-6 to 1e-14 relative:
// a hit to 1e-12 relative; outside by 1e-10: a miss.
TEST(ImplicitMethods, ExactGrazingAPolylineCrease) {
    const double e = 0.5;
    PolylineSkeleton corner;
    corner.points = {{-2, 0, 0}, {0, 0, 0}, {0, 2, 0}};
    Field field({{"l", corner, Kernel::GascuelQuadratic(e, 1, 1.5), 1}});
    auto exact = Make(ImplicitMethod::Exact, field, 1e-7);
    for (double rel : {1e-6, 1e-9, 1e-12, 1e-14, -1e-10}) {
        const double c = std::sqrt(2.0) * e * (1 - rel);
        const double s0 = c / 2 - 3, z0 = c - s0;
        const Ray ray{{-s0, s0, z0}, {-1, 1, -1}};
        std::optional<double> got = exact->FirstRoot(ray, 0, 1e9);
        const long double sum = static_cast<long double>(s0) + z0;
        const long double disc = 2.0L * e * e - sum * sum;
        if (rel < 0) {
            ASSERT_LT(disc, 0);
            EXPECT_FALSE(got) << rel;
            continue;
        }
        ASSERT_GT(disc, 0) << rel;
        ASSERT_TRUE(got) << rel;
        const double expect =
            static_cast<double>((static_cast<long double>(z0) - s0 - std::sqrt(disc)) / 2);
        EXPECT_NEAR(*got, expect, 1e-12 * expect) << rel;
    }
}

// The march step is the method's knob: a sphere of diameter 0.1 between two samples is
// missed with a step of 0.5 and hit with a step of 0.01 (the documented non-guarantee).
TEST(ImplicitMethods, MarchStepSkipsThinFeatures) {
    Field field = OnePoint(Kernel::GascuelQuadratic(0.05, 1, 0.1));
    Ray ray{{-3, 0, 0}, {1, 0, 0}};
    EXPECT_FALSE(Make(ImplicitMethod::March, field, 1e-9, 1, 0.5)->FirstRoot(ray, 0, 1e9));
    std::optional<double> got =
        Make(ImplicitMethod::March, field, 1e-9, 1, 0.01)->FirstRoot(ray, 0, 1e9);
    ASSERT_TRUE(got);
    EXPECT_NEAR(*got, 2.95, 1e-9);
    EXPECT_DOUBLE_EQ(DefaultMarchStep(field), 0.25 * 0.05);
    EXPECT_DOUBLE_EQ(DefaultMarchStep(OnePoint(Kernel::Blob(1, 2))), 0.25);
    MethodParams params;
    MarchMethod byDefault(field, params);
    EXPECT_DOUBLE_EQ(byDefault.Step(), 0.25 * 0.05);
}

// Sphere tracing's one global bound is at least the kernel's steepest slope: for the
// quadratic kernel with m = k(R − e) = 1 < 1.5 the outer slope peaks at
// (3 − m)²/(3(2 − m)ℓ) = 4/3 (kernel.h), above k = 1.
TEST(ImplicitMethods, SphereUsesGlobalLipschitzBound) {
    Field one = OnePoint(Kernel::GascuelQuadratic(1, 1, 2));
    MethodParams params;
    SphereMethod sphere(one, params);
    EXPECT_GE(sphere.Lipschitz(), 4.0 / 3.0 - 1e-12);
    Field two({{"a", PointSkeleton{{0, 0, 0}}, Kernel::GascuelQuadratic(1, 1, 2), 1},
               {"b", PointSkeleton{{10, 0, 0}}, Kernel::GascuelQuadratic(1, 1, 2), 1}});
    SphereMethod sum(two, params);
    EXPECT_GE(sum.Lipschitz(), 2 * (4.0 / 3.0) - 1e-12);  // the sum of the terms' slopes
}

// The exact solver's splitting for the other skeleton kinds, each alone: the surface is the
// set at distance e from the skeleton.
TEST(ImplicitMethods, ExactOtherSkeletonKinds) {
    const double e = 0.8;
    const Kernel k = Kernel::GascuelQuadratic(e, 1, 2);
    struct Case {
        const char* what;
        Skeleton skeleton;
        Ray ray;
        double expect;
    };
    PolylineSkeleton corner;
    corner.points = {{-2, 1, 0}, {0, 0, 0}, {1, 2, 0}};
    const double circleZ = std::sqrt(e * e - 0.5 * 0.5);
    const Case cases[] = {
        {"box face", BoxSkeleton{{-1, -1, -1}, {1, 1, 1}}, Ray{{-5, 0.3, 0.2}, {1, 0, 0}}, 4 - e},
        {"box edge", BoxSkeleton{{-1, -1, -1}, {1, 1, 1}},
         Ray{{-5, 1.5, 0}, {1, 0, 0}}, 4 - std::sqrt(e * e - 0.25)},
        {"cylinder side", CylinderSkeleton{{0, 0, -1}, {0, 0, 1}, 0.5},
         Ray{{0, -5, 0.3}, {0, 1, 0}}, 5 - 0.5 - e},
        {"cylinder cap", CylinderSkeleton{{0, 0, -1}, {0, 0, 1}, 0.5},
         Ray{{0.2, 0.1, 5}, {0, 0, -1}}, 4 - e},
        {"triangle", TriangleSkeleton{{-1, -1, 0}, {1, -1, 0}, {0, 1, 0}},
         Ray{{0, -0.2, 3}, {0, 0, -1}}, 3 - e},
        {"circle axis", CircleSkeleton{{0, 0, 0}, {0, 0, 1}, 0.5}, Ray{{0, 0, 3}, {0, 0, -1}},
         3 - circleZ},
        {"circle plane", CircleSkeleton{{0, 0, 0}, {0, 0, 1}, 0.5}, Ray{{-4, 0, 0}, {1, 0, 0}},
         4 - 0.5 - e},
        // From −y at x = 0.2 the corner (0, 0, 0) is the nearest point of both segments,
        // so the entry is at distance e from it.
        {"polyline corner", corner, Ray{{0.2, -5, 0}, {0, 1, 0}},
         5 - std::sqrt(e * e - 0.04)},
    };
    for (const Case& c : cases) {
        Field field({{"x", c.skeleton, k, 1}});
        std::optional<double> got =
            Make(ImplicitMethod::Exact, field, 1e-7)->FirstRoot(c.ray, 0, 1e9);
        ASSERT_TRUE(got) << c.what;
        EXPECT_NEAR(*got, c.expect, 1e-12 * c.expect) << c.what;
    }
}

// Negative weights: a positive point with a concentric negative one of smaller support
// carves a hollow ball. Quadratic kernels (e, k, R) = (1, 1, 2) and (0.5, 2, 1) weight −1:
// for r <= 0.5, F = (1.5 − r²/2) − (1.5 − 2r²) = 1.5r², so F = 1 at r = sqrt(2/3) > 0.5;
// for 0.5 < r < 1 the negative term's outer cubic applies. The outer surface is r = 1
// (F(1) = f1(1) = 1, the negative term vanishing at its R = 1). A ray from the centre
// outward leaves the cavity where F rises through 1, below r = 1: compare with bisection
// of the closed form.
TEST(ImplicitMethods, ExactNegativeWeightsCarve) {
    const Kernel outer = Kernel::GascuelQuadratic(1, 1, 2);
    const Kernel inner = Kernel::GascuelQuadratic(0.5, 2, 1);
    Field field({{"pos", PointSkeleton{}, outer, 1}, {"neg", PointSkeleton{}, inner, -1}});
    auto f = [&](double r) { return outer.Value(r) - inner.Value(r) - 1; };
    double lo = 0, hi = 0.999;  // f(0) < 0 (F(0) = 0), f(0.999) > 0
    ASSERT_LT(f(lo), 0);
    ASSERT_GT(f(hi), 0);
    for (int i = 0; i < 200; ++i) {
        double mid = 0.5 * (lo + hi);
        (f(mid) > 0 ? hi : lo) = mid;
    }
    auto exact = Make(ImplicitMethod::Exact, field, 1e-7);
    std::optional<double> got = exact->FirstRoot(Ray{{0, 0, 0}, {0, 1, 0}}, 0, 1e9);
    ASSERT_TRUE(got);
    EXPECT_NEAR(*got, lo, 1e-12);
    // From outside, the outer sphere r = 1.
    got = exact->FirstRoot(Ray{{0, 0, -5}, {0, 0, 1}}, 0, 1e9);
    ASSERT_TRUE(got);
    EXPECT_NEAR(*got, 4, 1e-12);
}

// Every factory of the registry makes a method that finds a lone blob point's sphere,
// radius R·sqrt(1 − sqrt(T/s)) (README.md, kernels): 0.5 for s = 1, R = 1 and
// T = (1 − 0.25)² = 0.5625, to its tolerance, and reports the owning term where it reports
// one (the octree methods through their own trees, built by this first ray).
TEST(ImplicitMethods, EveryFactoryMakesAWorkingMethod) {
    const Field field = OnePoint(Kernel::Blob(1, 1));
    static const ImplicitObjectStats stats;
    for (const MethodEntry& e : MethodRegistry()) {
        if (!e.create) continue;
        ImplicitOptions options;
        options.method = e.method;
        options.threshold = 0.5625;
        if (e.method == ImplicitMethod::Kb89) options.octree = OctreeHeuristics::Kb89();
        ASSERT_TRUE(!e.check || e.check(field.Terms()).empty()) << e.name;
        std::unique_ptr<IntersectionMethod> method = e.create(field, options, stats);
        ASSERT_TRUE(method) << e.name;
        const Ray ray{{0, 0, -5}, {0, 0, 1}};
        std::optional<MethodHit> hit = method->Intersect(ray, 0, 100);
        ASSERT_TRUE(hit.has_value()) << e.name;
        EXPECT_NEAR(hit->t, 4.5, 1e-6) << e.name;
        EXPECT_TRUE(hit->term == 0 || hit->term == -1) << e.name;
        EXPECT_TRUE(method->Bounds(field).Contains(ray.At(hit->t))) << e.name;
        EXPECT_NEAR(method->Normal(field, ray.At(hit->t), hit->term).z, -1, 1e-6) << e.name;
        EXPECT_FALSE(method->Intersect({{0, 2, -5}, {0, 0, 1}}, 0, 100)) << e.name;
    }
}

}  // namespace
}  // namespace rs
