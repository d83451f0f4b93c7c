// Time-varying transformations (spec §3.15): parameters that use `time`, `frame` or
// `linear` are evaluated at each ray's own time.
#include <gtest/gtest.h>

#include <cmath>

#include "libcommon/constants.h"
#include "libobj/hit.h"
#include "libshade/expression.h"
#include "libshade/parser.h"

namespace rs {
namespace {

// Distance along a ray at `time` from (x, −10, z) towards +y to the first hit, or −1.
double HitDistance(const Scene& scene, double x, double z, double time) {
    HitRecord hit;
    double tMax = kFar;
    Ray ray{{x, -10, z}, {0, 1, 0}, time};
    return scene.world->Intersect(ray, kEpsilon, tMax, hit) ? hit.t() : -1;
}

// Parses `text` and readies it for frame `frame` (as the renderer does: the frame number is
// set before the bounds are computed).
Scene Prepared(const std::string& text, double frameTime, double shutter, int frame = 0) {
    Scene scene = ParseSceneText(text, "t.ray", RenderOptions());
    SetCurrentFrame(frame);
    scene.world->PrepareFrame(frameTime, shutter);
    return scene;
}

TEST(Animation, TranslationFollowsEachRaysTime) {
    // A unit sphere moving along x at 3 units per unit time over the shutter [0, 2).
    Scene s = Prepared("sphere 1 0 0 0 translate (3 * time) 0 0\n", 0, 2);
    EXPECT_NEAR(HitDistance(s, 0, 0, 0), 9, 1e-9);
    EXPECT_EQ(HitDistance(s, 0, 0, 1), -1);        // the sphere is at x = 3 by then
    EXPECT_NEAR(HitDistance(s, 3, 0, 1), 9, 1e-9);
    EXPECT_NEAR(HitDistance(s, 4.5, 0, 1.5), 9, 1e-9);
    // At time 0.5 the centre is at x = 1.5.
    EXPECT_NEAR(HitDistance(s, 1.5, 0, 0.5), 9, 1e-9);
}

TEST(Animation, LinearDrivesADefinedVariable) {
    // The coin.ray idiom: a defined variable built on linear(); it rises from z = 0 at time 1
    // to z = 4 at time 3 and stays there.
    Scene s = Prepared("define lift (linear(1, 0, 3, 4))\n"
                       "sphere 0.5 0 0 0 translate 0 0 (lift)\n",
                       0, 4);
    for (double time : {0.0, 1.0}) EXPECT_NEAR(HitDistance(s, 0, 0, time), 9.5, 1e-9);
    EXPECT_NEAR(HitDistance(s, 0, 2, 2), 9.5, 1e-9);
    EXPECT_EQ(HitDistance(s, 0, 0, 2), -1);
    for (double time : {3.0, 3.9}) EXPECT_NEAR(HitDistance(s, 0, 4, time), 9.5, 1e-9);
}

TEST(Animation, StaticAndAnimatedStepsComposeInWrittenOrder) {
    // scale 2, then move by time along x: the sphere of radius 2 is centred at (time, 0, 0).
    // (Written the other way round the motion would be doubled.)
    Scene s = Prepared("sphere 1 0 0 0 scale 2 2 2 translate (time) 0 0\n", 0, 4);
    EXPECT_NEAR(HitDistance(s, 3, 0, 3), 8, 1e-9);
    EXPECT_EQ(HitDistance(s, 6.5, 0, 3), -1);
}

TEST(Animation, RotationAngleFromTime) {
    // A unit sphere at x = 5 rotated about z by 90°·time: at time 1 it sits at y = 5, on
    // the ray through x = 0, z = 0 (which reaches its near side at y = 4, distance 14).
    Scene s = Prepared("sphere 1 5 0 0 rotate 0 0 1 (90 * time)\n", 0, 1);
    EXPECT_NEAR(HitDistance(s, 5, 0, 0), 10 - 1, 1e-9);
    EXPECT_NEAR(HitDistance(s, 0, 0, 1), 14, 1e-9);
}

TEST(Animation, FrameIsTheFrameNumberNotTheTime) {
    const char* kScene = "sphere 1 0 0 0 translate (2 * frame) 0 0\n";
    Scene third = Prepared(kScene, 3, 1, 3);
    EXPECT_NEAR(HitDistance(third, 6, 0, 3), 9, 1e-9);
    EXPECT_NEAR(HitDistance(third, 6, 0, 3.9), 9, 1e-9);  // no blur within the frame
    EXPECT_EQ(HitDistance(third, 0, 0, 3), -1);
    Scene first = Prepared(kScene, 0, 1, 0);
    EXPECT_NEAR(HitDistance(first, 0, 0, 0), 9, 1e-9);
}

}  // namespace
}  // namespace rs
