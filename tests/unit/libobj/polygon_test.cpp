#include "libobj/polygon.h"

#include <gtest/gtest.h>

#include <cmath>

#include "libcommon/constants.h"
#include "test_arg_reader.h"

namespace rs {
namespace {

using testing::ExpectVecNear;
using testing::HitT;
using testing::MustHit;
using testing::TestArgReader;

Ray Down(double x, double y) { return {{x, y, 5}, {0, 0, -2}}; }

TEST(Polygon, SquareHitAndNormal) {
    const Polygon square({{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}}, false);
    PrimitiveHit hit = MustHit(square, Down(1, 1));
    EXPECT_NEAR(hit.t, 2.5, 1e-12);
    ExpectVecNear(square.Normal({1, 1, 0}, hit).geometric, {0, 0, 1});
    EXPECT_LT(HitT(square, Down(3, 1)), 0);
    EXPECT_LT(HitT(square, Down(1, 1), 1e-5, 2), 0);
    // Newell: twice the area along the normal.
    ExpectVecNear(Polygon::NewellNormal({{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}}),
                  {0, 0, 8});
}

TEST(Polygon, NonConvex) {
    // An L shape: the notch (1.5, 1.5) is outside.
    const Polygon ell({{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}, {1, 2, 0}, {0, 2, 0}}, false);
    EXPECT_GT(HitT(ell, Down(0.5, 1.5)), 0);
    EXPECT_GT(HitT(ell, Down(1.5, 0.5)), 0);
    EXPECT_LT(HitT(ell, Down(1.5, 1.5)), 0);
}

TEST(Polygon, PentagramCentreIsInsideByNonZeroWinding) {
    // Vertices every 144° on the unit circle: the centre has winding number 2 (it would be
    // outside under the even-odd rule); a tip region has winding 1.
    std::vector<Vec3> star;
    for (int k = 0; k < 5; ++k) {
        const double a = kPi / 2 + k * 4 * kPi / 5;
        star.push_back({std::cos(a), std::sin(a), 0});
    }
    const Polygon p(star, false);
    EXPECT_GT(HitT(p, Down(0, 0)), 0);
    EXPECT_GT(HitT(p, Down(0, 0.8)), 0);
    EXPECT_LT(HitT(p, Down(0.5, 0.8)), 0);
}

TEST(Polygon, VerticalPlane) {
    // In the xz-plane: the dominant normal axis is y.
    const Polygon p({{0, 0, 0}, {0, 0, 1}, {1, 0, 1}, {1, 0, 0}}, false);
    ExpectVecNear(p.Normal({0.5, 0, 0.5}, {}).geometric, {0, 1, 0});
    EXPECT_NEAR(HitT(p, {{0.5, 4, 0.5}, {0, -0.5, 0}}), 8, 1e-12);
    EXPECT_LT(HitT(p, {{1.5, 4, 0.5}, {0, -0.5, 0}}), 0);
}

TEST(Polygon, UVIsObjectXY) {
    const Polygon square({{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}}, false);
    SurfaceUV uv = square.UV({1.5, 0.25, 0}, {0, 0, 1}, {});
    EXPECT_EQ(uv.uv.u, 1.5);
    EXPECT_EQ(uv.uv.v, 0.25);
}

TEST(Polygon, CreateReadsVerticesWhileNumbersFollow) {
    TestArgReader args({0, 0, 0, 2, 0, 0, 2, 2, 0, 0, 2, 0}, /*flip=*/true);
    auto prim = Polygon::Create(args);
    ASSERT_NE(prim, nullptr);
    EXPECT_TRUE(args.AllConsumed());
    ExpectVecNear(prim->Normal({1, 1, 0}, {}).geometric, {0, 0, -1});
    ExpectVecNear(prim->Bounds().hi, {2, 2, 0});
    EXPECT_EQ(prim->Counters().hits, RegisterCounter("Polygon hits"));
}

TEST(Polygon, DegenerateInput) {
    TestArgReader two({0, 0, 0, 1, 0, 0});
    EXPECT_THROW(Polygon::Create(two), FatalError);
    TestArgReader colinear({0, 0, 0, 1, 1, 1, 2, 2, 2});
    EXPECT_EQ(Polygon::Create(colinear), nullptr);
    EXPECT_EQ(colinear.warnings.size(), 1u);
}

}  // namespace
}  // namespace rs
