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

TEST(Polygon, ManyVerticesMatchTheFanTest) {
    // A gear-like outline, star-shaped from the origin (radius 1 ± 0.3 over 24 teeth,
    // 144 vertices: the banded winding test). A point is inside exactly when it lies on the
    // inner side of the edge of its angular sector; points at the vertices' own heights
    // (band boundaries) are included. The winding test must agree everywhere.
    constexpr int kVertices = 144;
    std::vector<Vec3> gear;
    for (int k = 0; k < kVertices; ++k) {
        const double a = 2 * kPi * k / kVertices;
        const double r = 1 + 0.3 * ((k / 3) % 2 == 0 ? 1 : -1);
        gear.push_back({r * std::cos(a), r * std::sin(a), 0});
    }
    const Polygon p(gear, false);
    const auto insideByFan = [&](double x, double y) {
        double a = std::atan2(y, x);
        if (a < 0) a += 2 * kPi;
        const int k = static_cast<int>(a / (2 * kPi) * kVertices) % kVertices;
        const Vec3& v0 = gear[k];
        const Vec3& v1 = gear[(k + 1) % kVertices];
        // Counter-clockwise outline: inside is to the left of v0 → v1.
        return (v1.x - v0.x) * (y - v0.y) - (v1.y - v0.y) * (x - v0.x) > 0;
    };
    uint64_t state = 12345;
    const auto uniform = [&] {
        state = state * 6364136223846793005ull + 1442695040888963407ull;
        return static_cast<double>(state >> 11) * 0x1p-53 * 3 - 1.5;
    };
    int inside = 0;
    for (int i = 0; i < 4000; ++i) {
        const double x = uniform();
        const double y = i % 4 == 0 ? gear[i % kVertices].y : uniform();
        const bool expected = insideByFan(x, y);
        inside += expected;
        EXPECT_EQ(HitT(p, Down(x, y)) > 0, expected) << x << " " << y;
    }
    EXPECT_GT(inside, 500);  // both answers occur
    EXPECT_LT(inside, 3500);
}

TEST(Polygon, ManyVerticesKeepTheNonZeroRule) {
    // The star polygon {29/5}: the centre is wound 5 times, a point outside the circle 0.
    std::vector<Vec3> star;
    for (int k = 0; k < 29; ++k) {
        const double a = k * 5 * 2 * kPi / 29;
        star.push_back({std::cos(a), std::sin(a), 0});
    }
    const Polygon p(star, false);
    EXPECT_GT(HitT(p, Down(0, 0)), 0);
    EXPECT_GT(HitT(p, Down(0.1, -0.2)), 0);
    EXPECT_LT(HitT(p, Down(1.2, 0)), 0);
    EXPECT_LT(HitT(p, Down(0, -1.01)), 0);
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
