// `texture patches`: part colours checked against the HSV definition read backwards (the
// largest channel is the value, the smallest v(1 − s), the hue follows from the channel
// order), and the surface edits against the documented contract.
#include "libtext/patches_texture.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace rs {
namespace {

constexpr double kTol = 1e-12;

// The hue in [0, 1) of an RGB colour (standard RGB → HSV inversion).
double Hue(const Color& c) {
    double hi = std::max({c.r, c.g, c.b}), lo = std::min({c.r, c.g, c.b});
    double d = hi - lo, h;
    if (hi == c.r) {
        h = (c.g - c.b) / d;
    } else if (hi == c.g) {
        h = 2 + (c.b - c.r) / d;
    } else {
        h = 4 + (c.r - c.g) / d;
    }
    h /= 6;
    return h < 0 ? h + 1 : h;
}

// Distance between two hues on the unit circle, in [0, 0.5].
double HueDistance(double a, double b) {
    double d = std::fabs(a - b);
    return std::min(d, 1 - d);
}

TEST(PatchesTexture, PartColoursFollowTheGoldenRatioHues) {
    const double golden = (std::sqrt(5.0) - 1) / 2;
    const double v = PatchesTexture::kValue, s = PatchesTexture::kSaturation;
    for (int part = 0; part < 200; ++part) {
        Color c = PatchesTexture::PartColor(part);
        EXPECT_NEAR(std::max({c.r, c.g, c.b}), v, kTol) << part;
        EXPECT_NEAR(std::min({c.r, c.g, c.b}), v * (1 - s), kTol) << part;
        double expected = part * golden - std::floor(part * golden);
        EXPECT_NEAR(HueDistance(Hue(c), expected), 0, 1e-9) << part;
    }
    // Hue 0 is red: (v, v(1 − s), v(1 − s)).
    Color red = PatchesTexture::PartColor(0);
    EXPECT_NEAR(red.r, 0.9, kTol);
    EXPECT_NEAR(red.g, 0.27, kTol);
    EXPECT_NEAR(red.b, 0.27, kTol);
}

TEST(PatchesTexture, ConsecutivePartsAreFarApart) {
    // Consecutive golden-ratio hues are 1 − 0.618… = 0.381… of the circle apart.
    const double gap = (3 - std::sqrt(5.0)) / 2;
    for (int part = 0; part < 100; ++part) {
        double a = Hue(PatchesTexture::PartColor(part));
        double b = Hue(PatchesTexture::PartColor(part + 1));
        EXPECT_NEAR(HueDistance(a, b), gap, 1e-9) << part;
    }
}

TEST(PatchesTexture, ReplacesDiffuseAndScalesAmbient) {
    Surface surface = Surface::Default();
    surface.ambient = Color(0.2, 0.1, 0.05);
    surface.reflect = 0.3;
    const Surface before = surface;
    TextureContext ctx;
    ctx.primitiveHit.part = 3;
    PatchesTexture().Apply(ctx, surface);
    Color c = PatchesTexture::PartColor(3);
    EXPECT_EQ(surface.diffuse, c);
    EXPECT_NEAR(surface.ambient.r, 0.2 * c.r, kTol);
    EXPECT_NEAR(surface.ambient.g, 0.2 * c.g, kTol);
    EXPECT_NEAR(surface.ambient.b, 0.2 * c.b, kTol);
    EXPECT_EQ(surface.specular, before.specular);
    EXPECT_EQ(surface.specpow, before.specpow);
    EXPECT_EQ(surface.reflect, before.reflect);
}

TEST(PatchesTexture, NoPartLeavesTheSurfaceAlone) {
    Surface surface = Surface::Default();
    const Surface before = surface;
    TextureContext ctx;  // part −1
    PatchesTexture().Apply(ctx, surface);
    EXPECT_EQ(surface.diffuse, before.diffuse);
    EXPECT_EQ(surface.ambient, before.ambient);
}

}  // namespace
}  // namespace rs
