#include "libtext/texture_registry.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>

#include <unistd.h>

#include "fake_args.h"
#include "libimage/image.h"
#include "libtext/image_texture.h"

namespace rs {
namespace {

class TextureRegistryTest : public ::testing::Test {
  protected:
    void SetUp() override {
        dir_ = std::filesystem::temp_directory_path() /
               ("rs_libtext_" + std::to_string(::getpid()));
        std::filesystem::create_directories(dir_);
        colorMap_ = (dir_ / "grey.map").string();
        std::ofstream(colorMap_) << "0 0 0\n128 128 128\n255 255 255\n";
        Image image;
        image.width = 2;
        image.height = 1;
        image.channels = 1;
        image.pixels = {0, 255};
        grey_ = (dir_ / "grey.png").string();
        std::string error;
        ASSERT_TRUE(WriteImage(grey_, image, error)) << error;
    }
    void TearDown() override { std::filesystem::remove_all(dir_); }

    std::shared_ptr<Texture> Make(const std::string& keyword, std::vector<std::string> tokens) {
        for (const TextureEntry& e : TextureRegistry()) {
            if (keyword != e.keyword) continue;
            testing::FakeArgs args(std::move(tokens));
            args.surfaces["red"] = Surface::Default();
            std::shared_ptr<Texture> t = e.create(args);
            EXPECT_TRUE(args.AtEnd()) << keyword;
            return t;
        }
        ADD_FAILURE() << "no entry " << keyword;
        return nullptr;
    }

    std::filesystem::path dir_;
    std::string colorMap_, grey_;
};

TEST_F(TextureRegistryTest, OneRowPerKeyword) {
    std::set<std::string> keywords;
    for (const TextureEntry& e : TextureRegistry()) {
        EXPECT_TRUE(keywords.insert(e.keyword).second) << e.keyword;
        EXPECT_NE(e.create, nullptr);
        EXPECT_NE(std::string(e.usage).find(e.keyword), std::string::npos);
    }
    std::set<std::string> expected = {"checker", "blotch", "bump",  "marble", "fbm",
                                      "fbmbump", "wood",   "gloss", "cloud",  "sky",
                                      "stripe",  "windy",  "mount", "image",
                                      "patches"};
    EXPECT_EQ(keywords, expected);
}

TEST_F(TextureRegistryTest, EveryFactoryReadsItsArguments) {
    EXPECT_TRUE(Make("checker", {"red"}));
    EXPECT_TRUE(Make("blotch", {"0.3", "red"}));
    EXPECT_TRUE(Make("bump", {"0.5"}));
    EXPECT_TRUE(Make("marble", {}));
    EXPECT_TRUE(Make("marble", {colorMap_}));
    EXPECT_TRUE(Make("fbm", {"0", "1", "0.5", "2", "6", "0.1"}));
    EXPECT_TRUE(Make("fbm", {"0", "1", "0.5", "2", "6", "0.1", colorMap_}));
    EXPECT_TRUE(Make("fbmbump", {"0", "1", "0.5", "2", "6"}));
    EXPECT_TRUE(Make("wood", {}));
    EXPECT_TRUE(Make("gloss", {"0.7"}));
    EXPECT_TRUE(Make("cloud", {"1", "0.5", "2", "6", "0.3", "0.6", "0.5"}));
    EXPECT_TRUE(Make("sky", {"1", "0.5", "2", "6", "0.3", "0.6"}));
    EXPECT_TRUE(Make("stripe", {"red", "0.1", "0.5"}));
    EXPECT_TRUE(Make("stripe", {"red", "0.1", "0.5", "map", "cylindrical"}));
    EXPECT_TRUE(Make("windy", {"1", "1", "1", "1", "4", "2", "0.5", "0"}));
    EXPECT_TRUE(Make("mount", {colorMap_, "0.1", "0.5"}));
    EXPECT_TRUE(Make("image", {grey_}));
    EXPECT_TRUE(Make("image", {grey_, "component", "bump", "range", "2", "-1", "smooth", "tile",
                               "1", "1", "map", "planar", "0", "0", "0", "0", "1", "0", "1",
                               "0", "0"}));
    EXPECT_TRUE(Make("image", {grey_, "textsurf", "red", "map", "uv"}));
    EXPECT_TRUE(Make("patches", {}));
}

TEST_F(TextureRegistryTest, FactoriesStopAtTheNextItem) {
    // Transforms after a texture belong to the parser: optional arguments stop before them.
    for (const char* keyword : {"wood", "marble", "image"}) {
        for (const TextureEntry& e : TextureRegistry()) {
            if (std::string(e.keyword) != keyword) continue;
            std::vector<std::string> tokens = {"translate", "1", "2", "3"};
            if (e.keyword == std::string("image")) tokens.insert(tokens.begin(), grey_);
            testing::FakeArgs args(tokens);
            EXPECT_TRUE(e.create(args)) << keyword;
            EXPECT_TRUE(args.Peek("translate")) << keyword;
        }
    }
}

TEST_F(TextureRegistryTest, BadInputFails) {
    EXPECT_THROW(Make("marble", {"/nonexistent/x.map"}), FatalError);
    EXPECT_THROW(Make("mount", {"/nonexistent/x.map", "1", "1"}), FatalError);
    EXPECT_THROW(Make("image", {"/nonexistent/x.png"}), FatalError);
    EXPECT_THROW(Make("image", {grey_, "component", "colour"}), FatalError);
    EXPECT_THROW(Make("fbm", {"0", "1", "0.5"}), FatalError);
    // A 3-channel image cannot feed a scalar component.
    Image rgb;
    rgb.width = rgb.height = 1;
    rgb.channels = 3;
    rgb.pixels = {1, 2, 3};
    std::string path = (dir_ / "rgb.png").string(), error;
    ASSERT_TRUE(WriteImage(path, rgb, error)) << error;
    EXPECT_THROW(Make("image", {path, "component", "specpow"}), FatalError);
    EXPECT_TRUE(Make("image", {path, "component", "diffuse"}));
}

TEST_F(TextureRegistryTest, ImagesAreLoadedOncePerPath) {
    std::string error;
    auto a = ImageTexture::LoadShared(grey_, error);
    auto b = ImageTexture::LoadShared(grey_, error);
    ASSERT_TRUE(a);
    EXPECT_EQ(a.get(), b.get());
}

}  // namespace
}  // namespace rs
