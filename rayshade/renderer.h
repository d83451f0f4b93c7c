// The frame loop of spec §3.3: one sample per pixel everywhere, then full n×n supersampling
// of the image border and of every pixel whose neighbourhood shows contrast above the
// thresholds, repeated until nothing changes.
//
// Determinism: every sample draws from a random stream keyed by (pixel, frame, cell), so
// the image does not depend on the number of threads or the order of work. Refinement
// passes test contrast over the whole image between passes (the original goes row by
// row); the set of supersampled pixels is therefore also independent of threads.
#pragma once

#include <algorithm>
#include <functional>
#include <limits>
#include <memory>
#include <type_traits>
#include <vector>

#include "libcommon/constants.h"
#include "libcommon/large_buffer.h"
#include "libimage/image.h"
#include "libshade/scene.h"
#include "rayshade/camera.h"
#include "rayshade/sampling.h"
#include "rayshade/tracer.h"
#include "rayshade/worker_pool.h"

namespace rs {

// The rendered region of the screen (spec §3.2 "Window and crop").
struct RenderWindow {
    int minX = 0, maxX = 0, minY = 0, maxY = 0;
    int Width() const { return maxX - minX + 1; }
    int Height() const { return maxY - minY + 1; }
};

// Computes the window from options; reports Abort "Invalid window specification" when it
// falls outside the screen.
RenderWindow ComputeWindow(const RenderOptions& options);

// The contrast test of spec §3.3 on a pixel and its four neighbours: true when, in some
// channel, (max - min) / (max + min) exceeds that channel's threshold.
inline bool ContrastExceeds(const Color (&five)[5], const Color& threshold) {
    Color lo = five[0], hi = lo;
    for (const Color& c : five) {
        lo = {std::min(lo.r, c.r), std::min(lo.g, c.g), std::min(lo.b, c.b)};
        hi = {std::max(hi.r, c.r), std::max(hi.g, c.g), std::max(hi.b, c.b)};
    }
    auto exceeds = [](double mn, double mx, double t) {
        double sum = mx + mn;
        return sum > kEpsilon && (mx - mn) / sum > t;
    };
    return exceeds(lo.r, hi.r, threshold.r) || exceeds(lo.g, hi.g, threshold.g) ||
           exceeds(lo.b, hi.b, threshold.b);
}

// Progress callback: `done` of `total` units of work finished (never called by two threads
// at once).
using ProgressFn = std::function<void(long done, long total)>;

// One pixel's state: its single sample until it is supersampled, then the filtered n×n
// result (which reuses the single sample for its cell). Kept small (20 bytes): a frame holds
// one per pixel. Single precision is plenty for values that end as 8-bit channels.
// Trivially constructible, so a frame's states are allocated without a serial zeroing
// pass: the renderer value-initialises them (PixelState{}, all zero) on its threads, and
// the first touch of fresh memory, expensive on virtual machines, happens in parallel.
struct PixelState {
    float r, g, b;
    float alpha;
    int16_t singleCell;
    bool sampled : 1;       // the single sample has been taken
    bool supersampled : 1;

    Color Value() const { return {r, g, b}; }
    // Values beyond float's range (a light of intensity 1e300) saturate at ±FLT_MAX instead of
    // becoming infinite; NaN stays NaN (Renderer::Encode counts it).
    void SetValue(const Color& c) {
        r = ToFloat(c.r);
        g = ToFloat(c.g);
        b = ToFloat(c.b);
    }
    static float ToFloat(double v) {
        constexpr double kMax = std::numeric_limits<float>::max();
        return static_cast<float>(v > kMax ? kMax : v < -kMax ? -kMax : v);
    }
};

static_assert(std::is_trivially_default_constructible_v<PixelState> && sizeof(PixelState) == 20);

// Everything needed to continue a frame where it stopped; the renderer updates it as it
// goes and hands it to the checkpoint callback. Continuing from a saved state gives the
// same image as an uninterrupted render, because every sample's random stream is keyed by
// its pixel and cell, not by the order of work.
struct FrameState {
    enum class Phase : int { SingleSamples = 0, Border = 1, Refinement = 2, Done = 3 };
    int frame = 0;
    int width = 0, rows = 0;  // rows includes the extra row below the window
    Phase phase = Phase::SingleSamples;
    int pass = 0;             // refinement passes completed
    // The pixels the current refinement pass supersamples, in increasing order.
    std::vector<long, LargeBufferAllocator<long>> todo;
    std::vector<PixelState, LargeBufferAllocator<PixelState>> pixels;
};

// Called by the renderer at safe points with the current state; `final` is true when the
// render stops early (stop requested) and the state must be kept.
using CheckpointFn = std::function<void(const FrameState& state, bool final)>;

// Asks every render in progress to stop at the next safe point (async-signal-safe).
void RequestStop();
bool StopRequested();

// Thrown by RenderFrame when a stop was requested; the checkpoint callback has saved the
// state by then.
struct RenderStopped {};

class Renderer {
  public:
    // Renders on `workers` (ThreadCount(scene.options) threads, made by the caller so the
    // same threads can prepare the scene first), or on a pool of its own.
    Renderer(const Scene& scene, ProgressFn progress, WorkerPool& workers);
    Renderer(const Scene& scene, ProgressFn progress);

    // Renders frame number `frame` whose shutter opens at `frameTime`. The image is RGB, or
    // RGBA when `withAlpha` (alpha = filtered fraction of samples that hit something).
    // `resumeFrom`, when given, is a state saved by an earlier, interrupted render of the
    // same frame; `checkpoint` is offered the state about every `checkpointSeconds`.
    Image RenderFrame(int frame, double frameTime, bool withAlpha,
                      FrameState* resumeFrom = nullptr, CheckpointFn checkpoint = {},
                      double checkpointSeconds = 10);

    // The number of threads a render uses: -t N, or every core.
    static int ThreadCount(const RenderOptions& options);

  private:
    // Renders on *shared, or on `own` when shared is null.
    Renderer(const Scene& scene, ProgressFn progress, std::unique_ptr<WorkerPool> own,
             WorkerPool* shared);
    using Pixel = PixelState;

    void TakeSingleSample(int x, int y, Pixel& px) const;
    void Supersample(int x, int y, Pixel& px) const;
    Color SampleCell(int absX, int absY, int cell, Rng& rng, double& alpha) const;
    // Runs body(i) for i in [0, count) on the worker threads; stops handing out work when
    // a stop is requested.
    void ParallelFor(long count, const std::function<void(long)>& body) const {
        workers_.Run(count, body, true);
    }
    // The same, but always runs every i (work that must complete: initialisation, encoding).
    void ParallelForAll(long count, const std::function<void(long)>& body) const {
        workers_.Run(count, body, false);
    }
    bool NeedsRefinement(const Pixel* pixels, int x, int y) const;
    // A window smaller than the screen (window_render.cpp): supersamples exactly the pixels
    // the full-screen render supersamples there, so tiles paste into the full image.
    bool WindowIsScreen() const;
    Image RenderSubWindow(bool withAlpha, FrameState* resumeFrom, const CheckpointFn& checkpoint,
                          double checkpointSeconds);
    Image Encode(const FrameState& state, bool withAlpha) const;
    const Scene& scene_;
    const RenderOptions& options_;
    RenderWindow window_;
    CameraSetup camera_;
    SamplingPattern pattern_;
    Tracer tracer_;
    ProgressFn progress_;
    std::unique_ptr<WorkerPool> ownWorkers_;  // when constructed without a pool
    WorkerPool& workers_;                     // runs the const rendering loops
    int frame_ = 0;
    double frameTime_ = 0;
};

}  // namespace rs
