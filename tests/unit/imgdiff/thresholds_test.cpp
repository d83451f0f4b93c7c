#include "thresholds.h"

#include <gtest/gtest.h>

namespace rs {
namespace {

void ExpectThresholds(const std::optional<Thresholds>& t, double mean, double max, double frac,
                      double bright) {
    ASSERT_TRUE(t);
    EXPECT_EQ(t->mean, mean);
    EXPECT_EQ(t->max, max);
    EXPECT_EQ(t->frac, frac);
    EXPECT_EQ(t->bright, bright);
}

TEST(ThresholdTable, SharedReferenceTableRows) {
    const std::string path = std::string(RAYSHADE_REFERENCE_DIR) + "/thresholds.tsv";
    std::string error;
    ExpectThresholds(LoadThresholds(path, "mtv", "256", error), 0.012, 0.25, 0.13, 0.01);
    ExpectThresholds(LoadThresholds(path, "mtv", "default", error), 0.017, 0.26, 0.21, 0.01);
    ExpectThresholds(LoadThresholds(path, "boxball", "256", error), 0.0075, 0.28, 0.09, 0.01);
    // No row of its own: the "default any" row.
    ExpectThresholds(LoadThresholds(path, "balls", "256", error), 0.005, 0.15, 0.05, 0.01);
    ExpectThresholds(LoadThresholds(path, "mtv", "512", error), 0.005, 0.15, 0.05, 0.01);
}

TEST(ThresholdTable, LookupOrderIsExactThenSceneAnyThenDefault) {
    const std::string text =
        "# comment\n"
        "\n"
        "default any 1 1 1 1\n"
        "default 128 2 2 2 2\n"
        "glass any 3 3 3 3\n"
        "glass\t256\t4\t4\t4\t4\n";
    std::string error;
    const auto rows = ParseThresholdTable(text, "t.tsv", error);
    ASSERT_TRUE(rows) << error;
    ASSERT_EQ(rows->size(), 4u);
    EXPECT_EQ(LookupThresholds(*rows, "glass", "256", error)->mean, 4);
    EXPECT_EQ(LookupThresholds(*rows, "glass", "128", error)->mean, 3);
    EXPECT_EQ(LookupThresholds(*rows, "planet", "128", error)->mean, 2);
    EXPECT_EQ(LookupThresholds(*rows, "planet", "default", error)->mean, 1);
}

TEST(ThresholdTable, ErrorsNameTheFileAndLine) {
    std::string error;
    EXPECT_FALSE(ParseThresholdTable("# x\ndefault any 1 2 3\n", "t.tsv", error));
    EXPECT_NE(error.find("t.tsv:2:"), std::string::npos) << error;
    EXPECT_FALSE(ParseThresholdTable("default any 1 2 x 4\n", "t.tsv", error));
    EXPECT_NE(error.find("t.tsv:1:"), std::string::npos) << error;
    EXPECT_FALSE(ParseThresholdTable("default any 1 2 -3 4\n", "t.tsv", error));

    const auto rows = ParseThresholdTable("mtv 256 1 1 1 1\n", "t.tsv", error);
    ASSERT_TRUE(rows);
    EXPECT_FALSE(LookupThresholds(*rows, "balls", "256", error));
    EXPECT_NE(error.find("default any"), std::string::npos) << error;

    EXPECT_FALSE(LoadThresholds("/nonexistent/t.tsv", "mtv", "256", error));
    EXPECT_NE(error.find("/nonexistent/t.tsv"), std::string::npos) << error;
}

TEST(ParseNonNegative, AcceptsWholeFiniteNonNegativeNumbersOnly) {
    EXPECT_EQ(ParseNonNegative("0.25"), 0.25);
    EXPECT_EQ(ParseNonNegative("1e-3"), 0.001);
    EXPECT_FALSE(ParseNonNegative(""));
    EXPECT_FALSE(ParseNonNegative("0.1x"));
    EXPECT_FALSE(ParseNonNegative("-1"));
    EXPECT_FALSE(ParseNonNegative("inf"));
    EXPECT_FALSE(ParseNonNegative("nan"));
}

}  // namespace
}  // namespace rs
