#include "libtext/colormap.h"

#include <gtest/gtest.h>

#include <sstream>

namespace rs {
namespace {

std::optional<ColorMap> Parse(const std::string& text, std::string& error) {
    std::istringstream in(text);
    return ParseColorMap(in, "maps/test.map", error);
}

TEST(ColorMap, ScalesEntriesAndLeavesMissingOnesBlack) {
    std::string error;
    std::optional<ColorMap> map = Parse("255 0 51\n  0 255 102 \r\n", error);
    ASSERT_TRUE(map) << error;
    EXPECT_EQ((*map)[0], Color(1, 0, 0.2));
    EXPECT_EQ((*map)[1], Color(0, 1, 0.4));
    EXPECT_EQ((*map)[2], Color(0, 0, 0));
    EXPECT_EQ((*map)[255], Color(0, 0, 0));
}

TEST(ColorMap, IgnoresLinesAfterThe256th) {
    std::string text;
    for (int i = 0; i < 256; ++i) text += std::to_string(i) + " 0 0\n";
    text += "this line is never read\n";
    std::string error;
    std::optional<ColorMap> map = Parse(text, error);
    ASSERT_TRUE(map) << error;
    EXPECT_DOUBLE_EQ((*map)[255].r, 1.0);
    EXPECT_DOUBLE_EQ((*map)[51].r, 0.2);
}

TEST(ColorMap, MalformedLinesNameFileAndLine) {
    const char* bad[] = {"1 2\n", "1 2 3 4\n", "1 2 x\n", "256 0 0\n", "-1 0 0\n", "\n",
                         "1.5 2 3\n"};
    for (const char* line : bad) {
        std::string error;
        EXPECT_FALSE(Parse(std::string("0 0 0\n10 10 10\n") + line, error)) << line;
        EXPECT_NE(error.find("maps/test.map: line 3:"), std::string::npos) << error;
    }
}

TEST(ColorMap, MissingFileIsAnError) {
    std::string error;
    EXPECT_FALSE(ReadColorMap("/nonexistent/dir/x.map", error));
    EXPECT_NE(error.find("/nonexistent/dir/x.map"), std::string::npos) << error;
}

TEST(ColorMap, LookupClampsToTheTable) {
    ColorMap map{};
    map[0] = Color(1, 0, 0);
    map[7] = Color(0, 1, 0);
    map[255] = Color(0, 0, 1);
    EXPECT_EQ(ColorMapLookup(map, -3), map[0]);
    EXPECT_EQ(ColorMapLookup(map, 7.99), map[7]);
    EXPECT_EQ(ColorMapLookup(map, 255.5), map[255]);
    EXPECT_EQ(ColorMapLookup(map, 1e9), map[255]);
}

}  // namespace
}  // namespace rs
