// Time sampling for motion blur (spec §3.3, §3.15): each eye ray's time lies in the shutter
// interval [t_f, t_f + shutter), in the stratum of its sample number.
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "libshade/expression.h"
#include "libshade/parser.h"
#include "rayshade/renderer.h"
#include "rayshade/sampling.h"

namespace rs {
namespace {

TEST(ShutterTime, ClosedShutterGivesTheFrameTime) {
    EXPECT_EQ(ShutterTime(3.5, 0, 3, 5, 0.7), 3.5);
    EXPECT_EQ(ShutterTime(3.5, -1, 3, 5, 0.7), 3.5);
}

TEST(ShutterTime, SampleNumberPicksItsStratumOfTheShutter) {
    // n = 3: nine strata of width shutter/9 = 0.25 starting at t_f = 10.
    const double tf = 10, shutter = 2.25;
    for (int m = 0; m < 9; ++m) {
        EXPECT_DOUBLE_EQ(ShutterTime(tf, shutter, 3, m, 0), tf + 0.25 * m);  // no jitter
        for (double xi : {0.0, 0.25, 0.5, 0.999999}) {
            double t = ShutterTime(tf, shutter, 3, m, xi);
            EXPECT_GE(t, tf + 0.25 * m);
            EXPECT_LT(t, tf + 0.25 * (m + 1));
            EXPECT_NEAR(t, tf + 0.25 * (m + xi), 1e-12);
        }
    }
}

TEST(ShutterTime, ThePixelsCellsCoverEveryStratumOnce) {
    // The dither permutation maps the n² cells to distinct sample numbers, so one fully
    // sampled pixel sees each stratum of the shutter exactly once.
    for (int n = 1; n <= 8; ++n) {
        SamplingPattern pattern(n, FilterKind::Box, 1);
        std::set<int> strata;
        for (int cell = 0; cell < n * n; ++cell) {
            double t = ShutterTime(0, 1, n, pattern.SampleNumber(cell), 0.5);
            strata.insert(static_cast<int>(std::floor(t * n * n)));
        }
        EXPECT_EQ(static_cast<int>(strata.size()), n * n) << "n = " << n;
        EXPECT_EQ(*strata.begin(), 0);
        EXPECT_EQ(*strata.rbegin(), n * n - 1);
    }
}

// Renders a one-pixel image of `scene` (fully sampled: the border always is) and returns
// its alpha, the filtered fraction of samples that hit something.
double CoverageOfOnePixel(const std::string& scene) {
    RenderOptions options;
    options.threads = 1;
    Scene s = ParseSceneText(scene, "t.ray", options);
    SetCurrentFrame(0);
    const double frameTime = s.options.startTime;  // frame 0
    s.world->PrepareFrame(frameTime, s.options.shutter);
    Renderer renderer(s, nullptr);
    Image image = renderer.RenderFrame(0, frameTime, true);
    EXPECT_EQ(image.width, 1);
    EXPECT_EQ(image.channels, 4);
    return image.pixels[3] / 255.0;
}

TEST(MotionBlur, CoverageIsTheFractionOfTheShutterAnObjectIsInView) {
    // A sphere that fills the view (it spans 78° around the view axis, the pixel's samples at
    // most 50°) until time 0.5 and then jumps far away: with the shutter
    // open over [0, 1) exactly half of the 16 strata see it (jittered times never land on
    // the step itself).
    const char* kScene =
        "screen 1 1 sample 4 shutter 1\n"
        "sphere 1000 0 1010 0 translate 0 0 (linear(0.5, 0, 0.5, 100000))\n";
    EXPECT_NEAR(CoverageOfOnePixel(kScene), 0.5, 1.0 / 255);
}

TEST(MotionBlur, ShutterStartsAtTheFrameTime) {
    // Frame 0 starting at time 2 with shutter 0.25: times in [2, 2.25). A sphere in view
    // only for times in [2.125, 3) covers half the exposure; one in view only before 2 or
    // from 2.25 on is never seen.
    auto scene = [](double from, double to) {
        return "screen 1 1 sample 4 shutter 0.25 starttime 2\n"
               "sphere 1000 0 1010 0 translate 0 0 (linear(" + std::to_string(from) +
               ", 100000, " + std::to_string(from) + ", 0) + linear(" + std::to_string(to) +
               ", 0, " + std::to_string(to) + ", 100000))\n";
    };
    EXPECT_NEAR(CoverageOfOnePixel(scene(2.125, 3)), 0.5, 1.0 / 255);
    EXPECT_NEAR(CoverageOfOnePixel(scene(1, 2)), 0, 1e-12);
    EXPECT_NEAR(CoverageOfOnePixel(scene(2.25, 3)), 0, 1e-12);
}

}  // namespace
}  // namespace rs
