// The implicit octree's memory budget (docs/robustness.md): a tree whose heuristics would
// subdivide far stops at its budget, yet still finds the exact surface.
#include <gtest/gtest.h>

#include <optional>

#include "libobj/implicit/lg_octree.h"

namespace rs {
namespace {

// A lone point skeleton with Gascuel's kernel of thickness e is the sphere of radius e
// (implicit/README.md), so the ray from (0, −5, 0) along +y first meets it at t = 5 − e.
TEST(OctreeBudget, TreeStaysWithinItsBudgetAndStillFindsTheSurface) {
    constexpr double kE = 0.5;
    const Field field({{"p", PointSkeleton{{0, 0, 0}}, Kernel::GascuelQuadratic(kE, 2, 1.2), 1}});
    OctreeSettings s;
    s.maxDepth = 9;
    s.useHeuristic3 = false;     // without 3 and 3bis only depth 2 (maxDepth) stops
    s.useHeuristic3bis = false;  // subdivision along the surface
    const LGOctree unlimited(field, 1.0, field.SupportBounds(), s);

    s.memoryBudget = 16384;
    const LGOctree budgeted(field, 1.0, field.SupportBounds(), s);
    // Contract (lg_octree.h): overshoot of at most 164 bytes per level of the path built.
    const std::size_t bound = s.memoryBudget + 164 * static_cast<std::size_t>(s.maxDepth);
    ASSERT_GT(unlimited.MemoryBytes(), bound);  // the budget does bind here
    EXPECT_LE(budgeted.MemoryBytes(), bound);

    const Ray ray{{0, -5, 0}, {0, 1, 0}, 0};
    for (const LGOctree* tree : {&unlimited, &budgeted}) {
        std::optional<double> t = tree->FirstRoot(ray, 1e-6, 100);
        ASSERT_TRUE(t.has_value());
        EXPECT_NEAR(*t, 5 - kE, 1e-6);
    }
}

}  // namespace
}  // namespace rs
