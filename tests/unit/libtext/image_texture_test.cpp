#include "libtext/image_texture.h"

#include <gtest/gtest.h>

#include <cmath>

namespace rs {
namespace {

// 2×2 RGB. Stored row 0 (texture v in [0, ½)) = blue, white; row 1 = red, green.
std::shared_ptr<const Image> Quad() {
    auto image = std::make_shared<Image>();
    image->width = 2;
    image->height = 2;
    image->channels = 3;
    image->pixels = {0, 0, 255, 255, 255, 255, 255, 0, 0, 0, 255, 0};
    return image;
}

std::shared_ptr<const Image> Grey(int channels, std::vector<uint8_t> pixels) {
    auto image = std::make_shared<Image>();
    image->width = 2;
    image->height = 2;
    image->channels = channels;
    image->pixels.assign(pixels.begin(), pixels.end());
    return image;
}

// (u, v) = (x, y) of the node-space point.
ImageTextureOptions Planar() {
    ImageTextureOptions o;
    o.mapping = PlanarMapping::Make({0, 0, 0}, {0, 1, 0}, {1, 0, 0});
    return o;
}

TextureContext At(double u, double v) {
    TextureContext ctx;
    ctx.point = {u, v, 0};
    ctx.normal = {0, 0, 1};
    return ctx;
}

Surface White() {
    Surface s;
    s.ambient = s.diffuse = s.specular = Color(1);
    return s;
}

void ExpectColorNear(const Color& a, const Color& b, double tol = 1e-12) {
    EXPECT_NEAR(a.r, b.r, tol);
    EXPECT_NEAR(a.g, b.g, tol);
    EXPECT_NEAR(a.b, b.b, tol);
}

TEST(ImageTexture, VZeroIsTheFirstStoredRowAndTilesRepeat) {
    ImageTexture texture(Quad(), Planar());
    struct Case {
        double u, v;
        Color c;
    } cases[] = {{0.25, 0.25, {0, 0, 1}}, {0.75, 0.25, {1, 1, 1}}, {0.25, 0.75, {1, 0, 0}},
                 {0.75, 0.75, {0, 1, 0}}, {-0.25, 1.75, {0, 1, 0}}, {3.25, -0.75, {0, 0, 1}}};
    for (const Case& c : cases) {
        Surface s = White();
        TextureContext ctx = At(c.u, c.v);
        texture.Apply(ctx, s);
        EXPECT_EQ(s.diffuse, c.c) << c.u << " " << c.v;
        EXPECT_EQ(s.ambient, c.c);
        EXPECT_EQ(s.specular, c.c);
    }
}

TEST(ImageTexture, TextureTransformActsOnUV) {
    ImageTexture texture(Quad(), Planar());
    texture.transform.Append(*Transform::Scale({2, 2, 2}));
    Surface s = White();
    TextureContext ctx = At(1.5, 0.5);  // (u, v) = (0.75, 0.25): row 0, right
    texture.Apply(ctx, s);
    EXPECT_EQ(s.diffuse, Color(1, 1, 1));
}

TEST(ImageTexture, SmoothAveragesTheFourNeighbours) {
    ImageTextureOptions o = Planar();
    o.smooth = true;
    ImageTexture texture(Quad(), o);
    Surface s = White();
    TextureContext ctx = At(0.25, 0.25);  // x = y = ½: equal weights
    texture.Apply(ctx, s);
    ExpectColorNear(s.diffuse, Color(0.5, 0.5, 0.5));
}

TEST(ImageTexture, ScalarComponentUsesRange) {
    ImageTextureOptions o = Planar();
    o.component = ImageComponent::Reflect;
    o.hi = 0.9;
    o.lo = 0.1;
    // Row 0, left pixel 51 = 0.2 → 0.1 + 0.2·0.8 = 0.26.
    ImageTexture texture(Grey(1, {51, 0, 0, 0}), o);
    Surface s = White();
    s.reflect = 0.5;
    TextureContext ctx = At(0.25, 0.25);
    texture.Apply(ctx, s);
    EXPECT_NEAR(s.reflect, 0.5 * 0.26, 1e-12);
    EXPECT_EQ(s.diffuse, Color(1));
}

TEST(ImageTexture, AlphaSkipsOrBlends) {
    // Grey + alpha, row 0: left fully transparent, right 51/255 grey at alpha 0.6.
    ImageTexture texture(Grey(2, {0, 0, 51, 153, 0, 0, 0, 0}), Planar());
    Surface clear = White();
    TextureContext left = At(0.25, 0.25);
    texture.Apply(left, clear);
    EXPECT_EQ(clear.diffuse, Color(1));
    Surface blended = White();
    TextureContext right = At(0.75, 0.25);
    texture.Apply(right, blended);
    ExpectColorNear(blended.diffuse, Color(0.4 + 0.6 * 0.2));
}

TEST(ImageTexture, TextSurfaceIsTheBase) {
    ImageTextureOptions o = Planar();
    Surface base;
    base.diffuse = Color(0.5);
    o.textSurface = base;
    ImageTexture texture(Quad(), o);
    Surface s = White();
    TextureContext ctx = At(0.75, 0.25);  // white pixel
    texture.Apply(ctx, s);
    EXPECT_EQ(s.diffuse, Color(0.5));
    EXPECT_EQ(s.ambient, Color(0));
}

TEST(ImageTexture, BumpUsesForwardDifferences) {
    // Heights: row 0: 0, 51; row 1: 102, 0 (in 1/255 units). At row 0's left pixel
    // F_u = 0.2, F_v = 0.4 (range 1, 0); ∂u = x̂, ∂v = ŷ, n = ẑ:
    // n + F_u(ẑ × ŷ) − F_v(ẑ × x̂) = (−0.2, −0.4, 1).
    ImageTextureOptions o = Planar();
    o.component = ImageComponent::Bump;
    ImageTexture texture(Grey(1, {0, 51, 102, 0}), o);
    Surface s = White();
    TextureContext ctx = At(0.25, 0.25);
    texture.Apply(ctx, s);
    Vec3 expected = Normalize({-0.2, -0.4, 1});
    EXPECT_NEAR(ctx.normal.x, expected.x, 1e-12);
    EXPECT_NEAR(ctx.normal.y, expected.y, 1e-12);
    EXPECT_NEAR(ctx.normal.z, expected.z, 1e-12);
    EXPECT_EQ(s.diffuse, Color(1));
}

TEST(ImageTexture, TileRules) {
    EXPECT_TRUE(ImageTexture::Covers(0, 0, -5, 7));
    EXPECT_TRUE(ImageTexture::Covers(0.0005, 0, -5, 7));  // below 0.001: no limit
    EXPECT_TRUE(ImageTexture::Covers(2, 0, 1.5, 9));
    EXPECT_FALSE(ImageTexture::Covers(2, 0, 2.5, 9));
    EXPECT_FALSE(ImageTexture::Covers(2, 0, -0.1, 9));
    EXPECT_FALSE(ImageTexture::Covers(0, 1, 0.5, 1.5));
    EXPECT_FALSE(ImageTexture::Covers(-1, 0, 0.5, 7));
    EXPECT_TRUE(ImageTexture::Covers(-1, 0, 1.5, 7));
    // Both negative: a rectangular hole.
    EXPECT_FALSE(ImageTexture::Covers(-1, -2, 0.5, 1.5));
    EXPECT_TRUE(ImageTexture::Covers(-1, -2, 0.5, 2.5));
    EXPECT_TRUE(ImageTexture::Covers(-1, -2, 1.5, 1.5));
    // Mixed signs: each axis separately.
    EXPECT_FALSE(ImageTexture::Covers(2, -1, 0.5, 0.5));
    EXPECT_TRUE(ImageTexture::Covers(2, -1, 0.5, 1.5));
}

TEST(ImageTexture, TilesOutsideLeaveTheSurface) {
    ImageTextureOptions o = Planar();
    o.tileU = 1;
    o.tileV = 1;
    ImageTexture texture(Quad(), o);
    Surface s = White();
    TextureContext ctx = At(1.25, 0.25);
    texture.Apply(ctx, s);
    EXPECT_EQ(s.diffuse, Color(1));
}

TEST(ImageTexture, ChannelRequirements) {
    EXPECT_TRUE(ImageTexture::ChannelsSuit(ImageComponent::Diffuse, 3));
    EXPECT_TRUE(ImageTexture::ChannelsSuit(ImageComponent::Color, 1));
    EXPECT_TRUE(ImageTexture::ChannelsSuit(ImageComponent::Bump, 2));
    EXPECT_FALSE(ImageTexture::ChannelsSuit(ImageComponent::Bump, 3));
    EXPECT_FALSE(ImageTexture::ChannelsSuit(ImageComponent::Specpow, 4));
}

}  // namespace
}  // namespace rs
