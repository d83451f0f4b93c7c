// BoundingVolumeHierarchy against brute force over random boxes and rays: both traversals
// visit every item whose box meets the segment exactly once (when no visit shrinks it; items
// sharing a leaf with one may be visited too), find the nearest of per-item hits however the
// segment shrinks, and VisitContaining finds every box holding a point, once. The walks in
// entry order and by point exist for median builds only (an SAH build keeps only the wide
// tree), so for SAH builds only the wide walk is tested. Box-ray tests themselves are Bounds3's (tested in libcommon);
// what is tested here is that the hierarchy loses no item and keeps no stale one.
#include "libgeom/bvh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <functional>
#include <limits>
#include <set>
#include <thread>
#include <vector>

#include "libcommon/parallel_build.h"
#include "libcommon/random.h"

namespace rs {
namespace {

using Split = BoundingVolumeHierarchy::Split;

double Uniform(Rng& rng, double lo, double hi) { return lo + (hi - lo) * rng.Uniform(); }

Vec3 RandomPoint(Rng& rng, double extent) {
    return {Uniform(rng, -extent, extent), Uniform(rng, -extent, extent),
            Uniform(rng, -extent, extent)};
}

// Boxes of random sizes in [-10, 10]^3; every fourth shares its centre with the previous
// one (ties in the median split), and every seventh is flat along an axis.
std::vector<Bounds3> RandomBoxes(Rng& rng, int count) {
    std::vector<Bounds3> boxes;
    for (int i = 0; i < count; ++i) {
        const Vec3 centre = (i % 4 == 3) ? boxes.back().Center() : RandomPoint(rng, 10);
        Vec3 half{Uniform(rng, 0.01, 2), Uniform(rng, 0.01, 2), Uniform(rng, 0.01, 2)};
        if (i % 7 == 6) half[i % 3] = 0;
        boxes.emplace_back(centre - half, centre + half);
    }
    return boxes;
}

// Rays from outside and inside the boxes' region; one in five parallel to an axis plane.
Ray RandomRay(Rng& rng, int index) {
    Ray ray;
    ray.origin = RandomPoint(rng, 14);
    ray.dir = RandomPoint(rng, 1);
    if (index % 5 == 4) ray.dir[index % 3] = 0;
    if (LengthSquared(ray.dir) == 0) ray.dir = {1, 0, 0};
    return ray;
}

std::set<int> BruteForceMeeting(const std::vector<Bounds3>& boxes, const Ray& ray, double tMin,
                                double tMax) {
    std::set<int> items;
    for (size_t i = 0; i < boxes.size(); ++i) {
        double t0 = tMin, t1 = tMax;
        if (boxes[i].ClipRay(ray, t0, t1)) items.insert(static_cast<int>(i));
    }
    return items;
}

// Each item's "hit": a point of its box's clipped segment, fixed per item and ray.
std::vector<double> ItemHits(const std::vector<Bounds3>& boxes, const Ray& ray, double tMin,
                             double tMax, Rng& rng) {
    std::vector<double> hits(boxes.size(), std::numeric_limits<double>::infinity());
    for (size_t i = 0; i < boxes.size(); ++i) {
        double t0 = tMin, t1 = tMax;
        if (boxes[i].ClipRay(ray, t0, t1)) hits[i] = Uniform(rng, t0, t1);
    }
    return hits;
}

class BvhTest : public ::testing::TestWithParam<Split> {};

TEST_P(BvhTest, BothTraversalsVisitEveryItemMeetingTheSegmentOnce) {
    Rng rng(11);
    // (20000 items: a tree built as a top and parts, bvh.h kParallelBuildItems.)
    for (int count : {1, 2, 3, 5, 17, 64, 200, 20000}) {
        BoundingVolumeHierarchy bvh;
        const std::vector<Bounds3> boxes = RandomBoxes(rng, count);
        bvh.Build(boxes, GetParam());
        for (int r = 0; r < 300; ++r) {
            const Ray ray = RandomRay(rng, r);
            const double tMin = Uniform(rng, -5, 5), tMaxStart = tMin + Uniform(rng, 0, 40);
            const std::set<int> expected = BruteForceMeeting(boxes, ray, tMin, tMaxStart);
            std::multiset<int> byAxis, byEntry;
            double tMax = tMaxStart;
            bvh.Traverse(ray, tMin, tMax, [&](int i) { return byAxis.insert(i), false; });
            std::vector<const std::multiset<int>*> walks{&byAxis};
            if (GetParam() == Split::Median) {
                bvh.TraverseInEntryOrder(ray, tMin, tMax, [&](int i) { return byEntry.insert(i), false; });
                walks.push_back(&byEntry);
            }
            for (const std::multiset<int>* visited : walks) {
                for (int i : expected) EXPECT_EQ(visited->count(i), 1u) << count << " boxes, ray " << r;
                EXPECT_EQ(std::set<int>(visited->begin(), visited->end()).size(), visited->size());
            }
            EXPECT_EQ(tMax, tMaxStart);
        }
    }
}

TEST_P(BvhTest, ShrinkingTraversalsFindTheNearestHit) {
    Rng rng(12);
    for (int count : {1, 4, 33, 150, 20000}) {
        BoundingVolumeHierarchy bvh;
        const std::vector<Bounds3> boxes = RandomBoxes(rng, count);
        bvh.Build(boxes, GetParam());
        for (int r = 0; r < 400; ++r) {
            const Ray ray = RandomRay(rng, r);
            const double tMin = 0, tMaxStart = 60;
            const std::vector<double> hits = ItemHits(boxes, ray, tMin, tMaxStart, rng);
            const double nearest = *std::min_element(hits.begin(), hits.end());
            const auto nearestOf = [&](auto traverse) {
                double tMax = tMaxStart;
                const bool found = traverse(tMax, [&](int i) {
                    if (!(hits[i] < tMax)) return false;
                    tMax = hits[i];
                    return true;
                });
                EXPECT_EQ(found, nearest < tMaxStart);
                return tMax;
            };
            const double expected = nearest < tMaxStart ? nearest : tMaxStart;
            EXPECT_EQ(expected, nearestOf([&](double& tMax, auto visit) {
                return bvh.Traverse(ray, tMin, tMax, visit);
            })) << count << " boxes, ray " << r;
            if (GetParam() != Split::Median) continue;
            EXPECT_EQ(expected, nearestOf([&](double& tMax, auto visit) {
                return bvh.TraverseInEntryOrder(ray, tMin, tMax, visit);
            })) << count << " boxes, ray " << r;
        }
    }
}

TEST_P(BvhTest, OcclusionTraversalStopsAtTheFirstHit) {
    Rng rng(13);
    BoundingVolumeHierarchy bvh;
    const std::vector<Bounds3> boxes = RandomBoxes(rng, 80);
    bvh.Build(boxes, GetParam());
    for (int r = 0; r < 400; ++r) {
        const Ray ray = RandomRay(rng, r);
        int visitsAfterHit = 0;
        bool anyBlockerVisited = false;
        bool hitSeen = false;
        double tMax = 60;
        // Items of even index are opaque blockers.
        const bool occluded = bvh.Traverse<true>(ray, 0, tMax, [&](int i) {
            if (hitSeen) ++visitsAfterHit;
            hitSeen = hitSeen || i % 2 == 0;
            return i % 2 == 0;
        });
        // Whether the full walk would visit a blocker at all.
        double fullMax = 60;
        bvh.Traverse(ray, 0, fullMax, [&](int i) {
            anyBlockerVisited = anyBlockerVisited || i % 2 == 0;
            return false;
        });
        EXPECT_EQ(occluded, anyBlockerVisited) << "ray " << r;
        EXPECT_EQ(visitsAfterHit, 0) << "ray " << r;
    }
}

TEST_P(BvhTest, VisitContainingFindsEveryBoxHoldingThePointOnce) {
    if (GetParam() != Split::Median) GTEST_SKIP() << "median builds only";
    Rng rng(14);
    BoundingVolumeHierarchy bvh;
    const std::vector<Bounds3> boxes = RandomBoxes(rng, 120);
    bvh.Build(boxes, GetParam());
    for (int k = 0; k < 2000; ++k) {
        // Half the points are box corners, on the boundary.
        const Vec3 p = k % 2 ? RandomPoint(rng, 11) : boxes[k % boxes.size()].Corner(k % 8);
        std::multiset<int> found;
        bvh.VisitContaining(p, [&](int i) { found.insert(i); });
        for (size_t i = 0; i < boxes.size(); ++i) {
            if (!boxes[i].Contains(p)) continue;
            EXPECT_EQ(found.count(static_cast<int>(i)), 1u) << "point " << k;
        }
        EXPECT_EQ(std::set<int>(found.begin(), found.end()).size(), found.size());
    }
}

TEST_P(BvhTest, EmptyHierarchyVisitsNothing) {
    BoundingVolumeHierarchy bvh;
    bvh.Build({}, GetParam());
    EXPECT_TRUE(bvh.IsEmpty());
    Ray ray;
    ray.dir = {1, 0, 0};
    double tMax = 1;
    int visits = 0;
    EXPECT_FALSE(bvh.Traverse(ray, 0, tMax, [&](int) { return ++visits, true; }));
    EXPECT_FALSE(bvh.TraverseInEntryOrder(ray, 0, tMax, [&](int) { return ++visits, true; }));
    EXPECT_EQ(visits, 0);
}

TEST_P(BvhTest, BuildingAgainReplacesTheTree) {
    Rng rng(15);
    BoundingVolumeHierarchy bvh;
    bvh.Build(RandomBoxes(rng, 40), GetParam());
    // The second set far from the first: a walk through a stale tree would miss it.
    std::vector<Bounds3> moved = RandomBoxes(rng, 30);
    for (Bounds3& b : moved) b = {b.lo + Vec3{100, 0, 0}, b.hi + Vec3{100, 0, 0}};
    bvh.Build(moved, GetParam());
    for (int r = 0; r < 200; ++r) {
        Ray ray = RandomRay(rng, r);
        ray.origin.x += 100;
        const std::set<int> expected = BruteForceMeeting(moved, ray, 0, 60);
        std::set<int> visited;
        double tMax = 60;
        bvh.Traverse(ray, 0, tMax, [&](int i) { return visited.insert(i), false; });
        for (int i : expected) EXPECT_EQ(visited.count(i), 1u) << "ray " << r;
    }
}

// The sequence of items each walk visits (no visit shrinking the segment) for random rays,
// and the items containing random points: a fingerprint of the tree's structure.
std::vector<int> WalkFingerprint(const BoundingVolumeHierarchy& bvh, Rng& rng) {
    std::vector<int> fingerprint;
    const auto record = [&](int i) { return fingerprint.push_back(i), false; };
    for (int r = 0; r < 200; ++r) {
        const Ray ray = RandomRay(rng, r);
        double tMax = 40;
        bvh.Traverse(ray, -5, tMax, record);
        fingerprint.push_back(-1);
        bvh.Traverse<true>(ray, -5, tMax, record);
        fingerprint.push_back(-2);
        bvh.TraverseInEntryOrder(ray, -5, tMax, record);  // median builds only
        fingerprint.push_back(-3);
        bvh.VisitContaining(RandomPoint(rng, 10), [&](int i) { fingerprint.push_back(i); });
        fingerprint.push_back(-4);
    }
    return fingerprint;
}

TEST_P(BvhTest, BuildsTheSameTreeWhateverLoopRunsItsTasks) {
    // Enough boxes for the build to split into tasks (bvh.h kParallelBuildItems), built with
    // no loop installed (every task in order on this thread), by three threads taking
    // indices from a shared counter, and by a loop running the indices backwards.
    Rng boxRng(21);
    const std::vector<Bounds3> boxes = RandomBoxes(boxRng, 20000);
    BoundingVolumeHierarchy serial;
    serial.Build(boxes, GetParam());
    Rng rayRng(22);
    const std::vector<int> expected = WalkFingerprint(serial, rayRng);
    const ParallelLoop threads = [](long count, const std::function<void(long)>& body) {
        std::atomic<long> next{0};
        const auto work = [&] {
            for (long i; (i = next.fetch_add(1)) < count;) body(i);
        };
        std::vector<std::thread> helpers;
        for (int t = 0; t < 2; ++t) helpers.emplace_back(work);
        work();
        for (std::thread& t : helpers) t.join();
    };
    const ParallelLoop backwards = [](long count, const std::function<void(long)>& body) {
        for (long i = count - 1; i >= 0; --i) body(i);
    };
    for (const ParallelLoop* loop : {&threads, &backwards}) {
        BoundingVolumeHierarchy bvh;
        {
            const ParallelBuildScope scope(loop);
            bvh.Build(boxes, GetParam());
        }
        EXPECT_EQ(bvh.ExpectedCost(), serial.ExpectedCost());
        Rng again(22);
        EXPECT_EQ(WalkFingerprint(bvh, again), expected) << (loop == &threads ? "threads" : "backwards");
    }
}

TEST(BvhCost, ExpectedCostCountsNodeAndItemTestsByArea) {
    // Unit cubes at x = 0, 10, 20: median splits give a root over [0, 21] x [0, 1]^2 (half
    // area 43) with two leaf lanes, cube 0 (half area 3) and cubes 1-2 ([10, 21] x [0, 1]^2,
    // 23): one wide node test plus 3/43 of one item and 23/43 of two.
    std::vector<Bounds3> cubes;
    for (double x : {0.0, 10.0, 20.0}) cubes.emplace_back(Vec3{x, 0, 0}, Vec3{x + 1, 1, 1});
    BoundingVolumeHierarchy bvh;
    bvh.Build(cubes, Split::Median);
    EXPECT_DOUBLE_EQ(bvh.ExpectedCost(), (43.0 + 3 + 2 * 23) / 43);
    // One item: its leaf is the root, met by every ray meeting the root.
    bvh.Build({cubes[0]}, Split::SurfaceArea);
    EXPECT_DOUBLE_EQ(bvh.ExpectedCost(), 2);
    bvh.Build({}, Split::SurfaceArea);
    EXPECT_EQ(bvh.ExpectedCost(), 0);
}

INSTANTIATE_TEST_SUITE_P(Splits, BvhTest, ::testing::Values(Split::Median, Split::SurfaceArea),
                         [](const ::testing::TestParamInfo<Split>& split) {
                             return split.param == Split::Median ? "Median" : "SurfaceArea";
                         });

}  // namespace
}  // namespace rs
