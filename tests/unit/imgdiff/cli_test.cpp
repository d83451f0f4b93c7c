#include "cli.h"

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "libimage/image.h"

namespace rs {
namespace {

namespace fs = std::filesystem;

class ImgdiffCli : public ::testing::Test {
  protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir = fs::temp_directory_path() /
              (std::string("imgdiff_test_") + info->name() + "_" + std::to_string(getpid()));
        fs::remove_all(dir);
        fs::create_directories(dir);
    }
    void TearDown() override { fs::remove_all(dir); }

    std::string PathOf(const std::string& name) const { return (dir / name).string(); }

    // An 8×8 grey image at `value`, written as `name`.
    std::string Grey(const std::string& name, uint8_t value, int width = 8) {
        Image image;
        image.width = width;
        image.height = 8;
        image.channels = 1;
        image.pixels.assign(static_cast<size_t>(width) * 8, value);
        std::string error;
        EXPECT_TRUE(WriteImage(PathOf(name), image, error)) << error;
        return PathOf(name);
    }

    int Run(const std::vector<std::string>& args) {
        out.str("");
        err.str("");
        return RunImgdiff(args, out, err);
    }

    fs::path dir;
    std::ostringstream out, err;
};

TEST_F(ImgdiffCli, IdenticalImagesPassWithoutAHeatMap) {
    const std::string a = Grey("a.png", 100), b = Grey("b.png", 100);
    EXPECT_EQ(Run({a, b}), kImgdiffPass) << err.str();
    EXPECT_NE(out.str().find("PASS"), std::string::npos) << out.str();
    const std::string report = out.str();
    EXPECT_EQ(std::count(report.begin(), report.end(), '\n'), 1);
    EXPECT_FALSE(fs::exists(a + ".diff.png"));
}

TEST_F(ImgdiffCli, DifferentImagesFailAndWriteTheHeatMap) {
    // 100 vs 110: every difference is 10/255 = 0.039, failing mean, frac and brightness.
    const std::string a = Grey("a.png", 110), b = Grey("b.png", 100);
    EXPECT_EQ(Run({a, b}), kImgdiffFail) << err.str();
    EXPECT_NE(out.str().find("FAIL"), std::string::npos) << out.str();
    std::string error;
    const auto heat = ReadImage(a + ".diff.png", error);
    ASSERT_TRUE(heat) << error;
    EXPECT_EQ(heat->width, 8);
    EXPECT_EQ(heat->channels, 3);

    EXPECT_EQ(Run({"--diff", PathOf("custom.png"), a, b}), kImgdiffFail);
    EXPECT_TRUE(fs::exists(PathOf("custom.png")));
}

TEST_F(ImgdiffCli, ThresholdOptionsDecide) {
    // Difference 10/255 = 0.0392 everywhere; brightness 10/100 = 0.1.
    const std::string a = Grey("a.png", 110), b = Grey("b.png", 100);
    EXPECT_EQ(Run({"--mean", "0.04", "--max", "0.04", "--frac", "1", "--bright", "0.11", a, b}),
              kImgdiffPass)
        << out.str() << err.str();
    EXPECT_EQ(Run({"--mean", "0.039", "--max", "0.04", "--frac", "1", "--bright", "0.11", a, b}),
              kImgdiffFail);
    EXPECT_EQ(Run({"--mean", "0.04", "--max", "0.04", "--frac", "1", "--bright", "0.09", a, b}),
              kImgdiffFail);
}

TEST_F(ImgdiffCli, ThresholdTableRowWithOptionsOverridingIt) {
    std::ofstream(PathOf("t.tsv")) << "default any 0.005 0.15 0.05 0.01\n"
                                      "wide 8 0.04 0.04 1 0.11\n";
    const std::string a = Grey("a.png", 110), b = Grey("b.png", 100);
    const std::string table = PathOf("t.tsv");
    EXPECT_EQ(Run({"--thresholds", table, "wide", "8", a, b}), kImgdiffPass) << err.str();
    EXPECT_EQ(Run({"--thresholds", table, "wide", "default", a, b}), kImgdiffFail);
    // An explicit option wins over the table, before or after it.
    EXPECT_EQ(Run({"--bright", "0.09", "--thresholds", table, "wide", "8", a, b}), kImgdiffFail);
    EXPECT_EQ(Run({"--thresholds", table, "wide", "default", "--mean", "1", "--max", "1",
                   "--frac", "1", "--bright", "1", a, b}),
              kImgdiffPass);
}

TEST_F(ImgdiffCli, PixelsOptionTestsFullResolutionDifferences) {
    // Difference 10/255 on every pixel: all beyond 9 steps, none beyond 10.
    const std::string a = Grey("a.png", 110), b = Grey("b.png", 100);
    const std::vector<std::string> loose = {"--mean", "1", "--max", "1", "--frac", "1",
                                            "--bright", "1"};
    auto with = [&](std::vector<std::string> extra) {
        std::vector<std::string> args = loose;
        args.insert(args.end(), extra.begin(), extra.end());
        args.push_back(a);
        args.push_back(b);
        return Run(args);
    };
    EXPECT_EQ(with({"--pixels", "10", "0"}), kImgdiffPass) << out.str() << err.str();
    EXPECT_EQ(with({"--pixels", "9", "0.999"}), kImgdiffFail) << out.str();
    EXPECT_NE(out.str().find("pixels>9/255 1.000000"), std::string::npos) << out.str();
    EXPECT_EQ(with({"--pixels", "9", "1"}), kImgdiffPass);
    EXPECT_EQ(with({"--pixels", "1.5", "0"}), kImgdiffError);
    EXPECT_EQ(with({"--pixels", "1"}), kImgdiffError);
}

TEST_F(ImgdiffCli, ErrorsExitWithTwo) {
    const std::string a = Grey("a.png", 100), b = Grey("b.png", 100);
    const std::string narrow = Grey("narrow.png", 100, 7);
    EXPECT_EQ(Run({a, narrow}), kImgdiffError);
    EXPECT_NE(err.str().find("size mismatch"), std::string::npos) << err.str();
    EXPECT_FALSE(fs::exists(a + ".diff.png"));
    EXPECT_EQ(Run({a, PathOf("missing.png")}), kImgdiffError);
    EXPECT_NE(err.str().find("missing.png"), std::string::npos) << err.str();
    EXPECT_EQ(Run({a}), kImgdiffError);
    EXPECT_EQ(Run({a, b, b}), kImgdiffError);
    EXPECT_EQ(Run({"--mean", "x", a, b}), kImgdiffError);
    EXPECT_EQ(Run({"--mean"}), kImgdiffError);
    EXPECT_EQ(Run({"--bogus", a, b}), kImgdiffError);
    EXPECT_EQ(Run({"--thresholds", PathOf("none.tsv"), "s", "256", a, b}), kImgdiffError);
    EXPECT_NE(err.str().find("none.tsv"), std::string::npos) << err.str();
    EXPECT_EQ(Run({"--thresholds", PathOf("none.tsv"), "s"}), kImgdiffError);
}

}  // namespace
}  // namespace rs
