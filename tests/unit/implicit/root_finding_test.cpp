#include "libobj/implicit/root_finding.h"

#include <gtest/gtest.h>

#include <cmath>

namespace rs {
namespace {

TEST(RootFinding, RiddersFindsSquareRootOfTwo) {
    auto f = [](double x) { return x * x - 2; };
    auto r = RiddersRoot(f, 0.0, f(0.0), 2.0, f(2.0), 1e-12, 100);
    ASSERT_TRUE(r.has_value());
    EXPECT_NEAR(r->root, std::sqrt(2.0), 1e-12);
    EXPECT_LE(r->iterations, 10);  // quadratic convergence, far fewer than bisection's 41
}

TEST(RootFinding, RiddersHandlesDecreasingFunctions) {
    auto f = [](double x) { return std::cos(x); };
    auto r = RiddersRoot(f, 1.0, f(1.0), 2.0, f(2.0), 1e-13, 100);
    ASSERT_TRUE(r.has_value());
    EXPECT_NEAR(r->root, M_PI / 2, 1e-13);
}

TEST(RootFinding, RiddersConvergesToToleranceOnFlatRoot) {
    // Triple root at 0.3: the function is tiny near it, the bracket must still shrink.
    auto f = [](double x) { return (x - 0.3) * (x - 0.3) * (x - 0.3); };
    for (double tol : {1e-3, 1e-6, 1e-9}) {
        auto r = RiddersRoot(f, 0.0, f(0.0), 1.0, f(1.0), tol, 200);
        ASSERT_TRUE(r.has_value());
        EXPECT_NEAR(r->root, 0.3, tol);
    }
}

TEST(RootFinding, BisectionFindsRoot) {
    auto f = [](double x) { return x * x * x - x - 1; };  // real root 1.3247179572447460
    auto r = BisectRoot(f, 1.0, f(1.0), 2.0, f(2.0), 1e-10, 100);
    ASSERT_TRUE(r.has_value());
    EXPECT_NEAR(r->root, 1.3247179572447460, 1e-10);
    EXPECT_GE(r->iterations, 30);  // log2(1/1e-10) ≈ 33 halvings
}

TEST(RootFinding, NoSignChangeGivesNothing) {
    auto f = [](double x) { return x * x + 1; };
    EXPECT_FALSE(RiddersRoot(f, -1.0, f(-1.0), 1.0, f(1.0), 1e-9, 100).has_value());
    EXPECT_FALSE(BisectRoot(f, -1.0, f(-1.0), 1.0, f(1.0), 1e-9, 100).has_value());
}

TEST(RootFinding, IterationCapGivesNothing) {
    auto f = [](double x) { return x - 0.123456789; };
    EXPECT_FALSE(BisectRoot(f, 0.0, f(0.0), 1.0, f(1.0), 1e-12, 3).has_value());
    auto g = [](double x) { return std::tanh(50 * (x - 0.7)); };
    EXPECT_FALSE(RiddersRoot(g, 0.0, g(0.0), 1.0, g(1.0), 1e-14, 1).has_value());
}

TEST(RootFinding, ExactZeroAtEndIsReturned) {
    auto f = [](double x) { return x - 1; };
    auto r = RiddersRoot(f, 1.0, 0.0, 2.0, 1.0, 1e-9, 10);
    ASSERT_TRUE(r.has_value());
    EXPECT_EQ(r->root, 1.0);
}

}  // namespace
}  // namespace rs
