// Windows (-W) sample exactly what the full-screen render samples there: tiles rendered as
// windows and pasted together equal the full render bit for bit, with adaptive
// supersampling, jitter, depth of field and motion blur, for any tile layout and thread count.
#include <gtest/gtest.h>

#include <algorithm>
#include <ostream>
#include <string>
#include <vector>

#include "libshade/expression.h"
#include "libshade/parser.h"
#include "rayshade/renderer.h"

namespace rs {
namespace {

// A checker floor and spheres at several depths: edges everywhere, so the contrast test
// refines chains of pixels that cross tile borders.
const std::string kWorld =
    "eyep -7 -6 2.2 lookp 0 0 0.8 up 0 0 1 fov 40\n"
    "background 0.1 0.12 0.2\n"
    "surface floor ambient 0.1 0.1 0.1 diffuse 0.8 0.8 0.75\n"
    "surface dark ambient 0.06 0.06 0.06 diffuse 0.45 0.45 0.5\n"
    "surface chrome ambient 0.02 0.02 0.02 diffuse 0.1 0.1 0.1 specular 0.9 0.9 0.9 specpow 90 reflect 0.7\n"
    "surface orange ambient 0.15 0.06 0.01 diffuse 0.9 0.45 0.1 specular 0.6 0.6 0.6 specpow 50\n"
    "light 0.9 point 3 -8 10\n"
    "light 0.3 directional -1 -0.5 1\n"
    "plane floor 0 0 0  0 0 1 texture checker dark scale 0.7 0.7 1\n"
    "sphere chrome 0.8 -1.5 -3 0.8\n"
    "sphere orange 0.8 0 0 0.8\n"
    "sphere chrome 0.8 1.5 3 0.8\n"
    "sphere orange 0.4 0 0 0 translate (linear(0, -2.6, 1, -1.6)) -1 1.5\n";

struct Window {
    int x0, x1, y0, y1;
};

// Renders frame 0 of `scene` (RGBA), the whole screen or only `window`; continues from
// `resume` when given, and offers `checkpoint` the state at every safe point.
Image Render(const std::string& scene, int threads, const Window* window = nullptr,
             FrameState* resume = nullptr, CheckpointFn checkpoint = {}) {
    RenderOptions options;
    options.threads = threads;
    Scene s = ParseSceneText(scene, "window_test.ray", options);
    if (window) {
        s.options.window[0] = window->x0;
        s.options.window[1] = window->x1;
        s.options.window[2] = window->y0;
        s.options.window[3] = window->y1;
    }
    SetCurrentFrame(0);
    s.world->PrepareFrame(s.options.startTime, s.options.shutter);
    Renderer renderer(s, nullptr);
    return renderer.RenderFrame(0, s.options.startTime, true, resume, std::move(checkpoint), 0);
}

// Renders `scene` as `columns` x `rows` tiles of (nearly) equal size and pastes them.
Image RenderTiled(const std::string& scene, int width, int height, int columns, int rows, int threads) {
    Image out;
    out.width = width;
    out.height = height;
    out.channels = 4;
    out.pixels.assign(static_cast<size_t>(width) * height * 4, 0);
    for (int j = 0; j < rows; ++j) {
        for (int i = 0; i < columns; ++i) {
            const Window w{i * width / columns, (i + 1) * width / columns - 1, j * height / rows,
                           (j + 1) * height / rows - 1};
            Image tile = Render(scene, threads, &w);
            EXPECT_EQ(tile.width, w.x1 - w.x0 + 1);
            EXPECT_EQ(tile.height, w.y1 - w.y0 + 1);
            for (int y = 0; y < tile.height; ++y) {
                std::copy(tile.Row(y), tile.Row(y) + tile.width * 4, out.Row(w.y0 + y) + w.x0 * 4);
            }
        }
    }
    return out;
}

long DifferingPixels(const Image& a, const Image& b) {
    EXPECT_EQ(a.width, b.width);
    EXPECT_EQ(a.height, b.height);
    if (a.pixels.size() != b.pixels.size()) return -1;
    long differing = 0;
    for (size_t k = 0; k < a.pixels.size(); k += 4)
        differing += !std::equal(&a.pixels[k], &a.pixels[k] + 4, &b.pixels[k]);
    return differing;
}

struct Case {
    const char* name;
    std::string options;  // scene keywords before the world
    int columns, rows;
};

void PrintTo(const Case& c, std::ostream* os) { *os << c.name; }

class WindowTiles : public ::testing::TestWithParam<Case> {};

TEST_P(WindowTiles, PastedTilesEqualTheFullRender) {
    const Case& c = GetParam();
    const std::string scene = "screen 48 36\n" + c.options + "\n" + kWorld;
    const Image full = Render(scene, 2);
    EXPECT_EQ(DifferingPixels(RenderTiled(scene, 48, 36, c.columns, c.rows, 2), full), 0);
    // Thread counts change neither.
    EXPECT_EQ(DifferingPixels(RenderTiled(scene, 48, 36, c.columns, c.rows, 1), full), 0);
}

INSTANTIATE_TEST_SUITE_P(
    Scenes, WindowTiles,
    ::testing::Values(Case{"Adaptive3NoJitter", "sample 3 nojitter", 3, 2},
                      Case{"Adaptive4Jitter", "sample 4 jitter", 2, 2},
                      // Low thresholds refine long chains of pixels across the tiles.
                      Case{"LowContrast", "sample 4 jitter contrast 0.03 0.03 0.03", 4, 3},
                      Case{"DepthOfField", "sample 3 aperture 0.15 focaldist 9.33", 3, 1},
                      Case{"MotionBlur", "sample 3 shutter 1", 1, 3},
                      // Tiles one pixel wide: every pixel is at a tile's edge.
                      Case{"ThinColumns", "sample 3 jitter", 48, 1},
                      Case{"OneSample", "sample 1", 3, 3}),
    [](const ::testing::TestParamInfo<Case>& param) { return std::string(param.param.name); });

TEST(WindowRender, EveryWindowIsThatPartOfTheFullRender) {
    // Before windows ran the full render's passes, a window supersampled its own border and
    // differed from the full render along its edges. Windows of 9x7 pixels at many places,
    // most touching no screen edge.
    const std::string scene = "screen 48 36 sample 4 jitter\n" + kWorld;
    const Image full = Render(scene, 2);
    long differing = 0;
    for (int y0 = 0; y0 + 7 <= 36; y0 += 4) {
        for (int x0 = 0; x0 + 9 <= 48; x0 += 6) {
            const Window w{x0, x0 + 8, y0, y0 + 6};
            const Image tile = Render(scene, 2, &w);
            ASSERT_EQ(tile.width, 9);
            ASSERT_EQ(tile.height, 7);
            for (int y = 0; y < tile.height; ++y)
                differing += !std::equal(tile.Row(y), tile.Row(y) + tile.width * 4, full.Row(w.y0 + y) + w.x0 * 4);
        }
    }
    EXPECT_EQ(differing, 0);
}

TEST(WindowRender, ContinuingFromASavedStateGivesTheSameWindow) {
    // A window's state saved at any safe point (here: every one, the checkpoint interval is
    // 0) continues to the image of an uninterrupted render; the states hold the samples
    // taken so far.
    const std::string scene = "screen 48 36 sample 4 jitter\n" + kWorld;
    const Window w{10, 29, 6, 21};
    std::vector<FrameState> saved;
    const Image whole = Render(scene, 2, &w, nullptr, [&](const FrameState& state, bool) { saved.push_back(state); });
    ASSERT_GE(saved.size(), 3u);
    for (size_t i : {size_t{0}, size_t{1}, saved.size() / 2, saved.size() - 1}) {
        FrameState state = saved[i];
        EXPECT_EQ(state.phase, FrameState::Phase::SingleSamples);
        long sampled = 0;
        for (const PixelState& px : state.pixels) sampled += px.sampled;
        EXPECT_GT(sampled, 0) << "state " << i;
        EXPECT_EQ(DifferingPixels(Render(scene, 2, &w, &state), whole), 0) << "state " << i;
    }
}

}  // namespace
}  // namespace rs
