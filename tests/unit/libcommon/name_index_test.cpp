#include "libcommon/name_index.h"

#include <gtest/gtest.h>

#include <string>

namespace rs {
namespace {

// "p<i>", built by appending (gcc 12's -Wrestrict misreads "p" + std::to_string(i)).
std::string PointName(int i) {
    std::string name = "p";
    name += std::to_string(i);
    return name;
}

TEST(NameIndex, EmptyFindsNothing) {
    NameIndex index;
    EXPECT_EQ(index.Size(), 0u);
    EXPECT_EQ(index.Find("a"), -1);
    EXPECT_EQ(index.Find(""), -1);
}

TEST(NameIndex, NamesKeepTheirInsertionIndexAcrossGrowth) {
    NameIndex index;
    constexpr int kCount = 100000;  // many rehashes
    for (int i = 0; i < kCount; ++i) {
        ASSERT_TRUE(index.Insert(PointName(i)));
    }
    ASSERT_EQ(index.Size(), static_cast<size_t>(kCount));
    for (int i = 0; i < kCount; ++i) {
        const std::string name = PointName(i);
        ASSERT_EQ(index.Find(name), i);
        ASSERT_EQ(index.Name(static_cast<size_t>(i)), name);
    }
    EXPECT_EQ(index.Find("p"), -1);
    EXPECT_EQ(index.Find("p100000"), -1);
    EXPECT_EQ(index.Find("q0"), -1);
}

TEST(NameIndex, DuplicateIsRefused) {
    NameIndex index;
    EXPECT_TRUE(index.Insert("arm"));
    EXPECT_TRUE(index.Insert("body"));
    EXPECT_FALSE(index.Insert("arm"));
    EXPECT_EQ(index.Size(), 2u);
    EXPECT_EQ(index.Find("arm"), 0);
    EXPECT_EQ(index.Find("body"), 1);
}

TEST(NameIndex, LongNamesAndPrefixesAreDistinct) {
    NameIndex index;
    const std::string long1(5000, 'x');
    EXPECT_TRUE(index.Insert(long1));
    EXPECT_TRUE(index.Insert(long1 + "y"));
    EXPECT_TRUE(index.Insert(""));
    EXPECT_TRUE(index.Insert("x"));
    EXPECT_EQ(index.Find(long1), 0);
    EXPECT_EQ(index.Find(long1 + "y"), 1);
    EXPECT_EQ(index.Find(""), 2);
    EXPECT_EQ(index.Find("x"), 3);
    EXPECT_EQ(index.Find("xx"), -1);
}

}  // namespace
}  // namespace rs
