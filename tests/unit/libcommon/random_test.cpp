#include "libcommon/random.h"

#include <gtest/gtest.h>

namespace rs {
namespace {

TEST(Drand48, MatchesPosixSequenceSeededWithOne) {
    // Values of glibc's srand48(1); drand48() (first three draws), computed independently
    // from the LCG definition x' = (0x5DEECE66D·x + 0xB) mod 2^48, x0 = 0x1330E.
    Drand48 r(1);
    EXPECT_NEAR(r.Next(), 0.041630344771878214, 1e-15);
    EXPECT_NEAR(r.Next(), 0.45449244472862915, 1e-15);
    EXPECT_NEAR(r.Next(), 0.8348172181669149, 1e-15);
}

TEST(Rng, SameKeySameStreamDifferentKeyDifferentStream) {
    Rng a = Rng::ForKey(3, 4), b = Rng::ForKey(3, 4), c = Rng::ForKey(4, 3);
    double va = a.Uniform();
    EXPECT_EQ(va, b.Uniform());
    EXPECT_NE(va, c.Uniform());
}

TEST(Rng, UniformStaysInUnitIntervalWithSaneMean) {
    Rng r(42);
    double sum = 0;
    const int n = 100000;
    for (int i = 0; i < n; ++i) {
        double u = r.Uniform();
        ASSERT_GE(u, 0.0);
        ASSERT_LT(u, 1.0);
        sum += u;
    }
    EXPECT_NEAR(sum / n, 0.5, 0.01);
}

}  // namespace
}  // namespace rs
