#include "libobj/disc.h"

#include <gtest/gtest.h>

#include "test_arg_reader.h"

namespace rs {
namespace {

using testing::ExpectVecNear;
using testing::HitT;
using testing::MustHit;
using testing::TestArgReader;

const Disc kDisc(2, {0, 0, 0}, {0, 0, 3});

TEST(Disc, HitInsideRadius) {
    Ray ray{{1, 1, 5}, {0, 0, -2}};
    PrimitiveHit hit = MustHit(kDisc, ray);
    EXPECT_NEAR(hit.t, 2.5, 1e-12);
    ExpectVecNear(kDisc.Normal(ray.At(hit.t), hit).geometric, {0, 0, 1});
    // From below as well.
    EXPECT_NEAR(HitT(kDisc, {{1, 1, -1}, {0, 0, 1}}), 1, 1e-12);
}

TEST(Disc, MissOutsideRadius) {
    // |(1.5, 1.5)|² = 4.5 > 4.
    EXPECT_LT(HitT(kDisc, {{1.5, 1.5, 5}, {0, 0, -1}}), 0);
    EXPECT_LT(HitT(kDisc, {{1, 1, 5}, {1, 0, 0}}), 0);
    EXPECT_LT(HitT(kDisc, {{1, 1, 5}, {0, 0, -1}}, 1e-5, 5), 0);
}

TEST(Disc, UV) {
    SurfaceUV a = kDisc.UV({1, 0, 0}, {0, 0, 1}, {});
    EXPECT_NEAR(a.uv.u, 0, 1e-12);
    EXPECT_NEAR(a.uv.v, 0.5, 1e-12);
    ExpectVecNear(a.dpdv, {1, 0, 0});
    ExpectVecNear(a.dpdu, {0, 1, 0});
    SurfaceUV b = kDisc.UV({0, -1, 0}, {0, 0, 1}, {});
    EXPECT_NEAR(b.uv.u, 0.75, 1e-12);
    SurfaceUV c = kDisc.UV({0, 2, 0}, {0, 0, 1}, {});
    EXPECT_NEAR(c.uv.u, 0.25, 1e-12);
    EXPECT_NEAR(c.uv.v, 1, 1e-12);
}

TEST(Disc, TightBoundsForTiltedDisc) {
    Disc d(2, {1, 2, 3}, {1, 0, 0});
    ExpectVecNear(d.Bounds().lo, {1, 0, 1});
    ExpectVecNear(d.Bounds().hi, {1, 4, 5});
}

TEST(Disc, CreateAndDegenerate) {
    TestArgReader good({2, 0, 0, 0, 0, 0, 1});
    ASSERT_NE(Disc::Create(good), nullptr);
    EXPECT_TRUE(good.AllConsumed());
    TestArgReader tiny({1e-7, 0, 0, 0, 0, 0, 1});
    EXPECT_EQ(Disc::Create(tiny), nullptr);
    EXPECT_EQ(tiny.warnings.size(), 1u);
    TestArgReader zero({1, 0, 0, 0, 0, 0, 0});
    EXPECT_EQ(Disc::Create(zero), nullptr);
    EXPECT_EQ(zero.warnings.size(), 1u);
}

}  // namespace
}  // namespace rs
