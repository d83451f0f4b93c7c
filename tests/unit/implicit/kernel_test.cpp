#include "libobj/implicit/kernel.h"

#include <gtest/gtest.h>

#include <algorithm>
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

// A kernel of `kind` with parameters (a, b, c): Gascuel thickness, stiffness, radius; blob
// strength a and radius c.
Kernel MakeKernel(KernelKind kind, double a, double b, double c) {
    switch (kind) {
        case KernelKind::GascuelLinear:
            return Kernel::GascuelLinear(a, b, c);
        case KernelKind::GascuelQuadratic:
            return Kernel::GascuelQuadratic(a, b, c);
        default:
            return Kernel::Blob(a, c);
    }
}

constexpr KernelKind kKinds[] = {KernelKind::GascuelLinear, KernelKind::GascuelQuadratic,
                                 KernelKind::Blob};

// A random valid kernel of `kind`: m = k(R − e) anywhere in (0, 3].
Kernel RandomKernel(Rng& rng, KernelKind kind) {
    const double radius = testing::Uniform(rng, 0.3, 3);
    if (kind == KernelKind::Blob) return Kernel::Blob(testing::Uniform(rng, 0.1, 4), radius);
    const double e = radius * testing::Uniform(rng, 0.02, 0.98);
    const double m = testing::Uniform(rng, 0.01, 3);
    return MakeKernel(kind, e, m / (radius - e), radius);
}

// A random box of valid kernels of `kind` (every corner valid), sometimes one kernel.
KernelBox RandomKernelBox(Rng& rng, KernelKind kind) {
    for (;;) {
        const Kernel lo = RandomKernel(rng, kind);
        const double spread = rng.Uniform() < 0.1 ? 0 : testing::Uniform(rng, 0, 0.6);
        const auto grow = [&](double v) { return v * (1 + spread * rng.Uniform()); };
        const Kernel hi = kind == KernelKind::Blob
                              ? Kernel::Blob(grow(lo.Strength()), grow(lo.Radius()))
                              : MakeKernel(kind, grow(lo.Thickness()), grow(lo.Stiffness()),
                                           grow(lo.Radius()));
        const KernelBox box(lo, hi);
        if (box.Validate("s").ok) return box;
    }
}

// A kernel inside the box: each parameter uniform in its range, or at one of its ends.
Kernel KernelInBox(Rng& rng, const KernelBox& box) {
    const auto pick = [&](double lo, double hi) {
        const double u = rng.Uniform();
        return u < 0.2 ? lo : u < 0.4 ? hi : testing::Uniform(rng, lo, hi);
    };
    const Kernel &lo = box.Lo(), &hi = box.Hi();
    const double radius = pick(lo.Radius(), hi.Radius());
    if (lo.Kind() == KernelKind::Blob) return Kernel::Blob(pick(lo.Strength(), hi.Strength()), radius);
    return MakeKernel(lo.Kind(), pick(lo.Thickness(), hi.Thickness()),
                      pick(lo.Stiffness(), hi.Stiffness()), radius);
}

// The facts KernelBox's value range rests on (kernel.cpp, proved there): at fixed r, a
// valid Gascuel kernel rises with e and with R and is affine in k; a blob rises with s and
// R. Checked on random valid kernels and random steps that keep the kernel valid.
TEST(KernelBox, ValueIsMonotoneInThicknessRadiusStrengthAndAffineInStiffness) {
    for (uint64_t seed = 1; seed <= 20000; ++seed) {
        Rng rng(seed);
        const KernelKind kind = kKinds[seed % 3];
        const Kernel f = RandomKernel(rng, kind);
        const double r = testing::Uniform(rng, 0, 1.2 * f.Radius());
        const double slack = 1e-13;
        const double grow = 1 + testing::Uniform(rng, 0, 0.3);
        if (kind == KernelKind::Blob) {
            ASSERT_GE(Kernel::Blob(f.Strength() * grow, f.Radius()).Value(r), f.Value(r) - slack);
            ASSERT_GE(Kernel::Blob(f.Strength(), f.Radius() * grow).Value(r), f.Value(r) - slack);
            continue;
        }
        const double e = f.Thickness(), k = f.Stiffness(), big = f.Radius();
        // A larger radius keeping m <= 3, a larger thickness keeping e < R.
        const double biggerRadius = std::min(big * grow, e + 3 / k);
        const double thicker = e + (big - e) * testing::Uniform(rng, 0, 0.99);
        ASSERT_GE(MakeKernel(kind, e, k, biggerRadius).Value(r), f.Value(r) - slack)
            << "seed " << seed;
        ASSERT_GE(MakeKernel(kind, thicker, k, big).Value(r), f.Value(r) - slack)
            << "seed " << seed;
        const double k2 = testing::Uniform(rng, 0, k), u = rng.Uniform();
        const double between = MakeKernel(kind, e, k2 + u * (k - k2), big).Value(r);
        const double affine = (1 - u) * MakeKernel(kind, e, k2, big).Value(r) + u * f.Value(r);
        ASSERT_NEAR(between, affine, 1e-12 * (1 + std::abs(affine))) << "seed " << seed;
    }
}

// Random boxes of valid kernels and random distance intervals: the box's bounds hold f,
// |f'|, |f''| (both sides of the jumps) and |f'|/r of random kernels of the box at random
// distances of the interval, ends included; and a one-kernel box bounds as tightly as the
// kernel's own Bounds (to rounding).
TEST(KernelBox, BoundsHoldForEveryKernelOfTheBox) {
    for (uint64_t seed = 1; seed <= 6000; ++seed) {
        Rng rng(seed);
        const KernelKind kind = kKinds[seed % 3];
        const KernelBox box = RandomKernelBox(rng, kind);
        const double a = testing::Uniform(rng, 0, box.Radius() * 1.1);
        const double b = a + testing::Uniform(rng, 0, box.Radius() * 0.7) * (seed % 7 == 0 ? 0 : 1);
        const KernelBounds kb = box.Bounds(a, b);
        double valueLo, valueHi;
        box.ValueRange(a, b, valueLo, valueHi);
        ASSERT_EQ(valueLo, kb.valueMin);
        ASSERT_EQ(valueHi, kb.valueMax);
        const double slack = 1e-12;
        const auto within = [&](double v, double bound) { return v <= bound * (1 + 1e-12) + slack; };
        for (int j = 0; j < 40; ++j) {
            const Kernel f = KernelInBox(rng, box);
            ASSERT_TRUE(f.Validate("s").ok) << "seed " << seed;
            for (int i = 0; i <= 20; ++i) {
                const double r = i == 0 ? a : i == 20 ? b : testing::Uniform(rng, a, b);
                ASSERT_GE(f.Value(r), kb.valueMin - slack) << "seed " << seed;
                ASSERT_LE(f.Value(r), kb.valueMax + slack) << "seed " << seed;
                ASSERT_TRUE(within(std::abs(f.Derivative(r)), kb.maxSlope)) << "seed " << seed;
                for (double side : {-1e-12, 0.0, 1e-12}) {
                    const double rs = std::clamp(r + side, a, b);
                    ASSERT_TRUE(within(std::abs(f.SecondDerivative(rs)), kb.maxCurvature))
                        << "seed " << seed;
                }
                if (r > 0) {
                    ASSERT_TRUE(within(std::abs(f.Derivative(r)) / r, kb.maxCurvature))
                        << "seed " << seed;
                }
            }
        }
        const KernelBox one(box.Lo(), box.Lo());
        const KernelBounds exact = box.Lo().Bounds(a, b), boxed = one.Bounds(a, b);
        ASSERT_DOUBLE_EQ(boxed.valueMin, exact.valueMin) << "seed " << seed;
        ASSERT_DOUBLE_EQ(boxed.valueMax, exact.valueMax) << "seed " << seed;
        ASSERT_NEAR(boxed.maxSlope, exact.maxSlope, 1e-9 * (1 + exact.maxSlope)) << "seed " << seed;
        if (std::isfinite(exact.maxCurvature)) {
            ASSERT_NEAR(boxed.maxCurvature, exact.maxCurvature, 1e-9 * (1 + exact.maxCurvature))
                << "seed " << seed;
        } else {
            ASSERT_TRUE(std::isinf(boxed.maxCurvature)) << "seed " << seed;
        }
    }
}

TEST(KernelBox, RadiusIsTheLargestAndBoundsVanishBeyondIt) {
    const KernelBox box(Kernel::GascuelQuadratic(0.4, 1, 1.2), Kernel::GascuelQuadratic(0.5, 1.5, 1.6));
    EXPECT_EQ(box.Radius(), 1.6);
    const KernelBounds kb = box.Bounds(1.6, 2);
    EXPECT_EQ(kb.valueMax, 0);
    EXPECT_EQ(kb.maxSlope, 0);
    EXPECT_EQ(kb.maxCurvature, 0);
    EXPECT_GT(box.Bounds(1.5, 2).valueMax, 0);  // within R_hi: some kernel of the box is not 0
}

TEST(KernelBox, ValidateNamesTheSkeletonAndTheRangesOfAnInvalidCorner) {
    // Thickness up to 0.9 meets radius down to 0.8: the corner (0.9, k, 0.8) has e > R.
    const KernelBox crossing(Kernel::GascuelLinear(0.5, 1, 0.8), Kernel::GascuelLinear(0.9, 1, 1.2));
    const KernelStatus st = crossing.Validate("arm");
    EXPECT_FALSE(st.ok);
    EXPECT_NE(st.message.find("'arm'"), std::string::npos) << st.message;
    EXPECT_NE(st.message.find("thickness [0.5, 0.9]"), std::string::npos) << st.message;
    // m = k_hi(R_hi − e_lo) = 2·(2 − 0.4) > 3, though the two kernels given are valid.
    const KernelBox stiff(Kernel::GascuelQuadratic(0.4, 1, 1.5), Kernel::GascuelQuadratic(0.6, 2, 2));
    EXPECT_TRUE(stiff.Lo().Validate("s").ok);
    EXPECT_TRUE(stiff.Hi().Validate("s").ok);
    EXPECT_FALSE(stiff.Validate("s").ok);
    EXPECT_FALSE(KernelBox(Kernel::Blob(-0.5, 1), Kernel::Blob(1, 1)).Validate("s").ok);
    EXPECT_TRUE(KernelBox(Kernel::Blob(0.5, 1), Kernel::Blob(1, 2)).Validate("s").ok);
}

}  // namespace
}  // namespace rs
