#include "libobj/implicit/patch.h"

#include <gtest/gtest.h>

namespace rs {
namespace {

FieldTerm Point(const std::string& name, Vec3 c, double weight = 1) {
    return {name, PointSkeleton{c}, Kernel::GascuelQuadratic(0.5, 2, 1.5), weight};
}

TEST(Patch, AutomaticNeighboursAreOverlappingSupports) {
    std::vector<FieldTerm> terms{Point("a", {0, 0, 0}), Point("b", {1, 0, 0}),
                                 Point("c", {10, 0, 0})};
    std::vector<Patch> patches = BuildPatches(terms, BlendMode::Automatic);
    ASSERT_EQ(patches.size(), 3u);
    EXPECT_EQ(patches[0].Members(), (std::vector<int>{0, 1}));
    EXPECT_EQ(patches[1].Members(), (std::vector<int>{1, 0}));
    EXPECT_EQ(patches[2].Members(), (std::vector<int>{2}));
    EXPECT_TRUE(patches[2].Box().Contains({11.4, 0, 0}));
    EXPECT_FALSE(patches[2].Box().Contains({11.6, 0, 0}));
}

TEST(Patch, ExplicitModeBlendsDeclaredPairsOnly) {
    std::vector<FieldTerm> terms{Point("a", {0, 0, 0}), Point("b", {1, 0, 0}),
                                 Point("c", {0.5, 0.5, 0})};
    std::vector<Patch> patches = BuildPatches(terms, BlendMode::Explicit, {{0, 2}});
    ASSERT_EQ(patches.size(), 3u);
    EXPECT_EQ(patches[0].Members(), (std::vector<int>{0, 2}));
    EXPECT_EQ(patches[1].Members(), (std::vector<int>{1}));
    EXPECT_EQ(patches[2].Members(), (std::vector<int>{2, 0}));
}

TEST(Patch, NegativeTermsOwnNoPatchButAreNeighbours) {
    std::vector<FieldTerm> terms{Point("a", {0, 0, 0}), Point("hole", {0.3, 0, 0}, -1)};
    std::vector<Patch> patches = BuildPatches(terms, BlendMode::Automatic);
    ASSERT_EQ(patches.size(), 1u);
    EXPECT_EQ(patches[0].Members(), (std::vector<int>{0, 1}));
}

TEST(Patch, PredominanceBreaksTiesByLowestIndex) {
    std::vector<FieldTerm> terms{Point("a", {-1, 0, 0}), Point("b", {1, 0, 0})};
    std::vector<Patch> patches = BuildPatches(terms, BlendMode::Automatic);
    Vec3 mid{0, 0.3, 0};  // equidistant: exact tie
    EXPECT_TRUE(patches[0].Predominates(mid));
    EXPECT_FALSE(patches[1].Predominates(mid));
    EXPECT_TRUE(patches[1].Predominates({0.1, 0.3, 0}));
    EXPECT_FALSE(patches[0].Predominates({0.1, 0.3, 0}));
    // Coincident skeletons: only the first ever predominates.
    std::vector<FieldTerm> same{Point("a", {0, 0, 0}), Point("b", {0, 0, 0})};
    std::vector<Patch> twins = BuildPatches(same, BlendMode::Automatic);
    EXPECT_TRUE(twins[0].Predominates({0.2, 0, 0}));
    EXPECT_FALSE(twins[1].Predominates({0.2, 0, 0}));
}

TEST(Patch, PatchFieldIsOwnPlusNeighbours) {
    std::vector<FieldTerm> terms{Point("a", {0, 0, 0}), Point("b", {1, 0, 0}),
                                 Point("c", {10, 0, 0})};
    std::vector<Patch> patches = BuildPatches(terms, BlendMode::Automatic);
    Vec3 p{0.4, 0.1, 0};
    Field all(terms);
    EXPECT_DOUBLE_EQ(patches[0].GetField().Value(p), all.Value(p));
}

}  // namespace
}  // namespace rs
