#include "libobj/box.h"

#include <gtest/gtest.h>

#include "test_arg_reader.h"

namespace rs {
namespace {

using testing::ExpectVecNear;
using testing::HitT;
using testing::MustHit;
using testing::TestArgReader;

// Corners given in "wrong" order: the box is [−1, 1] × [−2, 1] × [−3, 1].
const Box kBox({1, 1, 1}, {-1, -2, -3});

TEST(Box, HitFromOutside) {
    Ray ray{{-5, 0, 0}, {2, 0, 0}};
    PrimitiveHit hit = MustHit(kBox, ray);
    EXPECT_NEAR(hit.t, 2, 1e-12);
    SurfaceNormals n = kBox.Normal(ray.At(hit.t), hit);
    ExpectVecNear(n.geometric, {-1, 0, 0});
    EXPECT_TRUE(kBox.Enters(ray, hit, n));
}

TEST(Box, HitFromInsideReturnsFarWall) {
    Ray ray{{0, 0, 0}, {0, 0, -0.5}};
    PrimitiveHit hit = MustHit(kBox, ray);
    EXPECT_NEAR(hit.t, 6, 1e-12);
    SurfaceNormals n = kBox.Normal(ray.At(hit.t), hit);
    ExpectVecNear(n.geometric, {0, 0, -1});
    EXPECT_FALSE(kBox.Enters(ray, hit, n));
}

TEST(Box, DiagonalRayEntersThroughLastSlab) {
    // From (−3,−3,−3) along (1,1,1): slabs entered at t = 2 (x), 1 (y), 0 (z).
    Ray ray{{-3, -3, -3}, {1, 1, 1}};
    PrimitiveHit hit = MustHit(kBox, ray);
    EXPECT_NEAR(hit.t, 2, 1e-12);
    ExpectVecNear(kBox.Normal(ray.At(hit.t), hit).geometric, {-1, 0, 0});
}

TEST(Box, Misses) {
    EXPECT_LT(HitT(kBox, {{0, 5, 0}, {1, 0, 0}}), 0);   // parallel, outside the y slab
    EXPECT_LT(HitT(kBox, {{-5, 0, 0}, {-1, 0, 0}}), 0);  // pointing away
    EXPECT_LT(HitT(kBox, {{-5, 0, 0}, {1, 1, 0}}), 0);   // passes beside
}

TEST(Box, RangeClipping) {
    Ray ray{{-5, 0, 0}, {2, 0, 0}};  // faces at t = 2 and 3
    EXPECT_LT(HitT(kBox, ray, 1e-5, 1.5), 0);
    PrimitiveHit hit = MustHit(kBox, ray, 2.5);
    EXPECT_NEAR(hit.t, 3, 1e-12);
    SurfaceNormals n = kBox.Normal(ray.At(hit.t), hit);
    ExpectVecNear(n.geometric, {1, 0, 0});
    EXPECT_FALSE(kBox.Enters(ray, hit, n));
}

TEST(Box, NormalFaceOrderAtCorner) {
    // A corner is within ε of three faces: +x is tested first.
    ExpectVecNear(kBox.Normal({1, 1, 1}, {}).geometric, {1, 0, 0});
    ExpectVecNear(kBox.Normal({-1, -2, -3}, {}).geometric, {-1, 0, 0});
    ExpectVecNear(kBox.Normal({0, -2, -3}, {}).geometric, {0, -1, 0});
}

TEST(Box, NoUVParameterisation) {
    SurfaceUV uv = kBox.UV({1, 0, 0}, {1, 0, 0}, {});
    EXPECT_EQ(uv.uv.u, 0);
    EXPECT_EQ(uv.uv.v, 0);
    ExpectVecNear(uv.dpdu, {1, 0, 0});
    ExpectVecNear(uv.dpdv, {0, 1, 0});
}

TEST(Box, BoundsAndClosed) {
    ExpectVecNear(kBox.Bounds().lo, {-1, -2, -3});
    ExpectVecNear(kBox.Bounds().hi, {1, 1, 1});
    EXPECT_TRUE(kBox.IsClosed());
}

TEST(Box, CreateAndDegenerate) {
    TestArgReader good({0, 0, 0, 1, 2, 3});
    ASSERT_NE(Box::Create(good), nullptr);
    EXPECT_TRUE(good.warnings.empty());
    TestArgReader flat({0, 0, 0, 1, 1, 1e-6});
    EXPECT_EQ(Box::Create(flat), nullptr);
    EXPECT_EQ(flat.warnings.size(), 1u);
    EXPECT_TRUE(flat.AllConsumed());
}

}  // namespace
}  // namespace rs
