#include "libobj/plane.h"

#include <gtest/gtest.h>

#include "test_arg_reader.h"

namespace rs {
namespace {

using testing::ExpectVecNear;
using testing::HitT;
using testing::MustHit;
using testing::TestArgReader;

// z = 1, normal given with length 2.
const Plane kPlane({0, 0, 1}, {0, 0, 2});

TEST(Plane, HitFromBothSides) {
    Ray above{{3, 4, 5}, {0, 0, -2}};
    PrimitiveHit hit = MustHit(kPlane, above);
    EXPECT_NEAR(hit.t, 2, 1e-12);
    SurfaceNormals n = kPlane.Normal(above.At(hit.t), hit);
    ExpectVecNear(n.geometric, {0, 0, 1});
    EXPECT_TRUE(kPlane.Enters(above, hit, n));
    Ray below{{3, 4, -1}, {0, 0, 0.5}};
    hit = MustHit(kPlane, below);
    EXPECT_NEAR(hit.t, 4, 1e-12);
    EXPECT_FALSE(kPlane.Enters(below, hit, kPlane.Normal(below.At(hit.t), hit)));
}

TEST(Plane, Misses) {
    EXPECT_LT(HitT(kPlane, {{3, 4, 5}, {1, 0, 0}}), 0);   // parallel
    EXPECT_LT(HitT(kPlane, {{3, 4, 5}, {0, 0, 1}}), 0);   // away
    EXPECT_LT(HitT(kPlane, {{3, 4, 5}, {0, 0, -1}}, 1e-5, 4), 0);  // beyond tMax
}

TEST(Plane, UnboundedAndOpen) {
    EXPECT_FALSE(kPlane.IsBounded());
    EXPECT_FALSE(kPlane.IsClosed());
}

TEST(Plane, UVUsesTheRayFacingNormal) {
    // Facing +z: Û = (1,0,0), V̂ = (0,1,0) (spec §3.11.1); facing −z: Û = (−1,0,0),
    // V̂ = (0,1,0), so u is mirrored on the back side.
    SurfaceUV front = kPlane.UV({3, 4, 1}, {0, 0, 1}, {});
    EXPECT_NEAR(front.uv.u, 3, 1e-12);
    EXPECT_NEAR(front.uv.v, 4, 1e-12);
    ExpectVecNear(front.dpdu, {1, 0, 0});
    ExpectVecNear(front.dpdv, {0, 1, 0});
    SurfaceUV back = kPlane.UV({3, 4, 1}, {0, 0, -1}, {});
    EXPECT_NEAR(back.uv.u, -3, 1e-12);
    EXPECT_NEAR(back.uv.v, 4, 1e-12);
}

TEST(Plane, CreateAndDegenerate) {
    TestArgReader good({0, 0, 1, 0, 0, 2});
    auto prim = Plane::Create(good);
    ASSERT_NE(prim, nullptr);
    EXPECT_NEAR(HitT(*prim, {{3, 4, 5}, {0, 0, -2}}), 2, 1e-12);
    TestArgReader zero({0, 0, 1, 0, 0, 0});
    EXPECT_EQ(Plane::Create(zero), nullptr);
    EXPECT_EQ(zero.warnings.size(), 1u);
}

}  // namespace
}  // namespace rs
