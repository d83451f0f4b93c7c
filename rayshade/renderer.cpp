#include "rayshade/renderer.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <span>
#include <thread>
#include <utility>

#include "libcommon/constants.h"
#include "libcommon/error.h"
#include "libcommon/stats.h"
#include "rayshade/progress_estimate.h"

namespace rs {

namespace {

const CounterId kSupersampled = RegisterCounter("supersampled pixels");
// Pixel channels that were NaN or infinite when encoded (written as 0 or 255); printed by -v
// when non-zero. The numerics tests require it to stay zero.
const CounterId kNonFinitePixels = RegisterCounter("Non-finite pixel values");

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
        Report(Severity::Abort, {},
               "Invalid window specification: columns %d..%d, rows %d..%d of a %dx%d image "
               "(need 0 <= min <= max < size)",
               w.minX, w.maxX, w.minY, w.maxY, o.xres, o.yres);
    return w;
}

Renderer::Renderer(const Scene& scene, ProgressFn progress)
    : Renderer(scene, std::move(progress), std::make_unique<WorkerPool>(ThreadCount(scene.options)),
               nullptr) {}

Renderer::Renderer(const Scene& scene, ProgressFn progress, WorkerPool& workers)
    : Renderer(scene, std::move(progress), nullptr, &workers) {}

Renderer::Renderer(const Scene& scene, ProgressFn progress, std::unique_ptr<WorkerPool> own,
                   WorkerPool* shared)
    : scene_(scene),
      options_(scene.options),
      window_(ComputeWindow(scene.options)),
      camera_(scene.camera, scene.options),
      pattern_(scene.options.samples, scene.options.filter,
               scene.options.filterWidth > 0
                   ? scene.options.filterWidth
                   : (scene.options.filter == FilterKind::Gauss ? 1.8 : 1.0)),
      tracer_(scene),
      progress_(std::move(progress)),
      ownWorkers_(std::move(own)),
      workers_(shared != nullptr ? *shared : *ownWorkers_) {}

int Renderer::ThreadCount(const RenderOptions& options) {
    unsigned hw = std::thread::hardware_concurrency();
    return options.threads > 0 ? options.threads : static_cast<int>(hw ? hw : 1);
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
    const double xi = options_.shutter > 0 && options_.jitter ? rng.Uniform() : 0;
    const double time = ShutterTime(frameTime_, options_.shutter, n, sampleNumber, xi);
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
    px.singleCell = static_cast<int16_t>(std::min(cells - 1, static_cast<int>(rng.Uniform() * cells)));
    double alpha = 0;
    px.SetValue(SampleCell(absX, absY, px.singleCell, rng, alpha));
    px.alpha = static_cast<float>(alpha);
    px.sampled = true;
}

void Renderer::Supersample(int x, int y, Pixel& px) const {
    int absX = window_.minX + x, absY = window_.minY + y;
    Color sum;
    double alpha = 0;
    for (int cell = 0; cell < pattern_.Cells(); ++cell) {
        double w = pattern_.Weight(cell);
        if (cell == px.singleCell) {
            sum += px.Value() * w;
            alpha += px.alpha * w;
            continue;
        }
        Rng rng = Rng::ForKey(absX, absY, frame_, kCellStreamBase + cell);
        double a = 0;
        sum += SampleCell(absX, absY, cell, rng, a) * w;
        alpha += a * w;
    }
    px.SetValue(sum);
    px.alpha = static_cast<float>(alpha);
    px.supersampled = true;
    Count(kSupersampled);
}

bool Renderer::NeedsRefinement(const Pixel* pixels, int x, int y) const {
    const int w = window_.Width();
    const Color five[5] = {pixels[y * w + x].Value(), pixels[y * w + x - 1].Value(),
                           pixels[y * w + x + 1].Value(), pixels[(y - 1) * w + x].Value(),
                           pixels[(y + 1) * w + x].Value()};
    return ContrastExceeds(five, options_.contrast);
}

namespace {
std::atomic<bool> gStopRequested{false};
}  // namespace

void RequestStop() { gStopRequested.store(true, std::memory_order_relaxed); }
bool StopRequested() { return gStopRequested.load(std::memory_order_relaxed); }

Image Renderer::RenderFrame(int frame, double frameTime, bool withAlpha, FrameState* resumeFrom,
                            CheckpointFn checkpoint, double checkpointSeconds) {
    frame_ = frame;
    frameTime_ = frameTime;
    if (!WindowIsScreen()) return RenderSubWindow(withAlpha, resumeFrom, checkpoint, checkpointSeconds);
    const int w = window_.Width(), h = window_.Height();
    // One extra row below the window is sampled for the contrast test of the last row
    // (spec §3.3) but never written.
    const int rows = h + 1;
    FrameState fresh;
    FrameState& state = resumeFrom ? *resumeFrom : fresh;
    if (!resumeFrom) {
        state.frame = frame;
        state.width = w;
        state.rows = rows;
        state.pixels.resize(static_cast<size_t>(w) * rows);  // uninitialised (PixelState)
        ParallelForAll(rows, [&](long y) {
            std::fill_n(state.pixels.begin() + y * w, w, Pixel{});
        });
    }
    auto& pixels = state.pixels;
    using Phase = FrameState::Phase;

    // Progress in samples (progress_estimate.h); a continued frame starts with its work.
    const long extraSamples = pattern_.Cells() - 1;
    FrameProgress progress(w, h, pattern_.Cells(), progress_);
    if (resumeFrom) {
        long taken = 0;
        for (const Pixel& px : pixels) taken += (px.sampled ? 1 : 0) + (px.supersampled ? extraSamples : 0);
        progress.Add(taken);
    }
    auto lastCheckpoint = std::chrono::steady_clock::now();
    // After each piece of work: save the state when asked to stop (then stop) or when the
    // checkpoint interval has passed.
    auto safePoint = [&] {
        if (StopRequested()) {
            if (checkpoint) checkpoint(state, true);
            throw RenderStopped{};
        }
        auto now = std::chrono::steady_clock::now();
        if (checkpoint && std::chrono::duration<double>(now - lastCheckpoint).count() >= checkpointSeconds) {
            checkpoint(state, false);
            lastCheckpoint = now;
        }
    };

    // Supersamples the listed pixels that are not yet, kRun list entries per work item: with
    // one pixel (a few microseconds) per item, the threads contended for the shared index
    // and for the cache lines of neighbouring pixels, which the lists keep together. A stop
    // request waits for the items in progress only.
    auto supersampleAll = [&](std::span<const long> list) {
        constexpr long kRun = 32;
        const long count = static_cast<long>(list.size());
        ParallelFor((count + kRun - 1) / kRun, [&](long k) {
            long taken = 0;
            for (long i = k * kRun; i < std::min(count, (k + 1) * kRun); ++i) {
                const long idx = list[i];
                if (!pixels[idx].supersampled) {
                    Supersample(static_cast<int>(idx % w), static_cast<int>(idx / w), pixels[idx]);
                    ++taken;
                }
            }
            progress.Add(taken * extraSamples);
        });
    };

    // For the progress estimate while single samples are taken: the contrast test of the
    // interior rows whose neighbours are all sampled once rows [y0, y1) are (the rows not
    // tested after earlier blocks), on the single samples. Reads pixels only.
    std::atomic<long> flaggedSoFar{0}, testedSoFar{0};
    auto estimateRefinement = [&](int y0, int y1) {
        const int first = std::max(1, y0 - 1), last = std::min(h - 1, y1 - 2);
        if (last < first || w < 3) return;
        ParallelForAll(last - first + 1, [&](long i) {
            long count = 0;
            for (int x = 1; x < w - 1; ++x) count += NeedsRefinement(pixels.data(), x, first + static_cast<int>(i));
            flaggedSoFar += count;
            testedSoFar += w - 2;
        });
        progress.FlaggedSoFar(flaggedSoFar, testedSoFar);
    };

    // 1. One sample per pixel, in blocks of rows so the state can be saved between them:
    // sixteen blocks (of at least 16 rows). Each block ends with threads idle while the
    // last work items finish, so fewer, larger blocks scale better, and the items are
    // quarter rows (of at least 64 pixels): with whole rows, a 512-pixel frame's blocks of
    // 32 rows left up to a sixteenth of each block to one thread. A stop request does not
    // wait for the block (the workers stop taking items).
    if (state.phase == Phase::SingleSamples) {
        const int blockRows = std::max(16, (rows + 15) / 16);
        const int rowPieces = std::clamp(w / 64, 1, 4);
        for (int y0 = 0; y0 < rows; y0 += blockRows) {
            int y1 = std::min(rows, y0 + blockRows);
            ParallelFor(static_cast<long>(y1 - y0) * rowPieces, [&](long i) {
                const long y = y0 + i / rowPieces;
                const int piece = static_cast<int>(i % rowPieces);
                long taken = 0;
                for (int x = piece * w / rowPieces; x < (piece + 1) * w / rowPieces; ++x) {
                    Pixel& px = pixels[y * w + x];
                    if (!px.sampled) {
                        TakeSingleSample(x, static_cast<int>(y), px);
                        ++taken;
                    }
                }
                progress.Add(taken);
            });
            safePoint();
            if (extraSamples > 0) estimateRefinement(y0, y1);
        }
        state.phase = pattern_.Cells() > 1 ? Phase::Border : Phase::Done;
    }

    // 2. Full sampling of the first and last rows and of both end columns.
    if (state.phase == Phase::Border) {
        std::vector<long> border;
        for (int y = 0; y < rows; ++y) {
            const long row = static_cast<long>(y) * w;
            if (y == 0 || y == h - 1) {
                for (int x = 0; x < w; ++x) border.push_back(row + x);
            } else {
                border.push_back(row);
                if (w > 1) border.push_back(row + w - 1);
            }
        }
        supersampleAll(border);
        safePoint();
        state.phase = Phase::Refinement;
        state.pass = 0;
        state.todo.clear();
    }

    // 3. Contrast refinement until a pass changes nothing. The first pass tests every
    // interior pixel; later passes only the pixels whose five-pixel neighbourhood contains
    // one that the previous pass supersampled (no other test result can change). The order
    // of work does not matter: each pixel's samples depend on the pixel alone. Between
    // passes, each row finds its pixels to test, then its pixels to queue, from its own and
    // its two neighbouring rows: all rows in parallel, with no serial step over the lists.
    while (state.phase == Phase::Refinement) {
        supersampleAll(state.todo);
        safePoint();

        // Row y's entries of the list just supersampled (it is in increasing order).
        auto doneInRow = [&](int y) {
            auto first = std::lower_bound(state.todo.begin(), state.todo.end(), static_cast<long>(y) * w);
            auto last = std::lower_bound(first, state.todo.end(), static_cast<long>(y + 1) * w);
            return std::pair(first, last);
        };
        // The columns of each interior row whose contrast exceeds the thresholds, in
        // increasing order.
        std::vector<std::vector<int>> flagged(rows);
        ParallelFor(h - 1, [&](long i) {
            const int y = static_cast<int>(i) + 1;
            std::vector<uint8_t> candidate(w, state.pass == 0);
            if (state.pass > 0) {
                bool any = false;
                for (int dy = -1; dy <= 1; ++dy) {
                    auto [first, last] = doneInRow(y + dy);
                    for (auto t = first; t != last; ++t) {
                        const int x = static_cast<int>(*t - static_cast<long>(y + dy) * w);
                        candidate[x] = 1;
                        if (dy == 0) {
                            if (x > 0) candidate[x - 1] = 1;
                            if (x + 1 < w) candidate[x + 1] = 1;
                        }
                        any = true;
                    }
                }
                if (!any) return;
            }
            for (int x = 1; x < w - 1; ++x)
                if (candidate[x] && NeedsRefinement(pixels.data(), x, y)) flagged[y].push_back(x);
        });
        safePoint();  // a stop cuts the tests short: save the state from before them

        // Flagged pixels queue their five-pixel neighbourhoods, but not the pixels already
        // supersampled. markQueued marks row y's by column (false: none); each row's count
        // is found first, then the next list is written in place.
        auto markQueued = [&](int y, std::vector<uint8_t>& queue) {
            const bool above = y > 0 && !flagged[y - 1].empty();
            const bool below = y + 1 < rows && !flagged[y + 1].empty();
            if (flagged[y].empty() && !above && !below) return false;
            queue.assign(w, 0);
            for (int x : flagged[y]) queue[x - 1] = queue[x] = queue[x + 1] = 1;
            if (above)
                for (int x : flagged[y - 1]) queue[x] = 1;
            if (below)
                for (int x : flagged[y + 1]) queue[x] = 1;
            for (int x = 0; x < w; ++x)
                if (queue[x] && pixels[static_cast<long>(y) * w + x].supersampled) queue[x] = 0;
            return true;
        };
        std::vector<long> offset(rows + 1);  // of each row's pixels in the next list
        ParallelForAll(rows, [&](long y) {
            std::vector<uint8_t> queue;
            if (markQueued(static_cast<int>(y), queue))
                offset[y + 1] = static_cast<long>(std::count(queue.begin(), queue.end(), 1));
        });
        for (int y = 0; y < rows; ++y) offset[y + 1] += offset[y];
        // A list of an eighth of a huge page or more (the first pass's of a large frame) gets
        // a whole one (see LargeBufferAllocator): one page fault instead of 64 or more, which
        // took milliseconds on a virtual machine.
        constexpr size_t kHugeList = LargeBufferAllocator<long>::kHugePage / sizeof(long);
        const size_t count = static_cast<size_t>(offset[rows]);
        if (count >= kHugeList / 8) state.todo.reserve(std::max(count, kHugeList));
        state.todo.resize(count);
        ParallelForAll(rows, [&](long y) {
            std::vector<uint8_t> queue;
            if (!markQueued(static_cast<int>(y), queue)) return;
            long* out = state.todo.data() + offset[y];
            for (int x = 0; x < w; ++x)
                if (queue[x]) *out++ = y * w + x;
        });
        ++state.pass;
        progress.NextPass(static_cast<long>(state.todo.size()));
        if (state.todo.empty()) state.phase = Phase::Done;
    }
    progress.Finish();
    return Encode(state, withAlpha);
}

Image Renderer::Encode(const FrameState& state, bool withAlpha) const {
    // Byte = ⌊255·clamp(c^(1/gamma))⌋; alpha is not gamma-corrected.
    const int w = state.width, h = state.rows - 1;
    double exponent = std::fabs(options_.gamma) > kEpsilon ? 1 / options_.gamma : 1e14;
    Image image;
    image.width = w;
    image.height = h;
    image.channels = withAlpha ? 4 : 3;
    image.pixels.resize(static_cast<size_t>(w) * h * image.channels);
    ParallelForAll(h, [&](long y) {
        uint8_t* out = image.Row(static_cast<int>(y));
        for (int x = 0; x < w; ++x) {
            const Pixel& px = state.pixels[static_cast<size_t>(y) * w + x];
            if (!std::isfinite(px.r) || !std::isfinite(px.g) || !std::isfinite(px.b)) [[unlikely]]
                Count(kNonFinitePixels);
            *out++ = EncodeChannel(px.r, exponent);
            *out++ = EncodeChannel(px.g, exponent);
            *out++ = EncodeChannel(px.b, exponent);
            if (withAlpha) *out++ = EncodeChannel(px.alpha, 1);
        }
    });
    return image;
}

}  // namespace rs
