#include "rayshade/progress_estimate.h"

#include <algorithm>
#include <utility>

namespace rs {

namespace {

// Measured on the shared scenes at 384 × 384 (balls, glass, planet, csg, blob, mtv): the
// first pass's list holds 1.32 to 1.97 pixels per pixel flagged on the single samples
// (median 1.6), and the later passes together 2.5% to 12% of the first list (median 4.5%);
// hence kQueuedPerFlagged = 1.6 · 1.06 ≈ 1.7 and:
// later passes, as a fraction of the first pass's list, before two lists give a ratio.
constexpr double kLaterPassFraction = 0.06;
// Later passes are projected as a geometric series of the last ratio, capped so that a
// ratio near 1 does not project an endless refinement.
constexpr double kMaxPassRatio = 0.8;
constexpr long kScale = 10000;  // fractions are reported in 1/10000ths

}  // namespace

FrameProgress::FrameProgress(int width, int height, int cells, ProgressFn report)
    : pixels_(static_cast<long>(width) * (height + 1)),
      interior_(std::max(0L, static_cast<long>(width) - 2) * std::max(0, height - 1)),
      border_(std::min(pixels_, 2L * width + 2L * height)),
      extra_(cells - 1),
      report_(std::move(report)) {
    total_ = pixels_ + border_ * extra_;  // no contrast test yet: nothing beyond the border
}

void FrameProgress::Add(long samples) {
    done_ += samples;
    Report();
}

void FrameProgress::FlaggedSoFar(long flagged, long tested) {
    if (extra_ == 0 || tested <= 0) return;
    const double priorWeight = 0.25 * static_cast<double>(interior_);
    const double fraction = (static_cast<double>(flagged) + kPriorFlaggedFraction * priorWeight) /
                            (static_cast<double>(tested) + priorWeight);
    const double queued =
        std::min(static_cast<double>(interior_), kQueuedPerFlagged * fraction * static_cast<double>(interior_));
    total_ = pixels_ + border_ * extra_ + static_cast<long>(queued * static_cast<double>(extra_));
    Report();
}

void FrameProgress::NextPass(long queued) {
    // Every earlier pass is complete when the next list is known: the rest is this list and
    // the passes after it.
    double later = kLaterPassFraction * static_cast<double>(queued);
    if (lastQueued_ > 0) {
        const double ratio = std::min(kMaxPassRatio, static_cast<double>(queued) / static_cast<double>(lastQueued_));
        later = static_cast<double>(queued) * ratio / (1 - ratio);
    }
    lastQueued_ = queued;
    total_ = done_ + static_cast<long>((static_cast<double>(queued) + later) * static_cast<double>(extra_));
    Report();
}

void FrameProgress::Finish() {
    std::lock_guard<std::mutex> lock(reportMutex_);
    shown_ = kScale;
    if (report_) report_(kScale, kScale);
}

void FrameProgress::Report() {
    if (!report_) return;
    std::unique_lock<std::mutex> lock(reportMutex_, std::try_to_lock);
    if (!lock.owns_lock()) return;  // another thread is reporting: the next call catches up
    const long total = std::max(total_.load(), 1L);
    // Below 100% until Finish: the estimate may still grow.
    const long fraction = std::min(kScale - 1, done_.load() * kScale / total);
    if (fraction <= shown_) return;
    shown_ = fraction;
    report_(shown_, kScale);
}

}  // namespace rs
