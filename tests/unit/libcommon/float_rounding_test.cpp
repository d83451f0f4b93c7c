// FloatAtOrBelow / FloatAtOrAbove against the definition: the nearest float on the chosen
// side, i.e. the float cast stepped once with std::nextafter when it landed on the wrong side.
#include "libcommon/float_rounding.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "libcommon/random.h"

namespace rs {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

float Below(double x) {
    const float f = static_cast<float>(x);
    return static_cast<double>(f) > x ? std::nextafter(f, -kInf) : f;
}
float Above(double x) {
    const float f = static_cast<float>(x);
    return static_cast<double>(f) < x ? std::nextafter(f, kInf) : f;
}

void ExpectSameFloat(float expected, float actual, double x) {
    EXPECT_EQ(std::signbit(expected), std::signbit(actual)) << x;
    if (std::isnan(expected)) {
        EXPECT_TRUE(std::isnan(actual)) << x;
    } else {
        EXPECT_EQ(expected, actual) << x;
    }
}

TEST(FloatRounding, EdgeCasesMatchNextafter) {
    const double fmax = std::numeric_limits<float>::max();
    const double denorm = std::numeric_limits<float>::denorm_min();
    const std::vector<double> xs = {
        0.0, -0.0, 1.0, -1.0, 0.1, -0.1, 1e-300, -1e-300, denorm, -denorm, denorm / 3,
        -denorm / 3, std::numeric_limits<float>::min(), fmax, -fmax, fmax * (1 + 1e-12),
        -fmax * (1 + 1e-12), 1e300, -1e300, std::numeric_limits<double>::infinity(),
        -std::numeric_limits<double>::infinity(), std::nan("")};
    for (double x : xs) {
        ExpectSameFloat(Below(x), FloatAtOrBelow(x), x);
        ExpectSameFloat(Above(x), FloatAtOrAbove(x), x);
    }
}

TEST(FloatRounding, RandomDoublesAreBracketedByNeighbours) {
    Rng rng(20261204);
    for (int i = 0; i < 200000; ++i) {
        // Magnitudes from 2^-160 to 2^140: subnormal floats, normal ones, beyond the range.
        const int exponent = static_cast<int>(rng.Uniform() * 300) - 160;
        const double x = (rng.Uniform() < 0.5 ? -1 : 1) * std::ldexp(1 + rng.Uniform(), exponent);
        const float lo = FloatAtOrBelow(x), hi = FloatAtOrAbove(x);
        ExpectSameFloat(Below(x), lo, x);
        ExpectSameFloat(Above(x), hi, x);
        ASSERT_LE(static_cast<double>(lo), x);
        ASSERT_GE(static_cast<double>(hi), x);
        // Adjacent (or equal, when x is a float): nothing lies strictly between.
        if (lo != hi) {
            ASSERT_EQ(std::nextafter(lo, kInf), hi) << x;
        }
    }
}

}  // namespace
}  // namespace rs
