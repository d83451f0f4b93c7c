#include "libgeom/polynomial.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace rs {
namespace {

std::vector<double> Quadratic(double a, double b, double c) {
    double r[2];
    int n = SolveQuadratic(a, b, c, r);
    return {r, r + n};
}
std::vector<double> Cubic(double a, double b, double c, double d) {
    double r[3];
    int n = SolveCubic(a, b, c, d, r);
    return {r, r + n};
}
std::vector<double> Quartic(double a, double b, double c, double d, double e) {
    double r[4];
    int n = SolveQuartic(a, b, c, d, e, r);
    return {r, r + n};
}

// Coefficients (leading first) of Π (x − r_i).
std::vector<double> FromRoots(const std::vector<double>& roots) {
    std::vector<double> c{1};
    for (double r : roots) {
        std::vector<double> next(c.size() + 1, 0);
        for (size_t i = 0; i < c.size(); ++i) {
            next[i] += c[i];
            next[i + 1] -= r * c[i];
        }
        c = next;
    }
    return c;
}

void ExpectRoots(const std::vector<double>& actual, const std::vector<double>& expected,
                 double tol) {
    ASSERT_EQ(actual.size(), expected.size());
    for (size_t i = 0; i < expected.size(); ++i) EXPECT_NEAR(actual[i], expected[i], tol) << i;
}

TEST(Polynomial, QuadraticTwoRoots) { ExpectRoots(Quadratic(1, -3, 2), {1, 2}, 1e-14); }

TEST(Polynomial, QuadraticDoubleRootReportedOnce) {
    ExpectRoots(Quadratic(1, -2, 1), {1}, 1e-14);
}

TEST(Polynomial, QuadraticNoRealRoots) { EXPECT_TRUE(Quadratic(1, 0, 1).empty()); }

TEST(Polynomial, QuadraticWithZeroLeadingIsLinear) {
    ExpectRoots(Quadratic(0, 2, -4), {2}, 1e-15);
}

TEST(Polynomial, QuadraticWidelySpreadRootsKeepPrecision) {
    // Roots 1e-8 and 1e8: the naive formula loses the small one entirely.
    auto r = Quadratic(1, -(1e8 + 1e-8), 1);
    ASSERT_EQ(r.size(), 2u);
    EXPECT_NEAR(r[0], 1e-8, 1e-8 * 1e-12);
    EXPECT_NEAR(r[1], 1e8, 1e8 * 1e-12);
}

TEST(Polynomial, CubicThreeSimpleRoots) {
    auto c = FromRoots({1, 2, 3});
    ExpectRoots(Cubic(c[0], c[1], c[2], c[3]), {1, 2, 3}, 1e-12);
}

TEST(Polynomial, CubicDoubleRoot) {
    auto c = FromRoots({-2, 1, 1});
    ExpectRoots(Cubic(c[0], c[1], c[2], c[3]), {-2, 1}, 1e-7);
}

TEST(Polynomial, CubicTripleRoot) {
    auto c = FromRoots({2, 2, 2});
    ExpectRoots(Cubic(c[0], c[1], c[2], c[3]), {2}, 1e-4);
}

TEST(Polynomial, CubicOneRealRoot) {
    // x³ + x + 1: the real root is −0.6823278038280193 (Cardano).
    ExpectRoots(Cubic(1, 0, 1, 1), {-0.6823278038280193}, 1e-14);
}

TEST(Polynomial, QuarticFourSimpleRoots) {
    auto c = FromRoots({1, 2, 3, 4});
    ExpectRoots(Quartic(c[0], c[1], c[2], c[3], c[4]), {1, 2, 3, 4}, 1e-12);
}

TEST(Polynomial, QuarticTwoDoubleRoots) {
    auto c = FromRoots({1, 1, 3, 3});
    ExpectRoots(Quartic(c[0], c[1], c[2], c[3], c[4]), {1, 3}, 1e-7);
}

TEST(Polynomial, QuarticDoubleAndSimpleRoots) {
    auto c = FromRoots({-0.25, 0.5, 0.5, 7});
    ExpectRoots(Quartic(c[0], c[1], c[2], c[3], c[4]), {-0.25, 0.5, 7}, 1e-7);
}

TEST(Polynomial, QuarticQuadrupleRoot) {
    auto c = FromRoots({1, 1, 1, 1});
    ExpectRoots(Quartic(c[0], c[1], c[2], c[3], c[4]), {1}, 1e-3);
}

TEST(Polynomial, QuarticWithComplexPair) {
    // (x² + 1)(x − 2)(x + 5) = x⁴ + 3x³ − 9x² + 3x − 10.
    ExpectRoots(Quartic(1, 3, -9, 3, -10), {-5, 2}, 1e-12);
}

TEST(Polynomial, QuarticWithoutRealRoots) {
    // (x² + 1)(x² + 4) = x⁴ + 5x² + 4.
    EXPECT_TRUE(Quartic(1, 0, 5, 0, 4).empty());
}

TEST(Polynomial, QuarticCloseRootsSeparated) {
    auto c = FromRoots({-2, -1, 1, 1.001});
    ExpectRoots(Quartic(c[0], c[1], c[2], c[3], c[4]), {-2, -1, 1, 1.001}, 1e-10);
}

TEST(Polynomial, QuarticZeroRoot) {
    auto c = FromRoots({0, 1, 2, 3});
    ExpectRoots(Quartic(c[0], c[1], c[2], c[3], c[4]), {0, 1, 2, 3}, 1e-12);
}

TEST(Polynomial, QuarticNonMonicScaled) {
    // 1e-3·(x−1)(x−2)(x−3)(x−4): scaling must not change the roots.
    auto c = FromRoots({1, 2, 3, 4});
    for (double& v : c) v *= 1e-3;
    ExpectRoots(Quartic(c[0], c[1], c[2], c[3], c[4]), {1, 2, 3, 4}, 1e-11);
}

TEST(Polynomial, QuarticWithZeroLeadingIsCubic) {
    auto c = FromRoots({1, 2, 3});
    ExpectRoots(Quartic(0, c[0], c[1], c[2], c[3]), {1, 2, 3}, 1e-12);
}

TEST(Polynomial, IntervalRestrictsRoots) {
    // Ascending coefficients of (x−1)(x−2)(x−3)(x−4) = x⁴ − 10x³ + 35x² − 50x + 24.
    const double c[5] = {24, -50, 35, -10, 1};
    double r[4];
    int n = SolvePolynomialInInterval(c, 4, 1.5, 3.5, r);
    ASSERT_EQ(n, 2);
    EXPECT_NEAR(r[0], 2, 1e-12);
    EXPECT_NEAR(r[1], 3, 1e-12);
    // Closed interval: an end that is a root is reported.
    n = SolvePolynomialInInterval(c, 4, 2, 2.5, r);
    ASSERT_EQ(n, 1);
    EXPECT_NEAR(r[0], 2, 1e-12);
}

TEST(Polynomial, RandomQuarticsRecoverTheirRoots) {
    for (int seed = 0; seed < 500; ++seed) {
        std::mt19937_64 rng(seed);
        std::uniform_real_distribution<double> dist(-10, 10);
        std::vector<double> roots{dist(rng), dist(rng), dist(rng), dist(rng)};
        std::sort(roots.begin(), roots.end());
        // Keep the roots apart so each is a well-conditioned simple root.
        bool separated = true;
        for (int i = 0; i < 3; ++i) separated &= roots[i + 1] - roots[i] > 0.05;
        if (!separated) continue;
        auto c = FromRoots(roots);
        auto found = Quartic(c[0], c[1], c[2], c[3], c[4]);
        ASSERT_EQ(found.size(), 4u) << "seed " << seed;
        for (int i = 0; i < 4; ++i) EXPECT_NEAR(found[i], roots[i], 1e-8) << "seed " << seed;
    }
}

TEST(Polynomial, QuarticSimpleRootsKeepFullPrecision) {
    // Dyadic roots give exact coefficients; well-conditioned roots come out to a few ulp,
    // the rounding-error stop of the refinement cutting nothing short here.
    auto c = FromRoots({-1.5, 0.25, 0.75, 3});
    ExpectRoots(Quartic(c[0], c[1], c[2], c[3], c[4]), {-1.5, 0.25, 0.75, 3}, 4e-15);
}

TEST(Polynomial, QuarticNearlyTangentRootsWithinTheRoundingBand) {
    // (x − 1)(x − 1 − 10⁻⁵)(x + 2)(x + 3): the close pair is ill-conditioned (|p′| ≈ 1.2·10⁻⁴
    // against Σ|c_i| ≈ 27), so its roots are only determined to ~(2n + 1)u·27/1.2·10⁻⁴
    // ≈ 2·10⁻¹⁰; both are still found, distinct and in order, within that band.
    const double d = 1e-5;
    auto c = FromRoots({-3, -2, 1, 1 + d});
    auto r = Quartic(c[0], c[1], c[2], c[3], c[4]);
    ASSERT_EQ(r.size(), 4u);
    EXPECT_NEAR(r[0], -3, 1e-13);
    EXPECT_NEAR(r[1], -2, 1e-13);
    EXPECT_NEAR(r[2], 1, 1e-9);
    EXPECT_NEAR(r[3], 1 + d, 1e-9);
    EXPECT_LT(r[2], r[3]);
}

TEST(AscendingRoots, YieldsRootsNearestFirst) {
    // (x−1)(x−2)²(x−4) = x⁴ − 9x³ + 28x² − 36x + 16, ascending coefficients.
    const double c[5] = {16, -36, 28, -9, 1};
    AscendingRoots walker(c, 4, 0, 10);
    double x;
    ASSERT_TRUE(walker.Next(x));
    EXPECT_NEAR(x, 1, 1e-12);
    ASSERT_TRUE(walker.Next(x));
    EXPECT_NEAR(x, 2, 1e-7);  // the double root, once
    ASSERT_TRUE(walker.Next(x));
    EXPECT_NEAR(x, 4, 1e-12);
    EXPECT_FALSE(walker.Next(x));
    EXPECT_FALSE(walker.Next(x));
}

TEST(AscendingRoots, RespectsTheInterval) {
    const double c[5] = {16, -36, 28, -9, 1};
    AscendingRoots walker(c, 4, 1.5, 3);
    double x;
    ASSERT_TRUE(walker.Next(x));
    EXPECT_NEAR(x, 2, 1e-7);
    EXPECT_FALSE(walker.Next(x));
    AscendingRoots empty(c, 4, 5, 4);
    EXPECT_FALSE(empty.Next(x));
}

}  // namespace
}  // namespace rs
