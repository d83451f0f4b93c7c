#include "libtext/noise.h"

#include <gtest/gtest.h>

#include <cmath>

namespace rs {
namespace {

// Reference values of spec §3.12.1, measured on the original program.
TEST(Noise, MatchesOriginalReferenceValues) {
    EXPECT_NEAR(Noise({0, 0, 0}), -0.033920288, 1e-8);
    EXPECT_NEAR(Noise({0.5, 0.5, 0.5}), 0.216384888, 1e-8);
    EXPECT_NEAR(Noise({1.25, -2.5, 3.75}), 0.177592784, 1e-8);
    EXPECT_NEAR(Noise({10.1, 20.2, -30.3}), 0.209024745, 1e-8);
}

TEST(Noise, DNoiseMatchesOriginalReferenceValue) {
    Vec3 d = DNoise({0, 0, 0});
    EXPECT_NEAR(d.x, -0.033920288, 1e-8);
    EXPECT_NEAR(d.y, -0.0859375, 1e-8);
    EXPECT_NEAR(d.z, 0.423065186, 1e-8);
}

TEST(Noise, DNoiseXEqualsNoise) {
    for (int i = 0; i < 50; ++i) {
        Vec3 p{0.37 * i - 5, 1.3 * std::sin(i), 0.11 * i * i};
        EXPECT_DOUBLE_EQ(DNoise(p).x, Noise(p)) << "i=" << i;
    }
}

// Check values of the CRC-16/ARC table R given in spec §3.12.1.
TEST(Noise, GradientTableCheckValues) {
    EXPECT_EQ(NoiseGradientTableEntry(0), -1.0);
    EXPECT_EQ(NoiseGradientTableEntry(1), -0.20843505859375);
    EXPECT_EQ(NoiseGradientTableEntry(2), -0.332550048828125);
    EXPECT_EQ(NoiseGradientTableEntry(3), 0.859344482421875);
}

// At a lattice point every corner but the first has weight 0 and the gradient terms vanish,
// so Noise is ½R[m] for that corner's m: a multiple of 2^-16 (R[i] = crc/32768 − 1).
TEST(Noise, LatticePointsAreHalfATableEntry) {
    for (int i = -3; i <= 3; ++i) {
        double v = Noise({double(i), double(2 * i), double(-i)});
        double scaled = (2 * v + 1) * 32768;
        EXPECT_NEAR(scaled, std::round(scaled), 1e-6) << "i=" << i;
    }
}

TEST(Noise, ChaosAndFBmAreTheirDefiningSums) {
    Vec3 p{0.3, -1.7, 2.2};
    double chaos = Noise(p) + 0.5 * Noise(2.0 * p) + 0.25 * Noise(4.0 * p);
    EXPECT_NEAR(Chaos(p, 3), chaos, 1e-15);
    double fbm = Noise(p) + 0.6 * Noise(2.5 * p) + 0.36 * Noise(6.25 * p);
    EXPECT_NEAR(FBm(p, 0.6, 2.5, 3), fbm, 1e-15);
    Vec3 v = VFBm(p, 0.6, 2.5, 2);
    Vec3 expected = DNoise(p) + 0.6 * DNoise(2.5 * p);
    EXPECT_NEAR(v.x, expected.x, 1e-15);
    EXPECT_NEAR(v.y, expected.y, 1e-15);
    EXPECT_NEAR(v.z, expected.z, 1e-15);
    EXPECT_EQ(Chaos(p, 0), 0.0);
}

TEST(Noise, VFBmStopsWhenWeightBelowEpsilon) {
    // omega = 1e-3: weights 1, 1e-3, 1e-6 (< 1e-5, dropped).
    Vec3 p{0.3, -1.7, 2.2};
    Vec3 v = VFBm(p, 1e-3, 2.0, 5);
    Vec3 expected = DNoise(p) + 1e-3 * DNoise(2.0 * p);
    EXPECT_NEAR(v.y, expected.y, 1e-15);
}

TEST(Noise, FBmOmegaIsLambdaPower) {
    EXPECT_NEAR(FBmOmega(0.5, 2.0), 0.5, 1e-15);   // 2^-(1+1)/2
    EXPECT_NEAR(FBmOmega(0.0, 4.0), 0.5, 1e-15);   // 4^-1/2
}

}  // namespace
}  // namespace rs
