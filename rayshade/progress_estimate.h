// Progress of one frame, counted in eye-ray samples, with the work of adaptive
// supersampling estimated before it is known, so that the fraction reported grows roughly
// in proportion to time (a supersampled pixel costs n²−1 samples, many times a single one).
//
// The frame's work is: one sample per pixel; n²−1 more for each border pixel; n²−1 more
// for each pixel the contrast passes queue. The last is unknown until the passes run, so
// it is estimated in three stages:
//   1. while single samples are taken, from the fraction of the interior pixels tested so
//      far that exceed the contrast thresholds (starting from a prior), times
//      kQueuedPerFlagged (the pixels a flagged one eventually brings in: its
//      neighbourhood, and later passes);
//   2. once a pass's list is known, that list exactly, plus later passes projected from
//      the ratio of the last two lists (a geometric series);
//   3. at the end, exactly.
// The fraction reported never goes down: a raised estimate holds the bar still until the
// work catches up. Thread-safe; the callback is never run by two threads at once.
#pragma once

#include <atomic>
#include <mutex>

#include "rayshade/renderer.h"

namespace rs {

class FrameProgress {
  public:
    // Pixels the passes supersample per interior pixel flagged on the single samples
    // (measured, see the .cpp).
    static constexpr double kQueuedPerFlagged = 1.7;
    // The flagged fraction assumed before many rows are tested, weighted as if a quarter of
    // the interior had been: the first rows (often sky) say little about the rest.
    static constexpr double kPriorFlaggedFraction = 0.1;

    // A frame of width × height pixels plus the extra row below it (RenderFrame), with
    // `cells` samples per supersampled pixel (1: no supersampling).
    FrameProgress(int width, int height, int cells, ProgressFn report);

    // Work finished: `samples` eye rays (any thread).
    void Add(long samples);
    // Stage 1: `flagged` of `tested` interior pixels exceed the thresholds so far.
    void FlaggedSoFar(long flagged, long tested);
    // Stage 2: the next pass will supersample `queued` pixels (0: the refinement is over).
    void NextPass(long queued);
    // Reports 100%.
    void Finish();

    // The estimated total, in samples (for tests).
    long EstimatedTotal() const { return total_.load(); }

  private:
    void Report();

    const long pixels_;    // single samples, extra row included
    const long interior_;  // pixels the first contrast pass tests
    const long border_;    // pixels always supersampled: first and last rows, end columns
    const long extra_;  // samples a supersampled pixel adds to its single one
    ProgressFn report_;
    std::atomic<long> done_{0}, total_{0};
    std::mutex reportMutex_;
    long shown_ = 0;       // the largest fraction reported, in 1/10000ths
    long lastQueued_ = 0;  // the previous pass's list
};

}  // namespace rs
