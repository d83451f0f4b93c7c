#include "libobj/triangle.h"

#include <gtest/gtest.h>

#include <cmath>

#include "test_arg_reader.h"

namespace rs {
namespace {

using testing::ExpectVecNear;
using testing::HitT;
using testing::MustHit;
using testing::TestArgReader;

// Counter-clockwise seen from +z: N = (0, 0, 1).
const Triangle::Points kP{Vec3{0, 0, 0}, Vec3{2, 0, 0}, Vec3{0, 2, 0}};
const Triangle kFlat(kP, false);

TEST(Triangle, HitGivesBarycentrics) {
    Ray ray{{0.5, 0.5, 3}, {0, 0, -3}};
    PrimitiveHit hit = MustHit(kFlat, ray);
    EXPECT_NEAR(hit.t, 1, 1e-12);
    // (0.5, 0.5) = 0.5·p1 + 0.25·p2 + 0.25·p3.
    EXPECT_NEAR(hit.a, 0.5, 1e-12);
    EXPECT_NEAR(hit.b, 0.25, 1e-12);
    EXPECT_NEAR(hit.c, 0.25, 1e-12);
    SurfaceNormals n = kFlat.Normal(ray.At(hit.t), hit);
    ExpectVecNear(n.geometric, {0, 0, 1});
    ExpectVecNear(n.shading, {0, 0, 1});
    EXPECT_FALSE(n.smooth);
    EXPECT_TRUE(kFlat.Enters(ray, hit, n));
}

TEST(Triangle, HitFromBehind) {
    Ray ray{{0.5, 0.5, -1}, {0, 0, 1}};
    PrimitiveHit hit = MustHit(kFlat, ray);
    EXPECT_NEAR(hit.t, 1, 1e-12);
    SurfaceNormals n = kFlat.Normal(ray.At(hit.t), hit);
    ExpectVecNear(n.geometric, {0, 0, 1});  // unflipped
    EXPECT_FALSE(kFlat.Enters(ray, hit, n));
}

TEST(Triangle, Misses) {
    EXPECT_LT(HitT(kFlat, {{1.5, 1.5, 3}, {0, 0, -1}}), 0);  // beyond the hypotenuse
    EXPECT_LT(HitT(kFlat, {{-0.1, 0.5, 3}, {0, 0, -1}}), 0);
    EXPECT_LT(HitT(kFlat, {{0.5, 0.5, 3}, {1, 0, 0}}), 0);   // parallel
    EXPECT_LT(HitT(kFlat, {{0.5, 0.5, 3}, {0, 0, -1}}, 1e-5, 3), 0);
    EXPECT_LT(HitT(kFlat, {{0.5, 0.5, 3}, {0, 0, -1}}, 3), 0);
}

TEST(Triangle, SlantedNonUnitRay) {
    // From (−1, −1, 2) toward (0.5, 0.25, 0), direction scaled by 4.
    const Vec3 o{-1, -1, 2}, target{0.5, 0.25, 0};
    PrimitiveHit hit = MustHit(kFlat, {o, (target - o) * 4.0});
    EXPECT_NEAR(hit.t, 0.25, 1e-12);
    EXPECT_NEAR(hit.b, 0.25, 1e-12);
    EXPECT_NEAR(hit.c, 0.125, 1e-12);
}

TEST(Triangle, FlipNegatesNormal) {
    const Triangle flipped(kP, true);
    ExpectVecNear(flipped.Normal({0.5, 0.5, 0}, {}).geometric, {0, 0, -1});
    TestArgReader args({0, 0, 0, 2, 0, 0, 0, 2, 0}, /*flip=*/true);
    auto prim = Triangle::Create(args);
    ASSERT_NE(prim, nullptr);
    ExpectVecNear(prim->Normal({0.5, 0.5, 0}, {}).geometric, {0, 0, -1});
}

TEST(Triangle, FlatUV) {
    PrimitiveHit hit = MustHit(kFlat, {{0.5, 0.5, 3}, {0, 0, -1}});
    SurfaceUV uv = kFlat.UV({0.5, 0.5, 0}, {0, 0, 1}, hit);
    EXPECT_NEAR(uv.uv.v, 0.25, 1e-12);
    EXPECT_NEAR(uv.uv.u, 0.25 / 0.75, 1e-12);
    ExpectVecNear(uv.dpdu, {1, 0, 0});
    ExpectVecNear(uv.dpdv, {-std::sqrt(0.5), -std::sqrt(0.5), 0});  // toward p1
    PrimitiveHit atP3;
    atP3.a = 0, atP3.b = 0, atP3.c = 1;
    SurfaceUV top = kFlat.UV({0, 2, 0}, {0, 0, 1}, atP3);
    EXPECT_EQ(top.uv.u, 0);
    EXPECT_NEAR(top.uv.v, 1, 1e-12);
}

const Triangle::Points kN{Vec3{0, 0, 1}, Vec3{0, 1, 1}, Vec3{1, 0, 1}};

TEST(Triangle, PhongInterpolatesNormals) {
    const Triangle phong(kP, kN, false);
    PrimitiveHit hit = MustHit(phong, {{0.5, 0.5, 3}, {0, 0, -1}});
    SurfaceNormals n = phong.Normal({0.5, 0.5, 0}, hit);
    const double h = std::sqrt(0.5);
    const Vec3 blend = Vec3{0, 0, 1} * 0.5 + Vec3{0, h, h} * 0.25 + Vec3{h, 0, h} * 0.25;
    ExpectVecNear(n.shading, blend / Length(blend));
    ExpectVecNear(n.geometric, {0, 0, 1});
    EXPECT_TRUE(n.smooth);
}

TEST(Triangle, PhongInconsistentNormalsReverseN) {
    const Triangle::Points down{Vec3{0, 0, -1}, Vec3{0, 0, -1}, Vec3{0, 0, -1}};
    const Triangle phong(kP, down, false);
    ExpectVecNear(phong.Normal({0.5, 0.5, 0}, {}).geometric, {0, 0, -1});
    TestArgReader args({0, 0, 0, 0, 0, -1, 2, 0, 0, 0, 0, -1, 0, 2, 0, 0, 0, -1});
    auto prim = Triangle::Create(args);
    ASSERT_NE(prim, nullptr);
    EXPECT_TRUE(args.AllConsumed());
    EXPECT_EQ(args.advisories.size(), 1u);
    ExpectVecNear(prim->Normal({0.5, 0.5, 0}, {}).geometric, {0, 0, -1});
}

TEST(Triangle, PhongFlipNegatesBoth) {
    const Triangle phong(kP, kN, true);
    PrimitiveHit hit = MustHit(phong, {{0.5, 0.5, 3}, {0, 0, -1}});
    SurfaceNormals n = phong.Normal({0.5, 0.5, 0}, hit);
    ExpectVecNear(n.geometric, {0, 0, -1});
    EXPECT_LT(n.shading.z, 0);
    TestArgReader args({0, 0, 0, 0, 0, 1, 2, 0, 0, 0, 0, 1, 0, 2, 0, 0, 0, 1}, true);
    ASSERT_NE(Triangle::Create(args), nullptr);
    EXPECT_TRUE(args.advisories.empty());
}

TEST(Triangle, TriangleUV) {
    const Triangle::UVs uvs{Vec2{0, 0}, Vec2{2, 0}, Vec2{0, 4}};
    const Triangle tri(kP, kN, uvs, false);
    PrimitiveHit hit = MustHit(tri, {{0.5, 0.5, 3}, {0, 0, -1}});
    SurfaceUV uv = tri.UV({0.5, 0.5, 0}, {0, 0, 1}, hit);
    EXPECT_NEAR(uv.uv.u, 0.25 * 2, 1e-12);
    EXPECT_NEAR(uv.uv.v, 0.25 * 4, 1e-12);
    ExpectVecNear(uv.dpdu, {1, 0, 0});
    ExpectVecNear(uv.dpdv, {0, 1, 0});
    // u along the object's y edge and v along x: the derivatives swap.
    const Triangle::UVs swapped{Vec2{0, 0}, Vec2{0, 1}, Vec2{1, 0}};
    const Triangle tri2(kP, kN, swapped, false);
    SurfaceUV uv2 = tri2.UV({0.5, 0.5, 0}, {0, 0, 1}, hit);
    ExpectVecNear(uv2.dpdu, {0, 1, 0});
    ExpectVecNear(uv2.dpdv, {1, 0, 0});
}

TEST(Triangle, CreateUVReadsPointNormalUV) {
    TestArgReader args({0, 0, 0, 0, 0, 1, 0, 0,  //
                        2, 0, 0, 0, 0, 1, 1, 0,  //
                        0, 2, 0, 0, 0, 1, 0, 1});
    auto prim = Triangle::CreateUV(args);
    ASSERT_NE(prim, nullptr);
    EXPECT_TRUE(args.AllConsumed());
    PrimitiveHit hit = MustHit(*prim, {{0.5, 0.5, 3}, {0, 0, -1}});
    SurfaceUV uv = prim->UV({0.5, 0.5, 0}, {0, 0, 1}, hit);
    EXPECT_NEAR(uv.uv.u, 0.25, 1e-12);
    EXPECT_NEAR(uv.uv.v, 0.25, 1e-12);
    EXPECT_EQ(prim->Counters().tests, RegisterCounter("Triangle tests"));
}

TEST(Triangle, DegenerateInput) {
    TestArgReader colinear({0, 0, 0, 1, 1, 1, 2, 2, 2});
    EXPECT_EQ(Triangle::Create(colinear), nullptr);
    EXPECT_EQ(colinear.advisories.size() + colinear.warnings.size(), 1u);
    TestArgReader zeroNormal({0, 0, 0, 0, 0, 1, 2, 0, 0, 0, 0, 0, 0, 2, 0, 0, 0, 1});
    EXPECT_EQ(Triangle::Create(zeroNormal), nullptr);
    EXPECT_EQ(zeroNormal.warnings.size(), 1u);
    EXPECT_TRUE(zeroNormal.AllConsumed());
}

TEST(Triangle, Bounds) {
    ExpectVecNear(kFlat.Bounds().lo, {0, 0, 0});
    ExpectVecNear(kFlat.Bounds().hi, {2, 2, 0});
}

}  // namespace
}  // namespace rs
