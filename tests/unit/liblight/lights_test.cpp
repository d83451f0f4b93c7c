#include <gtest/gtest.h>

#include <cmath>

#include "libcommon/constants.h"
#include "liblight/area_light.h"
#include "liblight/directional_light.h"
#include "liblight/extended_light.h"
#include "liblight/point_light.h"
#include "liblight/spot_light.h"

namespace rs {
namespace {

TEST(PointLight, DirectionAndDistanceToThePoint) {
    PointLight light(Color(0.5), {0, 0, 10});
    Rng rng(1);
    LightSample s;
    ASSERT_TRUE(light.Sample({0, 0, 2}, -1, 1, rng, s));
    EXPECT_NEAR(s.shadeDir.z, 1, 1e-15);
    EXPECT_NEAR(s.shadowDist, 8, 1e-15);
    EXPECT_EQ(s.color, Color(0.5));  // no distance falloff
}

TEST(DirectionalLight, ConstantDirectionInfiniteDistance) {
    DirectionalLight light(Color(1), {1, -1, 1});
    Rng rng(1);
    LightSample s;
    ASSERT_TRUE(light.Sample({5, 5, 5}, -1, 1, rng, s));
    EXPECT_NEAR(s.shadeDir.x, 1 / std::sqrt(3.0), 1e-15);
    EXPECT_EQ(s.shadowDist, kFar);
}

TEST(SpotLight, SmoothstepBetweenOuterAndInnerCone) {
    // Aimed straight down from (0,0,10), inner 10°, outer 20°, coefficient 0 (no cosine
    // falloff), so the factor is exactly the smoothstep S(cosφ).
    SpotLight light(Color(1), {0, 0, 10}, {0, 0, 0}, 0, 10, 20);
    Rng rng(1);
    LightSample s;
    ASSERT_TRUE(light.Sample({0, 0, 0}, -1, 1, rng, s));
    EXPECT_NEAR(s.color.r, 1, 1e-12);  // inside the inner cone
    double at15 = 10 * std::tan(15 * kPi / 180);
    ASSERT_TRUE(light.Sample({at15, 0, 0}, -1, 1, rng, s));
    double co = std::cos(20 * kPi / 180), ci = std::cos(10 * kPi / 180), c = std::cos(15 * kPi / 180);
    double t = (c - co) / (ci - co);
    EXPECT_NEAR(s.color.r, t * t * (3 - 2 * t), 1e-12);
    double at25 = 10 * std::tan(25 * kPi / 180);
    EXPECT_FALSE(light.Sample({at25, 0, 0}, -1, 1, rng, s));
}

TEST(SpotLight, OmittedAnglesMeanNoCone) {
    SpotLight light(Color(1), {0, 0, 10}, {0, 0, 0}, 2, 180, 180);
    Rng rng(1);
    LightSample s;
    ASSERT_TRUE(light.Sample({10, 0, 0}, -1, 1, rng, s));
    // Only the cos^c falloff: cos 45° squared.
    EXPECT_NEAR(s.color.r, 0.5, 1e-12);
}

TEST(ExtendedLight, ShadowTargetsStayOnTheSquareAroundTheCentre) {
    ExtendedLight light(Color(1), 0.5, {0, 0, 10});
    Rng rng(3);
    for (int m = 0; m < 9; ++m) {
        LightSample s;
        ASSERT_TRUE(light.Sample({0, 0, 0}, m, 3, rng, s));
        EXPECT_NEAR(s.shadeDir.z, 1, 1e-15);  // shading uses the centre
        Vec3 target = s.shadowDir * s.shadowDist;
        EXPECT_NEAR(target.z, 10, 1e-12);      // square perpendicular to the centre direction
        EXPECT_LE(std::fabs(target.x), 0.5 + 1e-12);
        EXPECT_LE(std::fabs(target.y), 0.5 + 1e-12);
    }
}

TEST(AreaLightCell, SamplesInsideItsParallelogram) {
    AreaLightCell cell(Color(0.25), {0, 0, 5}, {1, 0, 0}, {0, 2, 0});
    Rng rng(9);
    for (int i = 0; i < 200; ++i) {
        LightSample s;
        ASSERT_TRUE(cell.Sample({0, 0, 0}, -1, 1, rng, s));
        Vec3 p = s.shadowDir * s.shadowDist;
        EXPECT_NEAR(p.z, 5, 1e-12);
        EXPECT_GE(p.x, 0);
        EXPECT_LE(p.x, 1);
        EXPECT_GE(p.y, 0);
        EXPECT_LE(p.y, 2);
    }
}

}  // namespace
}  // namespace rs
