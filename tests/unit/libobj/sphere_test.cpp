#include "libobj/sphere.h"

#include <gtest/gtest.h>

#include <cmath>

#include "test_arg_reader.h"

namespace rs {
namespace {

using testing::ExpectVecNear;
using testing::HitT;
using testing::MustHit;
using testing::TestArgReader;

// Radius 2 about (1, 2, 3).
const Sphere kSphere(2, {1, 2, 3});

TEST(Sphere, HitFromOutsideWithNonUnitDirection) {
    // From z = −10 with |d| = 2 the near wall z = 1 is 11 units, t = 5.5, away.
    Ray ray{{1, 2, -10}, {0, 0, 2}};
    PrimitiveHit hit = MustHit(kSphere, ray);
    EXPECT_NEAR(hit.t, 5.5, 1e-12);
    SurfaceNormals n = kSphere.Normal(ray.At(hit.t), hit);
    ExpectVecNear(n.geometric, {0, 0, -1});
    ExpectVecNear(n.shading, {0, 0, -1});
    EXPECT_FALSE(n.smooth);
    EXPECT_TRUE(kSphere.Enters(ray, hit, n));
}

TEST(Sphere, HitFromInsideReturnsFarWall) {
    Ray ray{{1, 2, 3}, {0, 3, 0}};
    PrimitiveHit hit = MustHit(kSphere, ray);
    EXPECT_NEAR(hit.t, 2.0 / 3.0, 1e-12);
    SurfaceNormals n = kSphere.Normal(ray.At(hit.t), hit);
    ExpectVecNear(n.geometric, {0, 1, 0});
    EXPECT_FALSE(kSphere.Enters(ray, hit, n));
}

TEST(Sphere, Misses) {
    EXPECT_LT(HitT(kSphere, {{10, 2, -10}, {0, 0, 1}}), 0);
    // Sphere behind the ray.
    EXPECT_LT(HitT(kSphere, {{1, 2, -10}, {0, 0, -1}}), 0);
}

TEST(Sphere, RangeClipping) {
    Ray ray{{1, 2, -10}, {0, 0, 2}};  // walls at t = 5.5 and 7.5
    EXPECT_LT(HitT(kSphere, ray, 1e-5, 5.0), 0);
    EXPECT_LT(HitT(kSphere, ray, 1e-5, 5.5), 0);  // open interval
    PrimitiveHit hit = MustHit(kSphere, ray, 6.0);
    EXPECT_NEAR(hit.t, 7.5, 1e-12);
    // Past the near wall the ray is inside: the far-wall hit leaves.
    EXPECT_FALSE(kSphere.Enters(ray, hit, kSphere.Normal(ray.At(hit.t), hit)));
    EXPECT_LT(HitT(kSphere, ray, 7.5), 0);
}

TEST(Sphere, DistantOriginKeepsPrecision) {
    // A transformed-looking ray: far origin, tiny non-unit direction toward the centre
    // along (0.6, 0.8, 0). The near wall is 1000 − 2 units away, t = 998 / 0.001.
    const Vec3 dirUnit{0.6, 0.8, 0};
    Ray ray{Vec3{1, 2, 3} + dirUnit * 1000.0, dirUnit * -0.001};
    EXPECT_NEAR(HitT(kSphere, ray), 998000.0, 998000.0 * 1e-13);
}

TEST(Sphere, UV) {
    const PrimitiveHit hit;
    auto uvAt = [&](const Vec3& n) { return kSphere.UV(Vec3{1, 2, 3} + n * 2.0, n, hit); };
    SurfaceUV a = uvAt({0, 1, 0});
    EXPECT_NEAR(a.uv.u, 0.25, 1e-12);
    EXPECT_NEAR(a.uv.v, 0.5, 1e-12);
    ExpectVecNear(a.dpdu, {-1, 0, 0});
    ExpectVecNear(a.dpdv, {0, 0, 1});
    SurfaceUV b = uvAt({0, -1, 0});
    EXPECT_NEAR(b.uv.u, 0.75, 1e-12);
    SurfaceUV c = uvAt({-1, 0, 0});
    EXPECT_NEAR(c.uv.u, 0.5, 1e-12);
    // n_y = 0 is not > 0, so u = 1 − 0 on the +x meridian.
    SurfaceUV d = uvAt({1, 0, 0});
    EXPECT_NEAR(d.uv.u, 1.0, 1e-12);
    // Poles: v = 0 at −z, 1 at +z, u = 0.
    SurfaceUV south = uvAt({0, 0, -1});
    EXPECT_NEAR(south.uv.v, 0, 1e-12);
    EXPECT_EQ(south.uv.u, 0);
    SurfaceUV north = uvAt({0, 0, 1});
    EXPECT_NEAR(north.uv.v, 1, 1e-12);
    EXPECT_EQ(north.uv.u, 0);
    // 45° below the equator in the xz-plane: v = acos(sin 45°)/π = 1/4.
    const double h = std::sqrt(0.5);
    EXPECT_NEAR(uvAt({-h, 0, -h}).uv.v, 0.25, 1e-12);
}

TEST(Sphere, BoundsAndClosed) {
    Bounds3 b = kSphere.Bounds();
    ExpectVecNear(b.lo, {-1, 0, 1});
    ExpectVecNear(b.hi, {3, 4, 5});
    EXPECT_TRUE(kSphere.IsClosed());
    EXPECT_TRUE(kSphere.IsBounded());
}

TEST(Sphere, CreateReadsRadiusThenCentre) {
    TestArgReader args({2, 1, 2, 3});
    auto prim = Sphere::Create(args);
    ASSERT_NE(prim, nullptr);
    EXPECT_TRUE(args.AllConsumed());
    EXPECT_TRUE(args.warnings.empty());
    EXPECT_NEAR(HitT(*prim, {{1, 2, -10}, {0, 0, 2}}), 5.5, 1e-12);
}

TEST(Sphere, CreateDiscardsTinyRadius) {
    TestArgReader args({1e-6, 0, 0, 0});
    EXPECT_EQ(Sphere::Create(args), nullptr);
    EXPECT_EQ(args.warnings.size(), 1u);
    EXPECT_TRUE(args.AllConsumed());
}

TEST(Sphere, CountersNamed) {
    EXPECT_EQ(kSphere.Counters().tests, RegisterCounter("Sphere tests"));
    EXPECT_EQ(kSphere.Counters().hits, RegisterCounter("Sphere hits"));
}

}  // namespace
}  // namespace rs
