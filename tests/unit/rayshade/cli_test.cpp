#include "rayshade/cli.h"

#include "libcommon/limits.h"

#include <gtest/gtest.h>

namespace rs {
namespace {

bool Parse(std::vector<std::string> args, CommandLine& cl, std::string& error) {
    return ParseCommandLine(args, cl, error);
}

TEST(CommandLine, ResolutionAndOutputSetTheirFlags) {
    CommandLine cl;
    std::string error;
    ASSERT_TRUE(Parse({"-R", "256", "128", "scene.ray", "-O", "out.png"}, cl, error)) << error;
    EXPECT_EQ(cl.options.xres, 256);
    EXPECT_EQ(cl.options.yres, 128);
    EXPECT_TRUE(cl.options.resolutionSet);
    EXPECT_EQ(cl.options.outFile, "out.png");
    EXPECT_TRUE(cl.options.outFileSet);
    EXPECT_EQ(cl.inputFile, "scene.ray");
}

TEST(CommandLine, PreviewForcesOneSampleNoShadowsDepthZero) {
    CommandLine cl;
    std::string error;
    ASSERT_TRUE(Parse({"-p"}, cl, error));
    EXPECT_EQ(cl.options.samples, 1);
    EXPECT_EQ(cl.options.maxDepth, 0);
    EXPECT_TRUE(cl.options.noShadows);
    EXPECT_TRUE(cl.options.jitter);
}

TEST(CommandLine, TogglesFlipTwice) {
    CommandLine cl;
    std::string error;
    ASSERT_TRUE(Parse({"-o", "-o", "-n"}, cl, error));
    EXPECT_TRUE(cl.options.shadowTransparency);
    EXPECT_TRUE(cl.options.noShadows);
}

TEST(CommandLine, SamplesClampToOne) {
    CommandLine cl;
    std::string error;
    ASSERT_TRUE(Parse({"-S", "0"}, cl, error));
    EXPECT_EQ(cl.options.samples, 1);
}

TEST(CommandLine, ErrorsAreReportedNotCrashed) {
    CommandLine cl;
    std::string error;
    EXPECT_FALSE(Parse({"-R", "12"}, cl, error));
    EXPECT_NE(error.find("-R"), std::string::npos);
    cl = CommandLine{};
    EXPECT_FALSE(Parse({"-R", "12", "x"}, cl, error));
    EXPECT_FALSE(Parse({"-Z"}, cl, error));
    EXPECT_FALSE(Parse({"a.ray", "b.ray"}, cl, error));
    EXPECT_FALSE(Parse({"-V", "-v"}, cl, error));
    EXPECT_FALSE(Parse({"-t", "0"}, cl, error));
}

}  // namespace
}  // namespace rs

namespace rs {
namespace {

TEST(CommandLine, LimitOptionRaisesALimitAndRejectsNonsense) {
    const long before = Limits().samplesPerSide;
    CommandLine cl;
    std::string error;
    ASSERT_TRUE(ParseCommandLine({"-L", "samplesPerSide=32"}, cl, error)) << error;
    EXPECT_EQ(Limits().samplesPerSide, 32);
    ASSERT_TRUE(ParseCommandLine({"-L", "samplesPerSide=" + std::to_string(before)}, cl, error));
    EXPECT_EQ(Limits().samplesPerSide, before);

    EXPECT_FALSE(ParseCommandLine({"-L", "nosuch=3"}, cl, error));
    EXPECT_NE(error.find("unknown limit 'nosuch'"), std::string::npos) << error;
    EXPECT_FALSE(ParseCommandLine({"-L", "rayDepth=-4"}, cl, error));
    EXPECT_NE(error.find("not a positive integer"), std::string::npos) << error;
    EXPECT_FALSE(ParseCommandLine({"-L", "rayDepth"}, cl, error));
    EXPECT_FALSE(ParseCommandLine({"-L"}, cl, error));
    EXPECT_EQ(Limits().rayDepth, 64);
}

TEST(CommandLine, ImplicitOverrides) {
    CommandLine cl;
    std::string error;
    EXPECT_TRUE(cl.implicit.Empty());
    ASSERT_TRUE(Parse({"-M", "segment", "-I", "1e-4", "-K", "7", "-J", "-1", "-B", "0.02", "-H",
                       "1bis=off", "-H", "t3=on", "scene.ray"},
                      cl, error))
        << error;
    ASSERT_TRUE(cl.implicit.method);
    EXPECT_EQ(*cl.implicit.method, ImplicitMethod::Segment);
    EXPECT_EQ(*cl.implicit.tolerance, 1e-4);
    EXPECT_EQ(*cl.implicit.maxDepth, 7);
    EXPECT_EQ(*cl.implicit.dRatio, -1);
    EXPECT_EQ(*cl.implicit.step, 0.02);
    ASSERT_EQ(cl.implicit.switches.size(), 2u);
    EXPECT_EQ(cl.implicit.switches[0], std::make_pair(std::string("1bis"), false));
    EXPECT_EQ(cl.implicit.switches[1], std::make_pair(std::string("t3"), true));
    const std::vector<std::vector<std::string>> bad = {
        {"-M", "bisection"}, {"-I", "0"}, {"-K", "17"}, {"-B", "-1"}, {"-H", "zz=on"},
        {"-H", "1bis=maybe"}, {"-M"}};
    for (const auto& args : bad) {
        CommandLine c;
        EXPECT_FALSE(Parse(args, c, error)) << args[0];
        EXPECT_FALSE(error.empty());
    }
}

}  // namespace
}  // namespace rs
