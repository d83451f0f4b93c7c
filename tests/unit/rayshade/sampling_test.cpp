#include "rayshade/sampling.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>

namespace rs {
namespace {

TEST(SamplingPattern, DitherIsAPermutationForEverySize) {
    for (int n = 1; n <= 16; ++n) {
        SamplingPattern p(n, FilterKind::Box, 1);
        std::vector<int> seen(n * n, 0);
        for (int s = 0; s < n * n; ++s) {
            int m = p.SampleNumber(s);
            ASSERT_GE(m, 0) << "n=" << n;
            ASSERT_LT(m, n * n) << "n=" << n;
            ++seen[m];
        }
        EXPECT_TRUE(std::all_of(seen.begin(), seen.end(), [](int c) { return c == 1; })) << "n=" << n;
    }
}

TEST(SamplingPattern, OriginalTableForThree) {
    SamplingPattern p(3, FilterKind::Box, 1);
    const int expected[] = {0, 2, 7, 6, 5, 1, 3, 8, 4};
    for (int s = 0; s < 9; ++s) EXPECT_EQ(p.SampleNumber(s), expected[s]);
}

TEST(SamplingPattern, WeightsSumToOne) {
    for (FilterKind f : {FilterKind::Box, FilterKind::Gauss}) {
        SamplingPattern p(4, f, 1.8);
        double sum = 0;
        for (int s = 0; s < 16; ++s) sum += p.Weight(s);
        EXPECT_NEAR(sum, 1, 1e-12);
    }
}

TEST(SamplingPattern, GaussianWeightsPeakAtTheCentre) {
    SamplingPattern p(3, FilterKind::Gauss, 1.8);
    EXPECT_GT(p.Weight(4), p.Weight(0));
    EXPECT_DOUBLE_EQ(p.Weight(0), p.Weight(8));
}

TEST(SamplingPattern, CellsTileTheFilterFootprint) {
    // Pixel i owns [i − w/2, i + w/2]; cell (k, l) starts at −w/2 + k·w/n.
    SamplingPattern p(2, FilterKind::Box, 1);
    EXPECT_DOUBLE_EQ(p.CellOffsetX(0), -0.5);
    EXPECT_DOUBLE_EQ(p.CellOffsetX(1), 0.0);
    EXPECT_DOUBLE_EQ(p.CellOffsetY(2), 0.0);
    EXPECT_DOUBLE_EQ(p.CellSize(), 0.5);
}

TEST(SquareSample, StaysInsideItsCell) {
    Rng rng(7);
    for (int m = 0; m < 9; ++m) {
        for (int i = 0; i < 100; ++i) {
            double x, y;
            SquareSample(m, 3, rng, x, y);
            double x0 = -1 + (m % 3) * 2.0 / 3, y0 = -1 + (m / 3) * 2.0 / 3;
            ASSERT_GE(x, x0);
            ASSERT_LT(x, x0 + 2.0 / 3);
            ASSERT_GE(y, y0);
            ASSERT_LT(y, y0 + 2.0 / 3);
        }
    }
}

}  // namespace
}  // namespace rs
