#include "libobj/cone.h"

#include <gtest/gtest.h>

#include <cmath>

#include "libobj/cylinder.h"
#include "test_arg_reader.h"

namespace rs {
namespace {

using testing::ExpectVecNear;
using testing::HitT;
using testing::MustHit;
using testing::TestArgReader;

// Radius 1 at z = 0 growing to 2 at z = 1: the surface x² + y² = (z + 1)², apex at z = −1.
const Cone kCone(1, {0, 0, 0}, 2, {0, 0, 1});
const double kH = std::sqrt(0.5);

TEST(Cone, HitFromOutside) {
    // At z = 0.5 the radius is 1.5.
    Ray ray{{-5, 0, 0.5}, {1, 0, 0}};
    PrimitiveHit hit = MustHit(kCone, ray);
    EXPECT_NEAR(hit.t, 3.5, 1e-12);
    SurfaceNormals n = kCone.Normal(ray.At(hit.t), hit);
    // ∇(x² + y² − (z+1)²) ∝ (−1.5, 0, −1.5): outward and down.
    ExpectVecNear(n.geometric, {-kH, 0, -kH});
    EXPECT_TRUE(kCone.Enters(ray, hit, n));
}

TEST(Cone, HitFromInside) {
    Ray ray{{0, 0, 0.5}, {0, 2, 0}};
    PrimitiveHit hit = MustHit(kCone, ray);
    EXPECT_NEAR(hit.t, 0.75, 1e-12);
    ExpectVecNear(kCone.Normal(ray.At(hit.t), hit).geometric, {0, kH, -kH});
}

TEST(Cone, EndsLimitTheSurface) {
    EXPECT_LT(HitT(kCone, {{-5, 0, 1.5}, {1, 0, 0}}), 0);
    // z = −0.5 lies on the full cone (radius 0.5) but before the small end.
    EXPECT_LT(HitT(kCone, {{-5, 0, -0.5}, {1, 0, 0}}), 0);
    EXPECT_LT(HitT(kCone, {{0, 0, -5}, {0, 0, 1}}), 0);  // along the axis
}

TEST(Cone, RayParallelToAGeneratorHasOneRoot) {
    // Direction (1, 0, 1) is parallel to the generator x = z + 1 on the +x side, so the
    // quadratic term vanishes. From (−2, 0, −0.5): (t − 2)² = (t + 0.5)² gives t = 0.75,
    // the point (−1.25, 0, 0.25) where the radius is 1.25.
    EXPECT_NEAR(HitT(kCone, {{-2, 0, -0.5}, {1, 0, 1}}), 0.75, 1e-12);
}

TEST(Cone, RangeClipping) {
    Ray ray{{-5, 0, 0.5}, {1, 0, 0}};  // walls at t = 3.5 and 6.5
    EXPECT_LT(HitT(kCone, ray, 1e-5, 3.5), 0);
    EXPECT_NEAR(HitT(kCone, ray, 4), 6.5, 1e-12);
}

TEST(Cone, EndsGivenInEitherOrder) {
    const Cone swapped(2, {0, 0, 1}, 1, {0, 0, 0});
    EXPECT_NEAR(HitT(swapped, {{-5, 0, 0.5}, {1, 0, 0}}), 3.5, 1e-12);
    EXPECT_NEAR(swapped.UV({1.5, 0, 0.5}, {}, {}).uv.v, 0.5, 1e-12);
}

TEST(Cone, UV) {
    // Canonical z runs from s = 0.5 (small end) to 1; the point at z = 0.5 is halfway.
    SurfaceUV a = kCone.UV({1.5, 0, 0.5}, {}, {});
    EXPECT_NEAR(a.uv.u, 0, 1e-12);
    EXPECT_NEAR(a.uv.v, 0.5, 1e-12);
    ExpectVecNear(a.dpdu, {0, 1, 0});
    ExpectVecNear(a.dpdv, {kH, 0, kH});  // along the generator, away from the apex
    SurfaceUV b = kCone.UV({0, -1, 0}, {}, {});
    EXPECT_NEAR(b.uv.u, 0.75, 1e-12);
    EXPECT_NEAR(b.uv.v, 0, 1e-12);
    EXPECT_NEAR(kCone.UV({0, 2, 1}, {}, {}).uv.v, 1, 1e-12);
}

TEST(Cone, PointedCone) {
    // r1 = 0: the apex itself is the small end (s = 0).
    const Cone c(0, {0, 0, 0}, 1, {0, 0, 1});
    EXPECT_NEAR(HitT(c, {{-5, 0, 0.5}, {1, 0, 0}}), 4.5, 1e-12);
    EXPECT_NEAR(c.UV({0.5, 0, 0.5}, {}, {}).uv.v, 0.5, 1e-12);
}

TEST(Cone, Bounds) {
    ExpectVecNear(kCone.Bounds().lo, {-2, -2, 0});
    ExpectVecNear(kCone.Bounds().hi, {2, 2, 1});
}

TEST(Cone, CreateAndDegenerate) {
    TestArgReader good({1, 0, 0, 0, 2, 0, 0, 1});
    auto prim = Cone::Create(good);
    ASSERT_NE(prim, nullptr);
    EXPECT_NE(dynamic_cast<Cone*>(prim.get()), nullptr);
    EXPECT_TRUE(good.AllConsumed());
    EXPECT_NEAR(HitT(*prim, {{-5, 0, 0.5}, {1, 0, 0}}), 3.5, 1e-12);

    TestArgReader equalRadii({1, 0, 0, 0, 1 + 1e-7, 0, 0, 2});
    auto cyl = Cone::Create(equalRadii);
    ASSERT_NE(cyl, nullptr);
    EXPECT_NE(dynamic_cast<Cylinder*>(cyl.get()), nullptr);
    EXPECT_TRUE(equalRadii.warnings.empty());

    TestArgReader shortAxis({1, 0, 0, 0, 2, 0, 0, 1e-6});
    EXPECT_EQ(Cone::Create(shortAxis), nullptr);
    EXPECT_EQ(shortAxis.warnings.size(), 1u);
    TestArgReader negative({-1, 0, 0, 0, 2, 0, 0, 1});
    EXPECT_EQ(Cone::Create(negative), nullptr);
    EXPECT_EQ(negative.warnings.size(), 1u);
}

}  // namespace
}  // namespace rs
