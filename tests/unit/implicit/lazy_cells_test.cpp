// The per-cell mode of LGOctree (lg_octree.h): cells expanded by the rays that reach them,
// results independent of the order and threads of the rays, and in agreement with the whole
// tree and with analytic answers.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <thread>
#include <vector>

#include "libcommon/error.h"
#include "libobj/implicit/lg_octree.h"
#include "test_util.h"

namespace rs {
namespace {

using testing::RandomPoint;
using testing::RandomUnit;
using testing::Uniform;

// Twelve Gascuel points blending along a random walk (a small fluid), weight 1.
std::vector<FieldTerm> WalkTerms(Rng& rng) {
    std::vector<FieldTerm> terms;
    Vec3 p{0, 0, 0};
    for (int i = 0; i < 12; ++i) {
        terms.push_back({"p", PointSkeleton{p}, Kernel::GascuelLinear(0.45, 2, 1), 1});
        p = p + RandomUnit(rng) * 0.6;
    }
    return terms;
}

// Rays from a sphere around the field towards random points of its box, some with a
// footprint (a pixel's cone, as eye rays under `tolerance auto` carry).
std::vector<Ray> SomeRays(Rng& rng, const Bounds3& box, int count) {
    std::vector<Ray> rays;
    const Vec3 c = box.Center();
    for (int i = 0; i < count; ++i) {
        const Vec3 o = c + RandomUnit(rng) * Uniform(rng, 4, 8);
        const Vec3 target = testing::RandomInBox(rng, box);
        Ray ray{o, Normalize(target - o)};
        if (i % 2) ray.footprintSpread = Uniform(rng, 1e-4, 0.05);
        rays.push_back(ray);
    }
    return rays;
}

OctreeSettings AutoAccuracy() {
    OctreeSettings s;
    s.autoTolerance = true;
    return s;
}

// The same first roots, bit for bit, whatever the order of the rays, the number of threads
// reaching the cells and whether the budget lets cells be kept.
TEST(LazyCells, ResultsDoNotDependOnRayOrderThreadsOrBudget) {
    for (uint64_t seed = 1; seed <= 5; ++seed) {
        Rng rng(seed);
        Field field(WalkTerms(rng));
        const Bounds3 box = field.SupportBounds();
        const std::vector<Ray> rays = SomeRays(rng, box, 400);
        const OctreeSettings s = AutoAccuracy();
        LazyCellStore inOrder(1u << 30), threaded(1u << 30), starved(600);
        const LGOctree a(field, 1.0, box, s, -1, &inOrder);
        const LGOctree b(field, 1.0, box, s, -1, &threaded);
        std::vector<Diagnostic> seen;
        ErrorSink old = SetErrorSink([&seen](const Diagnostic& d) { seen.push_back(d); });
        const LGOctree c(field, 1.0, box, s, -1, &starved);
        std::vector<std::optional<double>> want(rays.size()), got(rays.size()),
            recomputed(rays.size());
        for (size_t i = 0; i < rays.size(); ++i) want[i] = a.FirstRoot(rays[i], 1e-5, 1e9);
        std::vector<std::thread> threads;
        for (size_t k = 0; k < 4; ++k) {
            threads.emplace_back([&, k] {  // each thread backwards over its quarter
                for (size_t i = rays.size(); i-- > 0;) {
                    if (i % 4 == k) got[i] = b.FirstRoot(rays[i], 1e-5, 1e9);
                }
            });
        }
        for (std::thread& t : threads) t.join();
        for (size_t i = rays.size(); i-- > 0;) recomputed[i] = c.FirstRoot(rays[i], 1e-5, 1e9);
        SetErrorSink(old);
        int hits = 0;
        for (size_t i = 0; i < rays.size(); ++i) {
            ASSERT_EQ(want[i], got[i]) << "seed " << seed << " ray " << i;
            ASSERT_EQ(want[i], recomputed[i]) << "seed " << seed << " ray " << i;
            hits += want[i].has_value();
        }
        EXPECT_GT(hits, 50);
        EXPECT_EQ(inOrder.UsedBytes(), threaded.UsedBytes());
        EXPECT_GT(inOrder.UsedBytes(), starved.UsedBytes());
        EXPECT_TRUE(starved.Degraded());
        EXPECT_FALSE(inOrder.Degraded());
        ASSERT_EQ(seen.size(), 1u);  // one warning per store
        EXPECT_EQ(seen[0].severity, Severity::Warn);
    }
}

// Per-cell trees and whole trees find the same hits, within the tolerance; rays with and
// without footprints.
TEST(LazyCells, AgreeWithTheWholeTree) {
    for (uint64_t seed = 11; seed <= 16; ++seed) {
        Rng rng(seed);
        Field field(WalkTerms(rng));
        const Bounds3 box = field.SupportBounds();
        const OctreeSettings s = AutoAccuracy();
        LazyCellStore store(1u << 30);
        const LGOctree lazy(field, 1.0, box, s, -1, &store);
        const LGOctree whole(field, 1.0, box, s);
        EXPECT_TRUE(lazy.PerCell());
        EXPECT_FALSE(whole.PerCell());
        for (const Ray& ray : SomeRays(rng, box, 400)) {
            const std::optional<double> a = lazy.FirstRoot(ray, 1e-5, 1e9);
            const std::optional<double> b = whole.FirstRoot(ray, 1e-5, 1e9);
            ASSERT_EQ(a.has_value(), b.has_value()) << "seed " << seed;
            // Both within the automatic tolerance (at most autoToleranceCap) of a root.
            if (a) {
                EXPECT_NEAR(*a, *b, 2 * s.autoToleranceCap) << "seed " << seed;
            }
        }
    }
}

// A lone point is a sphere of radius e: per-cell trees, rays with footprints wide enough
// that they search whole inner cells as leaves, still meet it within the tolerance.
TEST(LazyCells, CoarseDescentStaysWithinTolerance) {
    const Vec3 c{0.2, -0.1, 0.3};
    const Kernel k = Kernel::GascuelQuadratic(0.5, 2, 1.2);
    Field field({{"p", PointSkeleton{c}, k, 1}});
    OctreeSettings s = AutoAccuracy();
    for (double spread : {0.0, 1e-3, 0.05, 0.5}) {
        LazyCellStore store(1u << 30);
        const LGOctree tree(field, 1.0, field.SupportBounds(), s, -1, &store);
        for (uint64_t seed = 1; seed <= 200; ++seed) {
            Rng rng(seed);
            Ray ray{c + RandomUnit(rng) * Uniform(rng, 3, 6), {0, 0, 1}};
            ray.dir = Normalize(c + RandomPoint(rng, -0.6, 0.6) - ray.origin);
            ray.footprintSpread = spread;
            const Vec3 oc = ray.origin - c;
            const double b = Dot(oc, ray.dir), disc = b * b - (Dot(oc, oc) - 0.25);
            const std::optional<double> got = tree.FirstRoot(ray, 1e-5, 1e9);
            ASSERT_EQ(disc > 0, got.has_value()) << "spread " << spread << " seed " << seed;
            if (got) {
                EXPECT_NEAR(*got, -b - std::sqrt(disc), s.autoToleranceCap)
                    << "spread " << spread << " seed " << seed;
            }
        }
        // The rays start at least 0.9 from the 2.4-wide root box (corners at 2.08 from c):
        // with spread 0.5 their footprints there are over 0.45 wide, and 8 of them exceed the
        // root, so no ray descends and no cell is expanded; narrower ones descend.
        if (spread == 0.5) {
            EXPECT_EQ(store.UsedBytes(), 0u);
        } else {
            EXPECT_GT(store.UsedBytes(), 0u) << "spread " << spread;
        }
    }
}

// Full and Empty cells of a per-cell tree agree with the field's sign (Classify expands the
// cells on its way).
TEST(LazyCells, CellClassesAgreeWithSampling) {
    for (uint64_t seed = 21; seed <= 30; ++seed) {
        Rng rng(seed);
        std::vector<FieldTerm> terms = WalkTerms(rng);
        terms.back().weight = -0.5;
        Field field(terms);
        LazyCellStore store(1u << 30);
        const LGOctree tree(field, 1.0, field.SupportBounds(), OctreeSettings{}, -1, &store);
        int leaves = 0;
        for (int i = 0; i < 3000; ++i) {
            const Vec3 p = testing::RandomInBox(rng, tree.Box());
            const CellClass c = tree.Classify(p);
            const double g = field.Value(p) - 1.0;
            if (c == CellClass::Full) {
                ASSERT_GT(g, 0) << "seed " << seed;
            } else if (c == CellClass::Empty) {
                ASSERT_LT(g, 0) << "seed " << seed;
            } else {
                ++leaves;
            }
        }
        EXPECT_GT(leaves, 0);
        EXPECT_GT(store.UsedBytes(), 0u);
    }
}

}  // namespace
}  // namespace rs
