#include "libobj/cylinder.h"

#include <gtest/gtest.h>

#include <cmath>

#include "test_arg_reader.h"

namespace rs {
namespace {

using testing::ExpectVecNear;
using testing::HitT;
using testing::MustHit;
using testing::TestArgReader;

// Radius 1 around the z axis, 0 ≤ z ≤ 2.
const Cylinder kCylinder(1, {0, 0, 0}, {0, 0, 2});

TEST(Cylinder, HitFromOutside) {
    Ray ray{{-5, 0, 1}, {2, 0, 0}};
    PrimitiveHit hit = MustHit(kCylinder, ray);
    EXPECT_NEAR(hit.t, 2, 1e-12);
    SurfaceNormals n = kCylinder.Normal(ray.At(hit.t), hit);
    ExpectVecNear(n.geometric, {-1, 0, 0});
    EXPECT_TRUE(kCylinder.Enters(ray, hit, n));
}

TEST(Cylinder, HitFromInside) {
    Ray ray{{0, 0, 1}, {0, 0.5, 0}};
    PrimitiveHit hit = MustHit(kCylinder, ray);
    EXPECT_NEAR(hit.t, 2, 1e-12);
    SurfaceNormals n = kCylinder.Normal(ray.At(hit.t), hit);
    ExpectVecNear(n.geometric, {0, 1, 0});
    EXPECT_FALSE(kCylinder.Enters(ray, hit, n));
    // Slanted from inside: x = 1 at t = 0.5, z = 1.5.
    EXPECT_NEAR(HitT(kCylinder, {{0, 0, 1}, {2, 0, 1}}), 0.5, 1e-12);
}

TEST(Cylinder, NoCapsAndHeightLimits) {
    EXPECT_LT(HitT(kCylinder, {{-5, 0, 3}, {1, 0, 0}}), 0);   // above the top
    EXPECT_LT(HitT(kCylinder, {{0, 0, -5}, {0, 0, 1}}), 0);   // along the axis
    EXPECT_LT(HitT(kCylinder, {{0, 0, 1}, {1, 0, 3}}), 0);    // leaves through the open top
    // Enters through the open top and hits the inside of the wall: x = 1 at t = 1, z = 1.
    EXPECT_NEAR(HitT(kCylinder, {{0, 0, 3}, {1, 0, -2}}), 1, 1e-12);
}

TEST(Cylinder, RangeClipping) {
    Ray ray{{-5, 0, 1}, {2, 0, 0}};  // walls at t = 2 and 3
    EXPECT_LT(HitT(kCylinder, ray, 1e-5, 2), 0);
    EXPECT_NEAR(HitT(kCylinder, ray, 2.5), 3, 1e-12);
}

TEST(Cylinder, ArbitraryAxis) {
    // Axis (3, 0, 4) from (1, 2, 3): length 5, unit (0.6, 0, 0.8); radius 0.5. A ray along
    // −y toward the axis midpoint meets the wall 0.5 before the axis.
    const Cylinder c(0.5, {1, 2, 3}, {4, 2, 7});
    const Vec3 mid{2.5, 2, 5};
    Ray ray{mid + Vec3{0, 5, 0}, {0, -3, 0}};
    PrimitiveHit hit = MustHit(c, ray);
    EXPECT_NEAR(hit.t, 1.5, 1e-12);
    ExpectVecNear(c.Normal(ray.At(hit.t), hit).geometric, {0, 1, 0});
    // The wall point along the axis-perpendicular (0.8, 0, −0.6) has normal that direction.
    const Vec3 side{0.8, 0, -0.6};
    Ray ray2{mid + side * 4.0, side * -1.0};
    hit = MustHit(c, ray2);
    EXPECT_NEAR(hit.t, 3.5, 1e-12);
    ExpectVecNear(c.Normal(ray2.At(hit.t), hit).geometric, side, 1e-12);
}

TEST(Cylinder, UVAlongZ) {
    // Axis +z: the canonical frame is the identity scaled by (1, 1, 2).
    SurfaceUV a = kCylinder.UV({1, 0, 0.5}, {1, 0, 0}, {});
    EXPECT_NEAR(a.uv.u, 0, 1e-12);
    EXPECT_NEAR(a.uv.v, 0.25, 1e-12);
    ExpectVecNear(a.dpdu, {0, 1, 0});
    ExpectVecNear(a.dpdv, {0, 0, 1});
    EXPECT_NEAR(kCylinder.UV({0, 1, 1}, {0, 1, 0}, {}).uv.u, 0.25, 1e-12);
    EXPECT_NEAR(kCylinder.UV({0, -1, 1}, {0, -1, 0}, {}).uv.u, 0.75, 1e-12);
    EXPECT_NEAR(kCylinder.UV({-1, 0, 2}, {-1, 0, 0}, {}).uv.v, 1, 1e-12);
}

TEST(Cylinder, UVCanonicalFrameForOtherAxes) {
    // Axis −z: half turn about +x, so canonical +y is object −y.
    const Cylinder down(1, {0, 0, 2}, {0, 0, 0});
    SurfaceUV a = down.UV({0, 1, 1}, {0, 1, 0}, {});
    EXPECT_NEAR(a.uv.u, 0.75, 1e-12);
    EXPECT_NEAR(a.uv.v, 0.5, 1e-12);
    EXPECT_NEAR(down.UV({1, 0, 1}, {1, 0, 0}, {}).uv.u, 0, 1e-12);
    // Axis +x: rotation about +y by 90° takes canonical +x to object −z, +y stays +y.
    const Cylinder sideways(1, {0, 0, 0}, {2, 0, 0});
    SurfaceUV b = sideways.UV({1, 0, -1}, {0, 0, -1}, {});
    EXPECT_NEAR(b.uv.u, 0, 1e-12);
    EXPECT_NEAR(b.uv.v, 0.5, 1e-12);
    EXPECT_NEAR(sideways.UV({1, 1, 0}, {0, 1, 0}, {}).uv.u, 0.25, 1e-12);
}

TEST(Cylinder, Bounds) {
    ExpectVecNear(kCylinder.Bounds().lo, {-1, -1, 0});
    ExpectVecNear(kCylinder.Bounds().hi, {1, 1, 2});
    EXPECT_FALSE(kCylinder.IsClosed());
}

TEST(Cylinder, CreateAndDegenerate) {
    TestArgReader good({1, 0, 0, 0, 0, 0, 2});
    auto prim = Cylinder::Create(good);
    ASSERT_NE(prim, nullptr);
    EXPECT_TRUE(good.AllConsumed());
    EXPECT_NEAR(HitT(*prim, {{-5, 0, 1}, {2, 0, 0}}), 2, 1e-12);
    TestArgReader zeroRadius({0, 0, 0, 0, 0, 0, 2});
    EXPECT_EQ(Cylinder::Create(zeroRadius), nullptr);
    EXPECT_EQ(zeroRadius.warnings.size(), 1u);
    TestArgReader shortAxis({1, 0, 0, 0, 0, 0, 1e-6});
    EXPECT_EQ(Cylinder::Create(shortAxis), nullptr);
    EXPECT_EQ(shortAxis.warnings.size(), 1u);
}

}  // namespace
}  // namespace rs
