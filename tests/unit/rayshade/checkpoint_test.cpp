#include "rayshade/checkpoint.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <string>
#include <vector>

namespace rs {
namespace {

// No scene file to read: its hash is FNV-1a's offset basis.
constexpr const char* kNoScene = "scene 1469598103934665603";

std::string Fingerprint(const std::vector<std::string>& args) { return RenderFingerprint(args, ""); }

TEST(Fingerprint, OneLinePerOptionWithItsArguments) {
    EXPECT_EQ(Fingerprint({"-R", "256", "128", "-n", "in.ray", "-O", "out.png"}),
              std::string("-R 256 128\n-n\nfile in.ray\n-O out.png\n") + kNoScene);
}

TEST(Fingerprint, LeavesOutWhatCannotChangeTheImage) {
    EXPECT_EQ(Fingerprint({"-c", "-q", "-v", "-t", "3", "-V", "log", "-F", "8", "-O", "o.png"}),
              Fingerprint({"-O", "o.png"}));
}

TEST(Fingerprint, TheDifferenceNamesTheOption) {
    const std::string saved = Fingerprint({"-R", "320", "240", "-g", "-O", "o.png"});
    EXPECT_EQ(DescribeFingerprintDifference(saved, saved), "");
    EXPECT_EQ(DescribeFingerprintDifference(saved, Fingerprint({"-R", "256", "256", "-g", "-O", "o.png"})),
              "it was saved with -R 320 240, not -R 256 256");
    EXPECT_EQ(DescribeFingerprintDifference(saved, Fingerprint({"-R", "320", "240", "-O", "o.png"})),
              "it was saved with -g, which this command lacks");
    EXPECT_EQ(DescribeFingerprintDifference(saved, Fingerprint({"-R", "320", "240", "-g", "-n", "-O", "o.png"})),
              "it was saved without -n, which this command gives");
    std::string edited = saved;
    edited.replace(edited.rfind(' ') + 1, std::string::npos, "42");
    EXPECT_EQ(DescribeFingerprintDifference(saved, edited), "the scene file has changed since");
}

void WriteText(const std::string& path, const char* text) {
    std::FILE* f = std::fopen(path.c_str(), "w");
    ASSERT_NE(f, nullptr);
    std::fputs(text, f);
    std::fclose(f);
}

TEST(Fingerprint, TheLazyOneHashesTheFileAsRead) {
    const std::string scene = ::testing::TempDir() + "rs_lazy_" + std::to_string(getpid()) + ".ray";
    WriteText(scene, "sphere 1 0 0 0\n");
    const std::vector<std::string> args{scene, "-O", "o.png"};
    LazyRenderFingerprint unchanged(args, scene);
    EXPECT_EQ(unchanged.Get(), RenderFingerprint(args, scene));

    // Rewritten between the stamp (construction, before the scene is read) and the hash:
    // the hash describes the new bytes, so the fingerprint must match no run's.
    LazyRenderFingerprint stale(args, scene);
    WriteText(scene, "sphere 2.5 0 0 0\n");  // (another size: timestamps are coarse)
    const std::string staleFingerprint = stale.Get();
    EXPECT_EQ(staleFingerprint, RenderFingerprint(args, scene) + "\nscene changed while rendering");
    EXPECT_EQ(DescribeFingerprintDifference(staleFingerprint, RenderFingerprint(args, scene)),
              "the scene file has changed since");
    EXPECT_EQ(stale.Get(), staleFingerprint);  // computed once
    EXPECT_EQ(DescribeFingerprintDifference(RenderFingerprint(args, scene), staleFingerprint),
              "the scene file has changed since");  // this run's scene changed
    std::remove(scene.c_str());
}

TEST(Fingerprint, LoadingAnotherRendersStateSaysWhatDiffers) {
    const std::string path = ::testing::TempDir() + "rs_fingerprint_" + std::to_string(getpid()) + ".partial";
    FrameState state;
    state.width = 1;
    state.rows = 2;
    state.pixels.assign(2, PixelState{});
    std::string error;
    ASSERT_TRUE(SaveFrameState(path, Fingerprint({"-S", "4", "-O", "o.png"}), state, error)) << error;
    FrameState loaded;
    EXPECT_FALSE(LoadFrameState(path, Fingerprint({"-S", "2", "-O", "o.png"}), loaded, error));
    EXPECT_EQ(error, "partial state '" + path + "' belongs to another render: it was saved with -S 4, "
                     "not -S 2 (-c needs the same command and scene file)");
    std::remove(path.c_str());
}

}  // namespace
}  // namespace rs
