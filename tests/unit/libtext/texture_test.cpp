// Texture patterns at points where the expected value follows from the spec's formulas and
// the original's reference value Noise(0) (spec §3.12.1): every octave of Chaos and fBm at
// the origin samples the origin again, so their sums there are Noise(0) times a geometric
// series.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "libcommon/constants.h"
#include "libtext/blotch.h"
#include "libtext/bump.h"
#include "libtext/checker.h"
#include "libtext/cloud.h"
#include "libtext/fbm.h"
#include "libtext/fbmbump.h"
#include "libtext/gloss.h"
#include "libtext/marble.h"
#include "libtext/mount.h"
#include "libtext/noise.h"
#include "libtext/sky.h"
#include "libtext/stripe.h"
#include "libtext/windy.h"
#include "libtext/wood.h"

namespace rs {
namespace {

constexpr double kNoise0 = -0.033920288;                           // Noise(0, 0, 0)
const Vec3 kDNoise0{-0.033920288, -0.0859375, 0.423065186};        // DNoise(0, 0, 0)
constexpr double kTol = 1e-7;

void ExpectVecNear(const Vec3& a, const Vec3& b, double tol = kTol) {
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
}
void ExpectColorNear(const Color& a, const Color& b, double tol = kTol) {
    EXPECT_NEAR(a.r, b.r, tol);
    EXPECT_NEAR(a.g, b.g, tol);
    EXPECT_NEAR(a.b, b.b, tol);
}

TextureContext At(const Vec3& p, const Vec3& n = {0, 0, 1}) {
    TextureContext ctx;
    ctx.point = p;
    ctx.normal = n;
    ctx.geometricNormal = n;
    return ctx;
}

Surface Plain(const Color& c) {
    Surface s;
    s.ambient = c;
    s.diffuse = c;
    s.specular = c;
    return s;
}

TEST(Checker, OddParityCellsTakeTheSurface) {
    Surface s = Plain(Color(0, 0, 1));
    CheckerTexture checker(s);
    struct Case {
        Vec3 p;
        bool replaced;
    } cases[] = {
        {{0.5, 0.5, 0.5}, false},   // 0 + 0 + 0
        {{1.5, 0.5, 0.5}, true},    // 1 + 0 + 0
        {{-0.5, 0.5, 0.5}, true},   // ⌊1.5⌋ = 1
        {{-1.5, 0.5, 0.5}, false},  // ⌊2.5⌋ = 2
        {{0, 0, 0}, true},          // 1 + 1 + 1
        {{2.5, 3.5, -0.25}, false}, // 2 + 3 + 1
    };
    for (const Case& c : cases) {
        Surface surface = Plain(Color(1, 0, 0));
        TextureContext ctx = At(c.p);
        checker.Apply(ctx, surface);
        EXPECT_EQ(surface.diffuse == s.diffuse, c.replaced) << c.p.x << " " << c.p.y;
    }
}

TEST(Checker, TextureTransformScalesTheCells) {
    CheckerTexture checker(Plain(Color(0, 0, 1)));
    checker.transform.Append(*Transform::Scale({2, 2, 2}));
    Surface surface = Plain(Color(1, 0, 0));
    TextureContext ctx = At({1.5, 0.5, 0.5});  // texture space (0.75, 0.25, 0.25): even
    checker.Apply(ctx, surface);
    EXPECT_EQ(surface.diffuse, Color(1, 0, 0));
}

TEST(Blotch, BlendsAboveTheThresholdOnly) {
    Surface s = Plain(Color(0, 0, 1));
    Surface surface = Plain(Color(1, 0, 0));
    TextureContext ctx = At({0, 0, 0});
    BlotchTexture(-0.5, s).Apply(ctx, surface);
    double beta = (kNoise0 + 0.5) / 1.5;
    ExpectColorNear(surface.diffuse, Color(1 - beta, 0, beta));

    Surface untouched = Plain(Color(1, 0, 0));
    BlotchTexture(0, s).Apply(ctx, untouched);  // Noise(0) < 0
    EXPECT_EQ(untouched.diffuse, Color(1, 0, 0));
}

TEST(Bump, AddsRawDNoise) {
    TextureContext ctx = At({0, 0, 0});
    Surface surface;
    BumpTexture(1).Apply(ctx, surface);
    ExpectVecNear(ctx.normal, Normalize(Vec3{0, 0, 1} + kDNoise0));
}

TEST(Bump, NormalUsesInverseTransposeOfTheTextureTransform) {
    // Texture space = node space scaled by ½ in x: normals go there unchanged (ẑ), and come
    // back with x halved.
    BumpTexture bump(1);
    bump.transform.Append(*Transform::Scale({2, 1, 1}));
    TextureContext ctx = At({0, 0, 0});
    Surface surface;
    bump.Apply(ctx, surface);
    ExpectVecNear(ctx.normal, Normalize({kDNoise0.x / 2, kDNoise0.y, 1 + kDNoise0.z}));

    BumpTexture shifted(1);
    shifted.transform.Append(Transform::Translate({1, 2, 3}));
    TextureContext moved = At({1, 2, 3});
    shifted.Apply(moved, surface);
    ExpectVecNear(moved.normal, Normalize(Vec3{0, 0, 1} + kDNoise0));
}

TEST(Bump, NormalsStayUnitUnderSkewedTransforms) {
    const unsigned seed = 20261122;
    Rng rng(seed);
    std::vector<std::shared_ptr<Texture>> textures = {
        std::make_shared<BumpTexture>(3.0),
        std::make_shared<FBmBumpTexture>(0.2, 2.0, 0.5, 2.0, 6),
        std::make_shared<WindyTexture>(1.0, 0.5, 1.0, 0.5, 4, 2.0, 0.5, 0.3),
        std::make_shared<GlossTexture>(0.3),
    };
    for (auto& t : textures) {
        t->transform.Append(*Transform::General({1, 0.5, 0}, {0, 2, 0.3}, {0.1, 0, 0.7},
                                                {1, 2, 3}));
    }
    for (int i = 0; i < 200; ++i) {
        Vec3 p{rng.Uniform() * 20 - 10, rng.Uniform() * 20 - 10, rng.Uniform() * 20 - 10};
        Vec3 n = Normalize({rng.Uniform() - 0.5, rng.Uniform() - 0.5, rng.Uniform() - 0.5});
        for (auto& t : textures) {
            TextureContext ctx = At(p, n);
            ctx.rng = &rng;
            ctx.sampleNumber = i % 9;
            ctx.samplesPerSide = 3;
            Surface surface;
            t->Apply(ctx, surface);
            ASSERT_NEAR(Length(ctx.normal), 1.0, 1e-12) << "seed " << seed << " i " << i;
        }
    }
}

TEST(Marble, ModulatesByTheMarbleValue) {
    double chaos = kNoise0 * 63.0 / 32.0;  // Σ_{j<6} 2^-j
    double v = std::pow(0.5 * (std::sin(8 * chaos) + 1), 0.77);
    Surface surface = Plain(Color(0.5, 1, 1));
    TextureContext ctx = At({0, 0, 0});
    MarbleTexture().Apply(ctx, surface);
    ExpectColorNear(surface.diffuse, Color(0.5 * v, v, v));
    ExpectColorNear(surface.ambient, Color(0.5 * v, v, v));
    ExpectColorNear(surface.specular, Color(0.5, 1, 1));

    auto map = std::make_shared<ColorMap>();
    int index = static_cast<int>(255 * v);
    (*map)[index] = Color(0.25, 0.5, 0.75);
    Surface mapped = Plain(Color(1, 1, 1));
    MarbleTexture(map).Apply(ctx, mapped);
    ExpectColorNear(mapped.diffuse, Color(0.25, 0.5, 0.75));
}

TEST(Marble, ValueStaysInTheUnitInterval) {
    for (int i = 0; i < 100; ++i) {
        Surface surface = Plain(Color(1, 1, 1));
        TextureContext ctx = At({0.1 * i, -0.03 * i, 0.07 * i});
        MarbleTexture().Apply(ctx, surface);
        EXPECT_GE(surface.diffuse.r, 0.0);
        EXPECT_LE(surface.diffuse.r, 1.0);
    }
}

TEST(Wood, MatchesTheFormulaAtTheOrigin) {
    double chi = kNoise0 * 127.0 / 64.0;  // Σ_{j<7} 2^-j
    double t = std::fabs(std::sin(std::sin(8 * chi)));
    double grain = std::fabs(std::sin(40 * chi));
    double g0 = 0.5 * std::pow(t, 0.3);
    double ring = std::pow((t + 1) / 2, 0.6);
    double b = ring * (0.6 * grain + 0.3), gr = ring * (0.2 * grain + 0.8);
    Color expected((0.5 * b + 0.35 * gr) * 2 * g0, g0 * std::max(b, gr) * (0.15 * grain + 0.85),
                   (0.25 * b + 0.35 * gr) * 2 * g0);
    Surface surface = Plain(Color(1, 1, 1));
    TextureContext ctx = At({0, 0, 0});
    WoodTexture().Apply(ctx, surface);
    ExpectColorNear(surface.diffuse, expected);
    ExpectColorNear(surface.ambient, expected);
}

TEST(FBm, OffsetScaleAndThreshold) {
    TextureContext ctx = At({0, 0, 0});
    Surface above = Plain(Color(1, 1, 1));
    FBmTexture(0.1, 2, 0.5, 2, 1, -0.5).Apply(ctx, above);  // one octave: v = Noise(0)
    ExpectColorNear(above.diffuse, Color(0.1 + 2 * (kNoise0 + 0.5)));

    Surface below = Plain(Color(1, 1, 1));
    FBmTexture(0.1, 2, 0.5, 2, 1, 0).Apply(ctx, below);
    ExpectColorNear(below.diffuse, Color(0.1));

    // Two octaves with ω = 2^-(1+1)/2 = ½: v = 1.5·Noise(0); offset 0.5, scale 1, thr −1.
    Surface two = Plain(Color(1, 1, 1));
    FBmTexture(0.5, 1, 0.5, 2, 2, -1).Apply(ctx, two);
    ExpectColorNear(two.ambient, Color(0.5 + 1.5 * kNoise0 + 1));
}

TEST(FBmBump, AddsOffsetAndScaledVfBmThenNormalises) {
    TextureContext ctx = At({0, 0, 0});
    Surface surface;
    FBmBumpTexture(0.1, 2, 0.5, 2, 1).Apply(ctx, surface);
    Vec3 expected = Vec3{0, 0, 1} + Vec3{0.1, 0.1, 0.1} + 2 * kDNoise0;
    ExpectVecNear(ctx.normal, Normalize(expected));
}

TEST(Sky, NormalisesRampsAndPowers) {
    // H = ½, λ = 2 → ω = ½, M = 2; one octave: It = (2 + Noise(0))/4; ramp 0.25 → 0.75.
    double it = ((2 + kNoise0) / 4 - 0.25) / 0.5;
    it = it * it;  // scale 2
    Surface surface = Plain(Color(1, 1, 1));
    TextureContext ctx = At({0, 0, 0});
    SkyTexture(2, 0.5, 2, 1, 0.75, 0.25).Apply(ctx, surface);
    EXPECT_NEAR(surface.transp, 1 - it, kTol);
    ExpectColorNear(surface.diffuse, Color(it));
    ExpectColorNear(surface.specular, Color(1));
}

TEST(Cloud, InsideTheSphereIsClearAndBlack) {
    TextureContext ctx = At({0, 0, 1});
    ctx.rayPrimitive = {{0, 0, 0.5}, {0, 0, 1}, 0};
    Surface surface = Plain(Color(1, 1, 1));
    CloudTexture(0.5, 0.5, 2, 3, 0.3, 0.6, 0.5).Apply(ctx, surface);
    EXPECT_EQ(surface.transp, 1.0);
    EXPECT_EQ(surface.diffuse, Color(0));
    EXPECT_EQ(surface.ambient, Color(0));
}

TEST(Cloud, ZeroRoughnessUsesTheHalfIntensityLimit) {
    // H = 0: It = ½. Looking straight at the centre: limb = 1, so
    // t = 1 − (½ − 0.3)/0.5 = 0.6; Kd *= 0.4·(1 − 0.5 + 0.5·½) = 0.3; A *= 0.4.
    TextureContext ctx = At({0, 0, -1});
    ctx.rayPrimitive = {{0, 0, -3}, {0, 0, 2}, 0};  // direction need not be unit
    Surface surface = Plain(Color(1, 1, 1));
    CloudTexture(0.5, 0, 2, 3, 0.3, 0.6, 0.5).Apply(ctx, surface);
    EXPECT_NEAR(surface.transp, 0.6, 1e-12);
    ExpectColorNear(surface.diffuse, Color(0.3), 1e-12);
    ExpectColorNear(surface.ambient, Color(0.4), 1e-12);
}

TEST(Gloss, MirrorLeavesNormalAndBlurTiltsByTheLensSample) {
    TextureContext ctx = At({0, 0, 0});
    ctx.sampleNumber = 0;
    ctx.samplesPerSide = 2;
    Surface surface;
    GlossTexture(1).Apply(ctx, surface);
    ExpectVecNear(ctx.normal, {0, 0, 1}, 1e-15);
    // Sample 0 of 2×2 with ξ = ½ (no rng): (−½, −½); axes of ẑ are x̂, ŷ.
    GlossTexture(0).Apply(ctx, surface);
    ExpectVecNear(ctx.normal, Normalize({-0.5, -0.5, 1}), 1e-12);
}

TEST(UnitSquareSample, StaysInsideTheSampleCell) {
    const uint64_t seed = 7;
    Rng rng(seed);
    for (int m = 0; m < 9; ++m) {
        for (int k = 0; k < 20; ++k) {
            Vec2 s = UnitSquareSample(m, 3, &rng);
            double x0 = -1 + (m % 3) * 2.0 / 3, y0 = -1 + (m / 3) * 2.0 / 3;
            ASSERT_GE(s.u, x0) << "seed " << seed;
            ASSERT_LT(s.u, x0 + 2.0 / 3) << "seed " << seed;
            ASSERT_GE(s.v, y0) << "seed " << seed;
            ASSERT_LT(s.v, y0 + 2.0 / 3) << "seed " << seed;
        }
    }
    Vec2 centre = UnitSquareSample(4, 3, nullptr);
    EXPECT_NEAR(centre.u, 0, 1e-15);
    EXPECT_NEAR(centre.v, 0, 1e-15);
}

TEST(Stripe, BandsBevelsAndFlatTop) {
    Surface s = Plain(Color(0, 0, 1));
    // Default planar mapping: u = x, v = y; ∂u = x̂, ∂v = ŷ.
    StripeTexture stripe(s, 0.1, 0.5, PlanarMapping::Make({0, 0, 0}, {0, 1, 0}, {1, 0, 0}));

    Surface flat = Plain(Color(1, 0, 0));
    TextureContext top = At({3.5, -1.5, 0});
    stripe.Apply(top, flat);
    EXPECT_EQ(flat.diffuse, Color(1, 0, 0));
    ExpectVecNear(top.normal, {0, 0, 1}, 0);

    Surface band = Plain(Color(1, 0, 0));
    TextureContext inBand = At({0.05, 0.5, 0});
    stripe.Apply(inBand, band);
    EXPECT_EQ(band.diffuse, Color(0, 0, 1));

    // u = 0.15, v = 0.5: u' = 0.05/0.9, v' = 0.4/0.9; v' ≥ u' and v' < 1 − u' → fu = −b:
    // n + fu(n × ŷ) = ẑ − 0.5·(−x̂).
    Surface bevel = Plain(Color(1, 0, 0));
    TextureContext onBevel = At({0.15, 0.5, 0});
    stripe.Apply(onBevel, bevel);
    EXPECT_EQ(bevel.diffuse, Color(1, 0, 0));
    ExpectVecNear(onBevel.normal, Normalize({0.5, 0, 1}), 1e-12);
}

TEST(Stripe, TextureTransformActsOnUV) {
    StripeTexture stripe(Plain(Color(0, 0, 1)), 0.1, 0.5,
                         PlanarMapping::Make({0, 0, 0}, {0, 1, 0}, {1, 0, 0}));
    stripe.transform.Append(*Transform::Scale({2, 2, 2}));
    Surface surface = Plain(Color(1, 0, 0));
    TextureContext ctx = At({1, 1, 0});  // (u, v) = (½, ½) after the inverse scale
    stripe.Apply(ctx, surface);
    EXPECT_EQ(surface.diffuse, Color(1, 0, 0));
}

TEST(Stripe, BevelsTurnWithARotatedPattern) {
    // The bevel of BandsBevelsAndFlatTop at texture (u', v') = (0.15, 0.5), with the pattern
    // turned by `rotate 0 0 1 90`: the point is (u', v')·M = (−0.5, 0.15), and the bumped
    // normal is that test's (0.5, 0, 1) turned the same way (∂P/∂u' = ŷ, ∂P/∂v' = −x̂).
    StripeTexture stripe(Plain(Color(0, 0, 1)), 0.1, 0.5,
                         PlanarMapping::Make({0, 0, 0}, {0, 1, 0}, {1, 0, 0}));
    stripe.transform.Append(*Transform::Rotate({0, 0, 1}, 90));
    Surface surface = Plain(Color(1, 0, 0));
    TextureContext ctx = At({-0.5, 0.15, 0});
    stripe.Apply(ctx, surface);
    EXPECT_EQ(surface.diffuse, Color(1, 0, 0));
    ExpectVecNear(ctx.normal, Normalize({0, 0.5, 1}), 1e-12);
}

TEST(Windy, SumsOctavesAndScalesByWind) {
    // chaoscale 0 → W0 = 1; at the origin every DNoise is DNoise(0):
    // G = bs·D0 + (1 + hs)·D0 for two octaves, times (W0 + offset).
    TextureContext ctx = At({0, 0, 0});
    Surface surface;
    WindyTexture(0.5, 1, 0, 2, 2, 3, 0.25, 0.5).Apply(ctx, surface);
    Vec3 g = (2 + 1 + 0.25) * kDNoise0 * 1.5;
    ExpectVecNear(ctx.normal, Normalize(Vec3{0, 0, 1} + 0.5 * g));
}

TEST(Mount, IndexesByHeightAndSlope) {
    auto map = std::make_shared<ColorMap>();
    (*map)[128] = Color(0.5, 0.25, 1);
    (*map)[64] = Color(1, 0.5, 0.5);
    MountTexture mount(map, 0, 0.25);
    Surface level = Plain(Color(1, 1, 1));
    TextureContext up = At({0, 0, 0.5}, {0, 0, 1});  // ⌊256·0.5⌋
    mount.Apply(up, level);
    ExpectColorNear(level.specular, Color(0.5, 0.25, 1), 0);
    Surface steep = Plain(Color(1, 1, 1));
    TextureContext side = At({0, 0, 0.5}, {1, 0, 0});  // ⌊256·(0.5 − 0.25)⌋
    mount.Apply(side, steep);
    ExpectColorNear(steep.diffuse, Color(1, 0.5, 0.5), 0);
}

}  // namespace
}  // namespace rs
