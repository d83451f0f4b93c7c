#include "metrics.h"

#include <cmath>

#include <gtest/gtest.h>

namespace rs {
namespace {

constexpr double kEps = 1e-12;

Image Filled(int width, int height, std::vector<uint8_t> pixel) {
    Image image;
    image.width = width;
    image.height = height;
    image.channels = static_cast<int>(pixel.size());
    image.pixels.resize(static_cast<size_t>(width) * height * pixel.size());
    for (size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = pixel[i % pixel.size()];
    return image;
}

void Set(Image& image, int x, int y, int c, uint8_t value) {
    image.Row(y)[x * image.channels + c] = value;
}

TEST(BoxDownsample, AveragesFullBlocksAndOnlyTheExistingPixelsOfPartialOnes) {
    // value(x, y) = x + 10y on 5×5: block means are (mean x) + 10·(mean y).
    UnitImage image;
    image.width = image.height = 5;
    image.channels = 1;
    for (int y = 0; y < 5; ++y) {
        for (int x = 0; x < 5; ++x) image.values.push_back(x + 10.0 * y);
    }
    const UnitImage small = BoxDownsample(image, 4);
    ASSERT_EQ(small.width, 2);
    ASSERT_EQ(small.height, 2);
    EXPECT_NEAR(small.At(0, 0, 0), 1.5 + 15.0, kEps);  // x 0..3, y 0..3
    EXPECT_NEAR(small.At(1, 0, 0), 4.0 + 15.0, kEps);  // x 4,    y 0..3
    EXPECT_NEAR(small.At(0, 1, 0), 1.5 + 40.0, kEps);  // x 0..3, y 4
    EXPECT_NEAR(small.At(1, 1, 0), 4.0 + 40.0, kEps);  // x 4,    y 4
}

TEST(ToUnit, ScalesBytesAndHarmonisesChannels) {
    Image grey = Filled(1, 1, {51});
    UnitImage rgb = ToUnit(grey, 3, true);
    ASSERT_EQ(rgb.channels, 4);
    EXPECT_NEAR(rgb.values[0], 0.2, kEps);
    EXPECT_NEAR(rgb.values[2], 0.2, kEps);
    EXPECT_EQ(rgb.values[3], 1.0);  // no source alpha: opaque
    UnitImage dropped = ToUnit(Filled(1, 1, {0, 255, 102, 7}), 3, false);
    ASSERT_EQ(dropped.channels, 3);
    EXPECT_NEAR(dropped.values[2], 0.4, kEps);
}

TEST(CompareImages, OneBrightBlockOfFour) {
    // 8×8 RGB at 100; the reference's top-left 4×4 block has red 151 (difference 51/255 = 0.2).
    // Downsampled 2×2: one pixel differs, by 0.2 in one of its 3 channels.
    const Image ours = Filled(8, 8, {100, 100, 100});
    Image ref = ours;
    for (int y = 0; y < 4; ++y) {
        for (int x = 0; x < 4; ++x) Set(ref, x, y, 0, 151);
    }
    std::string error;
    const auto m = CompareImages(ours, ref, error);
    ASSERT_TRUE(m) << error;
    EXPECT_NEAR(m->mean, 0.2 / 12, kEps);
    EXPECT_NEAR(m->max, 0.2, kEps);
    EXPECT_NEAR(m->frac, 0.25, kEps);
    // Colour sums over the 12 downsampled values: ours 1200/255, ref (1200 + 51)/255.
    EXPECT_NEAR(m->bright, 51.0 / 1251.0, kEps);
}

TEST(CompareImages, PartialEdgeBlockIsNotDilutedByMissingPixels) {
    // 5×1 grey; only the reference's last pixel is white. Its block holds just that pixel, so
    // the downsampled difference there is 1, not 1/4 or 1/16.
    const Image ours = Filled(5, 1, {0});
    Image ref = ours;
    Set(ref, 4, 0, 0, 255);
    std::string error;
    const auto m = CompareImages(ours, ref, error);
    ASSERT_TRUE(m) << error;
    EXPECT_NEAR(m->mean, 0.5, kEps);
    EXPECT_NEAR(m->max, 1.0, kEps);
    EXPECT_NEAR(m->frac, 0.5, kEps);
    EXPECT_NEAR(m->bright, 1.0, kEps);  // mean(ref) = 0.5, mean(ours) = 0
}

TEST(CompareImages, PixelToleranceIsExceededByEightStepsNotSeven) {
    // 7/255 = 0.0275 ≤ 0.03 < 8/255 = 0.0314.
    const Image ours = Filled(8, 4, {0});
    Image ref = ours;
    for (int y = 0; y < 4; ++y) {
        for (int x = 0; x < 4; ++x) {
            Set(ref, x, y, 0, 7);
            Set(ref, x + 4, y, 0, 8);
        }
    }
    std::string error;
    const auto m = CompareImages(ours, ref, error);
    ASSERT_TRUE(m) << error;
    EXPECT_NEAR(m->frac, 0.5, kEps);
    EXPECT_NEAR(m->max, 8.0 / 255, kEps);
}

TEST(FractionBeyond, CountsFullResolutionPixelsBeyondTheSteps) {
    // 10×10 RGB; 3 pixels differ by 2 steps in one channel, 4 by exactly 1 step, and one pair
    // of neighbours by +5 and −5 (which a 4×4 box average would cancel).
    const Image ours = Filled(10, 10, {100, 100, 100});
    Image ref = ours;
    Set(ref, 0, 0, 0, 102);
    Set(ref, 5, 5, 1, 98);
    Set(ref, 9, 9, 2, 102);
    for (int x = 0; x < 4; ++x) Set(ref, x, 2, 1, 101);
    Set(ref, 0, 1, 2, 105);
    Set(ref, 1, 1, 2, 95);
    std::string error;
    const auto one = FractionBeyond(ours, ref, 1, error);
    ASSERT_TRUE(one) << error;
    EXPECT_NEAR(*one, 5.0 / 100, kEps);
    EXPECT_NEAR(*FractionBeyond(ours, ref, 0, error), 9.0 / 100, kEps);
    EXPECT_NEAR(*FractionBeyond(ours, ref, 2, error), 2.0 / 100, kEps);
    EXPECT_NEAR(*FractionBeyond(ours, ref, 5, error), 0.0, kEps);
    EXPECT_FALSE(FractionBeyond(ours, Filled(10, 9, {100, 100, 100}), 1, error));
}

TEST(CompareImages, GreyAgainstRgbComparesInRgb) {
    std::string error;
    const auto m = CompareImages(Filled(1, 1, {10}), Filled(1, 1, {10, 10, 40}), error);
    ASSERT_TRUE(m) << error;
    EXPECT_NEAR(m->mean, (30.0 / 255) / 3, kEps);
    EXPECT_NEAR(m->max, 30.0 / 255, kEps);
    EXPECT_NEAR(m->bright, 30.0 / 60.0, kEps);  // colour sums 30 vs 60 (in 1/255)
}

TEST(CompareImages, AlphaCountsOnlyWhenBothHaveIt) {
    std::string error;
    auto m = CompareImages(Filled(2, 2, {1, 2, 3, 0}), Filled(2, 2, {1, 2, 3}), error);
    ASSERT_TRUE(m) << error;
    EXPECT_EQ(m->max, 0.0);
    m = CompareImages(Filled(2, 2, {0, 0, 0, 255}), Filled(2, 2, {0, 0, 0, 0}), error);
    ASSERT_TRUE(m) << error;
    EXPECT_NEAR(m->mean, 0.25, kEps);
    EXPECT_NEAR(m->max, 1.0, kEps);
    EXPECT_EQ(m->bright, 0.0);  // alpha is not brightness; both colour means are 0
}

TEST(CompareImages, BrightnessAgainstBlackReferenceIsInfinite) {
    std::string error;
    const auto m = CompareImages(Filled(1, 1, {1}), Filled(1, 1, {0}), error);
    ASSERT_TRUE(m) << error;
    EXPECT_TRUE(std::isinf(m->bright));
}

TEST(CompareImages, SizeMismatchIsAnError) {
    std::string error;
    EXPECT_FALSE(CompareImages(Filled(4, 4, {0}), Filled(4, 5, {0}), error));
    EXPECT_NE(error.find("size mismatch"), std::string::npos) << error;
}

TEST(WithinThresholds, StrictForMeanMaxBrightInclusiveForFrac) {
    const Thresholds t;  // 0.005 0.15 0.05 0.01
    EXPECT_TRUE(WithinThresholds({0.004, 0.1, 0.05, 0.009}, t));
    EXPECT_FALSE(WithinThresholds({0.005, 0.1, 0.01, 0.0}, t));
    EXPECT_FALSE(WithinThresholds({0.0, 0.15, 0.01, 0.0}, t));
    EXPECT_FALSE(WithinThresholds({0.0, 0.1, 0.051, 0.0}, t));
    EXPECT_FALSE(WithinThresholds({0.0, 0.1, 0.01, 0.01}, t));
}

TEST(HeatColour, RunsThroughItsStops) {
    auto expectColour = [](double d, double r, double g, double b) {
        double rgb[3];
        HeatColour(d, rgb);
        EXPECT_NEAR(rgb[0], r, kEps) << d;
        EXPECT_NEAR(rgb[1], g, kEps) << d;
        EXPECT_NEAR(rgb[2], b, kEps) << d;
    };
    expectColour(0.0, 0, 0, 0);
    expectColour(0.015, 0, 0, 0.5);
    expectColour(0.03, 0, 0, 1);
    expectColour(0.09, 0.5, 0, 0.5);
    expectColour(0.15, 1, 0, 0);
    expectColour(0.225, 1, 0.5, 0);
    expectColour(0.3, 1, 1, 0);
    expectColour(1.0, 1, 1, 0);
}

TEST(HeatMap, PaintsEachBlockWithItsDifference) {
    // 6×2 grey: the left block agrees (black), the partial right block (x 4..5) differs by 1
    // (yellow).
    const Image ours = Filled(6, 2, {0});
    Image ref = ours;
    for (int y = 0; y < 2; ++y) {
        Set(ref, 4, y, 0, 255);
        Set(ref, 5, y, 0, 255);
    }
    const Image heat = HeatMap(ours, ref);
    ASSERT_EQ(heat.width, 6);
    ASSERT_EQ(heat.height, 2);
    ASSERT_EQ(heat.channels, 3);
    for (int y = 0; y < 2; ++y) {
        for (int x = 0; x < 6; ++x) {
            const uint8_t* p = heat.Row(y) + x * 3;
            const std::vector<uint8_t> expected =
                x < 4 ? std::vector<uint8_t>{0, 0, 0} : std::vector<uint8_t>{255, 255, 0};
            EXPECT_TRUE(std::vector<uint8_t>(p, p + 3) == expected) << x << "," << y;
        }
    }
}

}  // namespace
}  // namespace rs
