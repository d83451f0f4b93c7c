#include "rayshade/renderer.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <thread>

#include "libcommon/constants.h"
#include "libcommon/error.h"
#include "libcommon/stats.h"

namespace rs {

namespace {

const CounterId kSupersampled = RegisterCounter("supersampled pixels");

// Purpose tags that separate the random streams of one pixel.
constexpr uint64_t kSingleSampleStream = 0;
constexpr uint64_t kCellStreamBase = 1;

uint8_t EncodeChannel(double v, double exponent) {
    if (!(v > 0)) return 0;  // also maps NaN to 0
    if (exponent != 1) v = std::pow(v, exponent);
    if (v >= 1) return 255;
    return static_cast<uint8_t>(255 * v);
}

}  // namespace

RenderWindow ComputeWindow(const RenderOptions& o) {
    double wx0 = o.window[0], wx1 = o.window[1] < 0 ? o.xres - 1 : o.window[1];
    double wy0 = o.window[2], wy1 = o.window[3] < 0 ? o.yres - 1 : o.window[3];
    double crop[4];
    for (int i = 0; i < 4; ++i) crop[i] = std::clamp(o.crop[i], 0.0, 1.0);
    if (crop[0] > crop[1]) std::swap(crop[0], crop[1]);
    if (crop[2] > crop[3]) std::swap(crop[2], crop[3]);
    RenderWindow w;
    w.minX = static_cast<int>(wx0 + crop[0] * (wx1 - wx0));
    w.maxX = static_cast<int>(wx0 + crop[1] * (wx1 - wx0));
    w.minY = static_cast<int>(wy0 + crop[2] * (wy1 - wy0));
    w.maxY = static_cast<int>(wy0 + crop[3] * (wy1 - wy0));
    if (w.minX < 0 || w.minY < 0 || w.maxX >= o.xres || w.maxY >= o.yres || w.minX > w.maxX ||
        w.minY > w.maxY)
        Report(Severity::Abort, {}, "Invalid window specification");
    return w;
}

Renderer::Renderer(const Scene& scene, ProgressFn progress)
    : scene_(scene),
      options_(scene.options),
      window_(ComputeWindow(scene.options)),
      camera_(scene.camera, scene.options),
      pattern_(scene.options.samples, scene.options.filter,
               scene.options.filterWidth > 0
                   ? scene.options.filterWidth
                   : (scene.options.filter == FilterKind::Gauss ? 1.8 : 1.0)),
      tracer_(scene),
      progress_(std::move(progress)) {
    unsigned hw = std::thread::hardware_concurrency();
    threads_ = options_.threads > 0 ? options_.threads : static_cast<int>(hw ? hw : 1);
}

void Renderer::ParallelFor(long count, const std::function<void(long)>& body) const {
    std::atomic<long> next{0};
    std::atomic<long> done{0};
    auto worker = [&] {
        for (long i; (i = next.fetch_add(1)) < count;) {
            body(i);
            done.fetch_add(1);
        }
    };
    int n = static_cast<int>(std::min<long>(threads_, std::max<long>(count, 1)));
    std::vector<std::thread> pool;
    for (int t = 1; t < n; ++t) pool.emplace_back(worker);
    worker();
    for (std::thread& t : pool) t.join();
}

Color Renderer::SampleCell(int absX, int absY, int cell, Rng& rng, double& alpha) const {
    const int n = pattern_.PerSide();
    const int sampleNumber = pattern_.SampleNumber(cell);
    double jx = 0, jy = 0;
    if (options_.jitter) {
        jx = rng.Uniform();
        jy = rng.Uniform();
    }
    double sx = absX + pattern_.CellOffsetX(cell) + jx * pattern_.CellSize();
    double sy = absY + pattern_.CellOffsetY(cell) + jy * pattern_.CellSize();
    double time = frameTime_;
    if (options_.shutter > 0)
        time += options_.shutter / (n * n) * (sampleNumber + (options_.jitter ? rng.Uniform() : 0));
    double lx = 0, ly = 0;
    if (camera_.HasAperture()) SquareSample(sampleNumber, n, rng, lx, ly);
    SampleState state{sampleNumber, n, &rng};
    bool hit = false;
    Color c = tracer_.TraceEye(camera_.EyeRay(sx, sy, lx, ly, time), state, hit);
    alpha = hit ? 1 : 0;
    return c;
}

void Renderer::TakeSingleSample(int x, int y, Pixel& px) const {
    int absX = window_.minX + x, absY = window_.minY + y;
    Rng rng = Rng::ForKey(absX, absY, frame_, kSingleSampleStream);
    int cells = pattern_.Cells();
    px.singleCell = std::min(cells - 1, static_cast<int>(rng.Uniform() * cells));
    px.single = SampleCell(absX, absY, px.singleCell, rng, px.singleAlpha);
}

void Renderer::Supersample(int x, int y, Pixel& px) const {
    int absX = window_.minX + x, absY = window_.minY + y;
    Color sum;
    double alpha = 0;
    for (int cell = 0; cell < pattern_.Cells(); ++cell) {
        double w = pattern_.Weight(cell);
        if (cell == px.singleCell) {
            sum += px.single * w;
            alpha += px.singleAlpha * w;
            continue;
        }
        Rng rng = Rng::ForKey(absX, absY, frame_, kCellStreamBase + cell);
        double a = 0;
        sum += SampleCell(absX, absY, cell, rng, a) * w;
        alpha += a * w;
    }
    px.full = sum;
    px.fullAlpha = alpha;
    px.supersampled = true;
    Count(kSupersampled);
}

bool Renderer::NeedsRefinement(const std::vector<Pixel>& pixels, int x, int y) const {
    const int w = window_.Width();
    const Pixel* five[5] = {&pixels[y * w + x], &pixels[y * w + x - 1], &pixels[y * w + x + 1],
                            &pixels[(y - 1) * w + x], &pixels[(y + 1) * w + x]};
    Color lo = Value(*five[0]), hi = lo;
    for (const Pixel* p : five) {
        const Color& c = Value(*p);
        lo = {std::min(lo.r, c.r), std::min(lo.g, c.g), std::min(lo.b, c.b)};
        hi = {std::max(hi.r, c.r), std::max(hi.g, c.g), std::max(hi.b, c.b)};
    }
    auto exceeds = [](double mn, double mx, double threshold) {
        double sum = mx + mn;
        return sum > kEpsilon && (mx - mn) / sum > threshold;
    };
    return exceeds(lo.r, hi.r, options_.contrast.r) || exceeds(lo.g, hi.g, options_.contrast.g) ||
           exceeds(lo.b, hi.b, options_.contrast.b);
}

Image Renderer::RenderFrame(int frame, double frameTime, bool withAlpha) {
    frame_ = frame;
    frameTime_ = frameTime;
    const int w = window_.Width(), h = window_.Height();
    // One extra row below the window is sampled for the contrast test of the last row
    // (spec §3.3) but never written.
    const int rows = h + 1;
    std::vector<Pixel> pixels(static_cast<size_t>(w) * rows);
    const long totalWork = static_cast<long>(w) * rows * 2;
    std::atomic<long> work{0};
    auto report = [&](long units) {
        long now = work.fetch_add(units) + units;
        if (progress_) progress_(std::min(now, totalWork), totalWork);
    };

    // 1. One sample per pixel.
    ParallelFor(rows, [&](long y) {
        for (int x = 0; x < w; ++x) TakeSingleSample(x, static_cast<int>(y), pixels[y * w + x]);
        report(w);
    });

    // 2. Full sampling of the first and last rows and of both end columns.
    if (pattern_.Cells() > 1) {
        std::vector<long> border;
        for (int y = 0; y < rows; ++y) {
            bool wholeRow = y == 0 || y == h - 1;
            for (int x = 0; x < w; ++x)
                if (wholeRow || x == 0 || x == w - 1) border.push_back(static_cast<long>(y) * w + x);
        }
        ParallelFor(static_cast<long>(border.size()), [&](long i) {
            long idx = border[i];
            Supersample(static_cast<int>(idx % w), static_cast<int>(idx / w), pixels[idx]);
        });

        // 3. Contrast refinement until a pass changes nothing.
        for (;;) {
            std::vector<char> mark(pixels.size(), 0);
            for (int y = 1; y < h; ++y)
                for (int x = 1; x < w - 1; ++x)
                    if (NeedsRefinement(pixels, x, y)) {
                        mark[y * w + x] = mark[y * w + x - 1] = mark[y * w + x + 1] = 1;
                        mark[(y - 1) * w + x] = mark[(y + 1) * w + x] = 1;
                    }
            std::vector<long> todo;
            for (size_t i = 0; i < pixels.size(); ++i)
                if (mark[i] && !pixels[i].supersampled) todo.push_back(static_cast<long>(i));
            if (todo.empty()) break;
            ParallelFor(static_cast<long>(todo.size()), [&](long i) {
                long idx = todo[i];
                Supersample(static_cast<int>(idx % w), static_cast<int>(idx / w), pixels[idx]);
            });
            report(static_cast<long>(todo.size()) / 4);
        }
    }
    if (progress_) progress_(totalWork, totalWork);

    // 4. Encode: byte = ⌊255·clamp(c^(1/gamma))⌋; alpha is not gamma-corrected.
    double exponent = std::fabs(options_.gamma) > kEpsilon ? 1 / options_.gamma : 1e14;
    Image image;
    image.width = w;
    image.height = h;
    image.channels = withAlpha ? 4 : 3;
    image.pixels.resize(static_cast<size_t>(w) * h * image.channels);
    for (int y = 0; y < h; ++y) {
        uint8_t* out = image.Row(y);
        for (int x = 0; x < w; ++x) {
            const Pixel& px = pixels[y * w + x];
            const Color& c = Value(px);
            *out++ = EncodeChannel(c.r, exponent);
            *out++ = EncodeChannel(c.g, exponent);
            *out++ = EncodeChannel(c.b, exponent);
            if (withAlpha) *out++ = EncodeChannel(px.supersampled ? px.fullAlpha : px.singleAlpha, 1);
        }
    }
    return image;
}

}  // namespace rs
