// The frame loop of spec §3.3: one sample per pixel everywhere, then full n×n supersampling
// of the image border and of every pixel whose neighbourhood shows contrast above the
// thresholds, repeated until nothing changes.
//
// Determinism: every sample draws from a random stream keyed by (pixel, frame, cell), so
// the image does not depend on the number of threads or the order of work. Refinement
// passes test contrast over the whole image between passes (the original goes row by
// row); the set of supersampled pixels is therefore also independent of threads.
#pragma once

#include <functional>
#include <vector>

#include "libimage/image.h"
#include "libshade/scene.h"
#include "rayshade/camera.h"
#include "rayshade/sampling.h"
#include "rayshade/tracer.h"

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

// Progress callback: `done` of `total` units of work finished (called from one thread).
using ProgressFn = std::function<void(long done, long total)>;

class Renderer {
  public:
    Renderer(const Scene& scene, ProgressFn progress);

    // Renders frame number `frame` whose shutter opens at `frameTime`. The image is RGB, or
    // RGBA when `withAlpha` (alpha = filtered fraction of samples that hit something).
    Image RenderFrame(int frame, double frameTime, bool withAlpha);

  private:
    struct Pixel {
        Color single;
        double singleAlpha = 0;
        int singleCell = 0;
        Color full;
        double fullAlpha = 0;
        bool supersampled = false;
    };

    void TakeSingleSample(int x, int y, Pixel& px) const;
    void Supersample(int x, int y, Pixel& px) const;
    Color SampleCell(int absX, int absY, int cell, Rng& rng, double& alpha) const;
    // Runs body(i) for i in [0, count) on the worker threads.
    void ParallelFor(long count, const std::function<void(long)>& body) const;
    bool NeedsRefinement(const std::vector<Pixel>& pixels, int x, int y) const;
    const Color& Value(const Pixel& px) const { return px.supersampled ? px.full : px.single; }

    const Scene& scene_;
    const RenderOptions& options_;
    RenderWindow window_;
    CameraSetup camera_;
    SamplingPattern pattern_;
    Tracer tracer_;
    ProgressFn progress_;
    int threads_;
    int frame_ = 0;
    double frameTime_ = 0;
};

}  // namespace rs
