#include "rayshade/progress_estimate.h"

#include <gtest/gtest.h>

#include <vector>

namespace rs {
namespace {

// A 10 × 9 frame (100 pixels with the extra row), 2 × 2 samples (3 more per supersampled
// pixel): 8 × 8 interior pixels, a border of 2·10 + 2·9 = 38.
struct Recorder {
    std::vector<long> shown;
    ProgressFn Fn() {
        return [this](long done, long total) {
            EXPECT_EQ(total, 10000);
            shown.push_back(done);
        };
    }
};

TEST(FrameProgress, StartsWithSingleSamplesAndTheBorder) {
    Recorder r;
    FrameProgress p(10, 9, 4, r.Fn());
    EXPECT_EQ(p.EstimatedTotal(), 100 + 38 * 3);
    p.Add(107);
    ASSERT_EQ(r.shown.size(), 1u);
    EXPECT_EQ(r.shown.back(), 107 * 10000 / 214);
}

TEST(FrameProgress, FlaggedPixelsEstimateTheRefinement) {
    FrameProgress p(10, 9, 4, {});
    // 1 of 10 tested pixels flagged, with the prior 0.1 weighted as 64/4 = 16 tested: a
    // fraction (1 + 1.6)/(10 + 16) = 0.1, so 1.7 · 0.1 · 64 = 10.88 pixels, 32 samples.
    p.FlaggedSoFar(1, 10);
    EXPECT_EQ(p.EstimatedTotal(), 100 + 38 * 3 + 32);
    p.FlaggedSoFar(26, 26);  // 1.7 · (27.6/42) · 64 = 71.5: at most every interior pixel
    EXPECT_EQ(p.EstimatedTotal(), 100 + 38 * 3 + 64 * 3);
}

TEST(FrameProgress, EachPassListIsExactAndLaterPassesProjected) {
    FrameProgress p(10, 9, 4, {});
    p.Add(214);
    p.NextPass(20);  // this list, then 6% of it in later passes: 20 · 1.06 · 3 = 63.6
    EXPECT_EQ(p.EstimatedTotal(), 214 + 63);
    p.Add(60);
    p.NextPass(5);  // ratio 1/4: later passes 5 · (1/4)/(3/4), so (5 + 5/3) · 3 = 20
    EXPECT_EQ(p.EstimatedTotal(), 274 + 20);
    p.Add(15);
    p.NextPass(0);
    EXPECT_EQ(p.EstimatedTotal(), 289);
}

TEST(FrameProgress, NeverGoesBackNorReachesTheEndBeforeFinish) {
    Recorder r;
    FrameProgress p(10, 9, 4, r.Fn());
    p.Add(150);
    p.FlaggedSoFar(26, 26);  // the estimate grows: the fraction would fall
    p.Add(1);
    p.Add(1000);  // beyond any estimate
    p.Finish();
    ASSERT_GE(r.shown.size(), 2u);
    for (size_t i = 1; i < r.shown.size(); ++i) EXPECT_GT(r.shown[i], r.shown[i - 1]);
    EXPECT_EQ(r.shown[r.shown.size() - 2], 9999);
    EXPECT_EQ(r.shown.back(), 10000);
}

TEST(FrameProgress, WithoutSupersamplingOnlySingleSamplesCount) {
    FrameProgress p(10, 9, 1, {});
    EXPECT_EQ(p.EstimatedTotal(), 100);
    p.FlaggedSoFar(5, 10);
    EXPECT_EQ(p.EstimatedTotal(), 100);
}

}  // namespace
}  // namespace rs
