#include "libobj/implicit/kernel.h"

#include <gtest/gtest.h>

#include <cmath>

#include "libcommon/random.h"
#include "test_util.h"

namespace rs {
namespace {

std::vector<Kernel> SampleKernels() {
    return {Kernel::GascuelLinear(0.5, 1.5, 1.5), Kernel::GascuelQuadratic(0.5, 1.5, 1.5),
            Kernel::GascuelLinear(0.3, 2.4, 0.9), Kernel::GascuelQuadratic(1, 0.5, 3),
            Kernel::GascuelLinear(1, 0.2, 2),  // m = 0.2: max |f'| > k
            Kernel::Blob(1, 1), Kernel::Blob(2.5, 0.7)};
}

TEST(Kernel, GascuelEndConditions) {
    for (bool quadratic : {false, true}) {
        double e = 0.4, k = 2, r = 1.5;  // m = 2.2
        Kernel f = quadratic ? Kernel::GascuelQuadratic(e, k, r) : Kernel::GascuelLinear(e, k, r);
        EXPECT_DOUBLE_EQ(f.Value(e), 1);
        EXPECT_DOUBLE_EQ(f.Derivative(e), -k);
        EXPECT_NEAR(f.Value(r - 1e-12), 0, 1e-12);
        EXPECT_NEAR(f.Derivative(r - 1e-12), 0, 1e-11);
        EXPECT_EQ(f.Value(r), 0);
        EXPECT_EQ(f.Value(2 * r), 0);
        // Inner part at the skeleton: linear 1 + ke, quadratic 1 + ke/2.
        EXPECT_DOUBLE_EQ(f.Value(0), quadratic ? 1 + k * e / 2 : 1 + k * e);
    }
}

// C¹ at r = e and r = R: one-sided values and slopes agree (differences O(h)).
TEST(Kernel, GascuelIsC1AtThicknessAndRadius) {
    for (const Kernel& f : SampleKernels()) {
        std::vector<double> joints{f.Radius()};
        if (f.Kind() != KernelKind::Blob) joints.push_back(f.Thickness());
        for (double j : joints) {
            double h = 1e-9;
            EXPECT_NEAR(f.Value(j - h), f.Value(j + h), 1e-7);
            EXPECT_NEAR(f.Derivative(j - h), f.Derivative(j + h), 1e-6);
        }
    }
}

// The corrected outer cubic equals (r − R)²(ar + b) with the research note's coefficients.
TEST(Kernel, OuterCubicMatchesCorrectedCoefficients) {
    double e = 0.5, k = 1.7, big = 2.0;
    double a = -(k * (e - big) + 2) / std::pow(e - big, 3);
    double b = (k * e * e - k * e * big + 3 * e - big) / std::pow(e - big, 3);
    Kernel f = Kernel::GascuelLinear(e, k, big);
    for (double r = e; r < big; r += 0.01) {
        EXPECT_NEAR(f.Value(r), (r - big) * (r - big) * (a * r + b), 1e-12) << r;
    }
}

TEST(Kernel, DerivativesMatchCentralDifferences) {
    for (const Kernel& f : SampleKernels()) {
        for (double r = 0.013; r < f.Radius() * 1.2; r += 0.0371) {
            double h = 1e-6;
            EXPECT_NEAR(f.Derivative(r), (f.Value(r + h) - f.Value(r - h)) / (2 * h), 1e-6) << r;
            if (std::abs(r - f.Thickness()) > 2 * h && std::abs(r - f.Radius()) > 2 * h) {
                EXPECT_NEAR(f.SecondDerivative(r),
                            (f.Derivative(r + h) - f.Derivative(r - h)) / (2 * h), 1e-5)
                    << r;
            }
        }
    }
}

TEST(Kernel, ValidKernelsArePositiveAndDecreasing) {
    for (const Kernel& f : SampleKernels()) {
        ASSERT_TRUE(f.Validate("s").ok);
        double prev = f.Value(0);
        for (double r = 0.001; r < f.Radius() * 1.1; r += 0.001) {
            EXPECT_GE(f.Value(r), 0);
            EXPECT_LE(f.Value(r), prev);
            prev = f.Value(r);
        }
    }
}

TEST(Kernel, ValidateRejectsNonMonotoneOuterPartNamingTheSkeleton) {
    Kernel f = Kernel::GascuelLinear(1, 2, 3);  // m = k(R − e) = 4 > 3
    KernelStatus st = f.Validate("arm");
    EXPECT_FALSE(st.ok);
    EXPECT_NE(st.message.find("'arm'"), std::string::npos);
    EXPECT_NE(st.message.find("exceeds 3"), std::string::npos);
    EXPECT_TRUE(Kernel::GascuelLinear(1, 1.5, 3).Validate("arm").ok);  // m = 3 exactly
    EXPECT_FALSE(Kernel::GascuelQuadratic(2, 1, 1).Validate("x").ok);  // e > R
    EXPECT_FALSE(Kernel::Blob(-1, 1).Validate("x").ok);
}

TEST(Kernel, AnalyticSlopeMaxima) {
    // Blob: max |f'| = 8s/(3√3 R) at r = R/√3.
    Kernel blob = Kernel::Blob(2, 1.5);
    EXPECT_NEAR(blob.Bounds(0, 10).maxSlope, 16 / (3 * std::sqrt(3.0) * 1.5), 1e-12);
    // Blob: max(|f''|, |f'|/r) = 8s/R² (|f''| at r = R).
    EXPECT_NEAR(blob.Bounds(0, 10).maxCurvature, 16 / (1.5 * 1.5), 1e-12);
    // Gascuel with m = 1: outer max |g'| = (3 − m)²/(3(2 − m)ℓ) = 4k/3.
    double e = 1, k = 0.5, big = 3;  // ℓ = 2, m = 1
    Kernel g = Kernel::GascuelLinear(e, k, big);
    EXPECT_NEAR(g.Bounds(e, big).maxSlope, 4 * k / 3, 1e-12);
    // Quadratic inner: curvature k/e; linear inner: unbounded at the skeleton.
    EXPECT_NEAR(Kernel::GascuelQuadratic(0.5, 2, 1.2).Bounds(0, 0.3).maxCurvature, 4, 1e-12);
    EXPECT_TRUE(std::isinf(Kernel::GascuelLinear(0.5, 2, 1.2).Bounds(0, 0.3).maxCurvature));
    EXPECT_NEAR(Kernel::GascuelLinear(0.5, 2, 1.2).Bounds(0.25, 0.3).maxCurvature, 8, 1e-12);
}

// Dense sampling of random intervals: f, |f'|, |f''| (both sides of the jumps) and |f'|/r
// stay inside the bounds.
TEST(Kernel, IntervalBoundsHoldOnSamples) {
    std::vector<Kernel> kernels = SampleKernels();
    for (uint64_t seed = 1; seed <= 2000; ++seed) {
        Rng rng(seed);
        const Kernel& f = kernels[seed % kernels.size()];
        double a = testing::Uniform(rng, 0, f.Radius() * 1.2);
        double b = a + testing::Uniform(rng, 0, f.Radius() * 0.6) * (seed % 5 == 0 ? 0 : 1);
        KernelBounds kb = f.Bounds(a, b);
        double slack = 1e-12;
        for (int i = 0; i <= 200; ++i) {
            double r = a + (b - a) * i / 200.0;
            ASSERT_GE(f.Value(r), kb.valueMin - slack) << "seed " << seed;
            ASSERT_LE(f.Value(r), kb.valueMax + slack) << "seed " << seed;
            ASSERT_LE(std::abs(f.Derivative(r)), kb.maxSlope * (1 + 1e-12) + slack)
                << "seed " << seed;
            for (double side : {-1e-12, 0.0, 1e-12}) {
                double rs = std::clamp(r + side, a, b);
                ASSERT_LE(std::abs(f.SecondDerivative(rs)), kb.maxCurvature * (1 + 1e-12) + slack)
                    << "seed " << seed;
            }
            if (r > 0) {
                ASSERT_LE(std::abs(f.Derivative(r)) / r, kb.maxCurvature * (1 + 1e-12) + slack)
                    << "seed " << seed;
            }
        }
    }
}

}  // namespace
}  // namespace rs
