// Rendering a window smaller than the screen so that it samples exactly what the full-screen
// render samples there (tiles of a render farm paste into the full image bit for bit).
//
// Every pixel's single sample and supersampled value depend on the pixel alone; what the
// window must reproduce is the full render's set S of supersampled pixels. In the full render
// S starts as the screen's border and grows pass by pass: a pixel whose five-pixel
// neighbourhood shows contrast (with the values of the pass) queues that neighbourhood. A
// pixel's decision depends on its neighbours' decisions, so it depends on pixels outside the
// window, in principle arbitrarily far away.
//
// The window therefore runs the same passes on a larger region R (the window and a margin),
// with three states per pixel: not supersampled, supersampled, and "maybe" (the full render
// may or may not have supersampled it at this pass). Pixels whose neighbourhood leaves R have
// unknown decisions; a pixel with maybe-neighbours is decided by testing every combination of
// their two possible values: the decision is certain when all combinations agree. Pass by
// pass, every true state of the full render is one the three-valued state allows (the
// abstraction is sound), so when the passes end and no pixel of the window is "maybe", the
// window's set is exactly the full render's. Otherwise the margin grows and the passes run
// again on the larger region, from the samples already taken; a region that covers the
// screen has no unknown pixels. In smooth parts of the
// picture every combination agrees, so the uncertainty stays within a few pixels of R's edge.
//
// The saved state of a window in progress holds the region's samples taken so far; a window
// continued with -c takes only the missing ones and runs the passes again from them.
#include <algorithm>
#include <chrono>
#include <utility>
#include <vector>

#include "rayshade/renderer.h"

namespace rs {

namespace {

enum class Decision : uint8_t { No = 0, Maybe = 1, Yes = 2 };

// Margin of the first attempt, in pixels, and the factor it grows by. Samples carry over
// to the next attempt, so a small first margin costs little when it is not enough; every
// margin pixel costs its samples (often its full supersampling, as "maybe" pixels are
// supersampled to test both values), so a small margin keeps a tile's extra work low.
constexpr int kFirstMargin = 2;
constexpr int kMarginGrowth = 2;

// A pixel and its four neighbours, as offsets.
constexpr std::pair<int, int> kFive[5] = {{0, 0}, {-1, 0}, {1, 0}, {0, -1}, {0, 1}};

// The region R in absolute screen coordinates; rows run to the screen's extra row below the
// last one (yres), which the full render samples for the last row's contrast test.
struct Region {
    int x0, x1, y0, y1;
    int Width() const { return x1 - x0 + 1; }
    int Height() const { return y1 - y0 + 1; }
    bool Contains(int x, int y) const { return x >= x0 && x <= x1 && y >= y0 && y <= y1; }
};

}  // namespace

bool Renderer::WindowIsScreen() const {
    return window_.minX == 0 && window_.minY == 0 && window_.maxX == options_.xres - 1 &&
           window_.maxY == options_.yres - 1;
}

Image Renderer::RenderSubWindow(bool withAlpha, FrameState* resumeFrom, const CheckpointFn& checkpoint,
                                double checkpointSeconds) {
    const int w = window_.Width(), h = window_.Height();
    const int xres = options_.xres, yres = options_.yres;
    if (resumeFrom && resumeFrom->phase == FrameState::Phase::Done) return Encode(*resumeFrom, withAlpha);
    const long totalWork = static_cast<long>(w) * h * 2;

    // The full render's rules: which pixels start supersampled, which are tested.
    auto onScreenBorder = [&](int x, int y) { return x == 0 || x == xres - 1 || y == 0 || y == yres - 1; };
    auto tested = [&](int x, int y) { return x >= 1 && x <= xres - 2 && y >= 1 && y <= yres - 1; };

    // With one sample per pixel the full render supersamples nothing: the window is its
    // single samples (a margin of zero, no passes).
    const bool adaptive = pattern_.Cells() > 1;
    int margin = adaptive ? kFirstMargin : 0;
    // A saved state of a window in progress: the region's samples (see `region` below),
    // its margin in `pass`. Decisions are not saved; they are found again from the samples
    // without tracing.
    if (resumeFrom && resumeFrom->phase == FrameState::Phase::SingleSamples && resumeFrom->pass > margin)
        margin = resumeFrom->pass;
    // The samples of the previous, smaller attempt (its region's pixels, see `region`).
    FrameState carried;
    Region carriedRegion{0, -1, 0, -1};
    for (;; margin *= kMarginGrowth) {
        const Region r{std::max(0, window_.minX - margin), std::min(xres - 1, window_.maxX + margin),
                       std::max(0, window_.minY - margin), std::min(yres, window_.maxY + 1 + margin)};
        const int rw = r.Width(), rh = r.Height();
        const long n = static_cast<long>(rw) * rh;
        const bool wholeScreen = r.x0 == 0 && r.y0 == 0 && r.x1 == xres - 1 && r.y1 == yres;
        // The region's single samples (pixels [0, n), marked `sampled` once taken) and its
        // supersampled values (pixels [n, 2n), marked `supersampled`): the state a stop or
        // a checkpoint saves.
        FrameState region;
        if (resumeFrom && resumeFrom->phase == FrameState::Phase::SingleSamples && resumeFrom->pass == margin &&
            resumeFrom->width == rw && resumeFrom->rows == 2 * rh) {
            region = std::move(*resumeFrom);
        } else {
            region.frame = frame_;
            region.width = rw;
            region.rows = 2 * rh;
            region.pass = margin;
            region.pixels.assign(static_cast<size_t>(2 * n), Pixel{});
        }
        Pixel* single = region.pixels.data();
        Pixel* super = single + n;
        // Index of absolute (x, y) in the region's arrays.
        auto at = [&](int x, int y) { return static_cast<long>(y - r.y0) * rw + (x - r.x0); };
        if (!carried.pixels.empty()) {
            const long cw = carriedRegion.Width(), cn = cw * carriedRegion.Height();
            for (int y = carriedRegion.y0; y <= carriedRegion.y1; ++y)
                for (int x = carriedRegion.x0; x <= carriedRegion.x1; ++x) {
                    const long c = static_cast<long>(y - carriedRegion.y0) * cw + (x - carriedRegion.x0);
                    single[at(x, y)] = carried.pixels[c];
                    super[at(x, y)] = carried.pixels[cn + c];
                }
            carried.pixels.clear();
        }
        auto lastCheckpoint = std::chrono::steady_clock::now();
        auto safePoint = [&] {
            if (StopRequested()) {
                if (checkpoint) checkpoint(region, true);
                throw RenderStopped{};
            }
            const auto now = std::chrono::steady_clock::now();
            if (checkpoint && std::chrono::duration<double>(now - lastCheckpoint).count() >= checkpointSeconds) {
                checkpoint(region, false);
                lastCheckpoint = now;
            }
        };
        // A pixel of R whose five-pixel neighbourhood leaves R: its own test and its
        // outside neighbours' tests are unknown.
        auto atFakeEdge = [&](int x, int y) {
            return (x == r.x0 && x > 0) || (x == r.x1 && x < xres - 1) || (y == r.y0 && y > 0) ||
                   (y == r.y1 && y < yres);
        };
        std::vector<Decision> decision(n, Decision::No);
        std::vector<uint8_t> changed(n, 1);  // since the last test (all, at first)
        if (adaptive) {
            for (int y = r.y0; y <= r.y1; ++y)
                for (int x = r.x0; x <= r.x1; ++x)
                    decision[at(x, y)] = onScreenBorder(x, y) ? Decision::Yes
                                         : atFakeEdge(x, y)   ? Decision::Maybe
                                                              : Decision::No;
        }

        // Sampling uses coordinates relative to the window, as the full-screen path does.
        ParallelFor(rh, [&](long i) {
            const int y = r.y0 + static_cast<int>(i);
            for (int x = r.x0; x <= r.x1; ++x) {
                const long k = at(x, y);
                if (!single[k].sampled) TakeSingleSample(x - window_.minX, y - window_.minY, single[k]);
            }
        });
        safePoint();
        if (progress_) progress_(totalWork / 2, totalWork);
        auto supersampleDecided = [&] {
            ParallelFor(rh, [&](long i) {
                const int y = r.y0 + static_cast<int>(i);
                for (int x = r.x0; x <= r.x1; ++x) {
                    const long k = at(x, y);
                    if (decision[k] == Decision::No || super[k].supersampled) continue;
                    Pixel px = single[k];
                    Supersample(x - window_.minX, y - window_.minY, px);
                    super[k] = px;
                }
            });
        };
        supersampleDecided();
        safePoint();

        // The three-valued test of pixel (x, y) against the current decisions.
        auto test = [&](int x, int y) {
            if (!tested(x, y)) return Decision::No;
            const int nx[5] = {x, x - 1, x + 1, x, x};
            const int ny[5] = {y, y, y, y - 1, y + 1};
            for (int j = 0; j < 5; ++j)
                if (!r.Contains(nx[j], ny[j])) return Decision::Maybe;
            long index[5];
            int maybeMask = 0;
            for (int j = 0; j < 5; ++j) {
                index[j] = at(nx[j], ny[j]);
                if (decision[index[j]] == Decision::Maybe) maybeMask |= 1 << j;
            }
            bool anyTrue = false, anyFalse = false;
            // Every combination of the maybe-neighbours' values (bit set: supersampled).
            for (int combo = maybeMask;; combo = (combo - 1) & maybeMask) {
                Color five[5];
                for (int j = 0; j < 5; ++j) {
                    const bool isSuper = (maybeMask >> j & 1) ? (combo >> j & 1) : decision[index[j]] == Decision::Yes;
                    five[j] = (isSuper ? super[index[j]] : single[index[j]]).Value();
                }
                (ContrastExceeds(five, options_.contrast) ? anyTrue : anyFalse) = true;
                if (combo == 0 || (anyTrue && anyFalse)) break;
            }
            return anyTrue && anyFalse ? Decision::Maybe : anyTrue ? Decision::Yes : Decision::No;
        };

        // Passes until no decision changes. Only pixels whose neighbourhood changed since
        // their last test are tested again (no other result can change).
        std::vector<Decision> flag(n, Decision::No);
        for (bool any = adaptive; any;) {
            ParallelFor(rh, [&](long i) {
                const int y = r.y0 + static_cast<int>(i);
                for (int x = r.x0; x <= r.x1; ++x) {
                    bool dirty = false;
                    for (auto [dx, dy] : kFive)
                        dirty = dirty || (r.Contains(x + dx, y + dy) && changed[at(x + dx, y + dy)]);
                    if (dirty) flag[at(x, y)] = test(x, y);
                }
            });
            safePoint();
            // A pixel's decision rises to the strongest test result in its neighbourhood;
            // the pass reads the previous decisions, so the new ones go to a second array.
            std::vector<Decision> raised(n);
            std::vector<uint8_t> next(n, 0);
            ParallelForAll(rh, [&](long i) {
                const int y = r.y0 + static_cast<int>(i);
                for (int x = r.x0; x <= r.x1; ++x) {
                    const long k = at(x, y);
                    Decision d = decision[k];
                    for (auto [dx, dy] : kFive)
                        if (r.Contains(x + dx, y + dy)) d = std::max(d, flag[at(x + dx, y + dy)]);
                    raised[k] = d;
                    next[k] = d != decision[k];
                }
            });
            decision.swap(raised);
            any = std::find(next.begin(), next.end(), 1) != next.end();
            changed = std::move(next);
            supersampleDecided();
            safePoint();
        }

        bool certain = true;
        for (int y = window_.minY; y <= window_.maxY && certain; ++y)
            for (int x = window_.minX; x <= window_.maxX; ++x)
                if (decision[at(x, y)] == Decision::Maybe) certain = false;
        if (!certain && !wholeScreen) {
            carried = std::move(region);
            carriedRegion = r;
            continue;
        }
        FrameState done;
        done.frame = frame_;
        done.width = w;
        done.rows = h + 1;
        done.phase = FrameState::Phase::Done;
        done.pixels.assign(static_cast<size_t>(w) * (h + 1), Pixel{});
        for (int y = window_.minY; y <= window_.maxY; ++y)
            for (int x = window_.minX; x <= window_.maxX; ++x) {
                const long k = at(x, y);
                done.pixels[static_cast<size_t>(y - window_.minY) * w + (x - window_.minX)] =
                    decision[k] == Decision::Yes ? super[k] : single[k];
            }
        if (progress_) progress_(totalWork, totalWork);
        return Encode(done, withAlpha);
    }
}

}  // namespace rs
