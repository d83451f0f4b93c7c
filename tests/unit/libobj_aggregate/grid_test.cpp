#include "libobj/grid.h"

#include <gtest/gtest.h>

#include <functional>
#include <thread>
#include <vector>

#include "libcommon/constants.h"
#include "libcommon/parallel_build.h"
#include "libcommon/random.h"
#include "libcommon/stats.h"
#include "libobj/list.h"
#include "libobj/object.h"
#include "libobj/sphere.h"
#include "libobj/triangle.h"
#include "test_shapes.h"

namespace rs {
namespace {

using testing::Probe;
using testing::TestBox;
using testing::TestPlane;
using testing::TestSphere;

std::shared_ptr<Object> Wrap(std::shared_ptr<Aggregate> agg,
                             const std::vector<std::shared_ptr<Object>>& children) {
    for (const auto& c : children) agg->AddChild(c);
    auto node = Object::MakeAggregate(std::move(agg));
    node->PrepareFrame(0, 0);
    return node;
}

using Search = GridAggregate::Search;

double Uniform(Rng& rng, double lo, double hi) { return lo + (hi - lo) * rng.Uniform(); }

Vec3 RandomPoint(Rng& rng, double lo, double hi) {
    return {Uniform(rng, lo, hi), Uniform(rng, lo, hi), Uniform(rng, lo, hi)};
}

Vec3 RandomDirection(Rng& rng) {
    for (;;) {
        Vec3 d = RandomPoint(rng, -1, 1);
        double len2 = LengthSquared(d);
        if (len2 > 1e-4 && len2 <= 1) return d / std::sqrt(len2);
    }
}

// A random scene: spheres of many sizes (some spanning most of the grid), boxes, some of
// them instanced through random scales and translations, and optionally a plane.
std::vector<std::shared_ptr<Object>> RandomScene(Rng& rng, bool withPlane) {
    std::vector<std::shared_ptr<Object>> children;
    const int count = 10 + static_cast<int>(rng.Uniform() * 80);
    for (int i = 0; i < count; ++i) {
        const double r = rng.Uniform() < 0.1 ? Uniform(rng, 1, 4) : Uniform(rng, 0.05, 0.6);
        const Vec3 c = RandomPoint(rng, -5, 5);
        std::shared_ptr<Object> child;
        if (i % 7 == 3) {
            const Vec3 h = RandomPoint(rng, 0.05, 1);
            child = Object::MakePrimitive(std::make_shared<TestBox>(c - h, c + h));
        } else {
            child = Object::MakePrimitive(std::make_shared<TestSphere>(c, r));
        }
        if (i % 5 == 2) {
            auto instance = Object::MakeInstance(child);
            instance->parentFromObject.Append(*Transform::Scale(RandomPoint(rng, 0.3, 2)));
            instance->parentFromObject.Append(Transform::Translate(RandomPoint(rng, -2, 2)));
            child = instance;
        }
        children.push_back(child);
    }
    if (withPlane) children.push_back(Object::MakePrimitive(std::make_shared<TestPlane>()));
    return children;
}

// Snaps some direction components to zero so axis-parallel rays are covered.
Vec3 MaybeAxisParallel(Rng& rng, Vec3 d) {
    for (int a = 0; a < 3; ++a) {
        if (rng.Uniform() < 0.1) d[a] = 0;
    }
    return LengthSquared(d) > 0 ? d : Vec3{0, 0, 1};
}

// Ray number i from a random point of [-reach, reach]³: every other one aimed near (within
// ±aim) a random bounded child's box centre, so most of those hit; directions not always of
// unit length, some components snapped to zero.
Ray RandomRayAmong(Rng& rng, const std::vector<std::shared_ptr<Object>>& children, int i,
                   double reach, double aim) {
    const Vec3 origin = RandomPoint(rng, -reach, reach);
    Vec3 dir = RandomDirection(rng);
    if (i % 2 == 0) {
        const auto& target = children[static_cast<size_t>(rng.Uniform() * children.size())];
        if (target->IsBounded())
            dir = Normalize(target->BoundsInParent().Center() + RandomPoint(rng, -aim, aim) - origin);
    }
    return {origin, MaybeAxisParallel(rng, dir * Uniform(rng, 0.5, 2)), 0};
}

// Either search, forced or chosen.
TEST(GridAggregate, FindsTheSameHitsAsAListOnRandomScenes) {
    for (uint64_t seed = 1; seed <= 60; ++seed) {
        SCOPED_TRACE(::testing::Message() << "seed " << seed);
        Rng rng(seed);
        const auto children = RandomScene(rng, seed % 4 == 0);
        const int nx = 1 + static_cast<int>(rng.Uniform() * 12);
        const int ny = 1 + static_cast<int>(rng.Uniform() * 12);
        const int nz = 1 + static_cast<int>(rng.Uniform() * 12);
        const Search search = seed % 3 == 0 ? Search::Voxels : seed % 3 == 1 ? Search::Hierarchy
                                                                             : Search::Automatic;
        auto list = Wrap(std::make_shared<ListAggregate>(), children);
        auto grid = Wrap(std::make_shared<GridAggregate>(nx, ny, nz, search), children);
        EXPECT_EQ(grid->IsBounded(), list->IsBounded());
        EXPECT_EQ(grid->aggregate()->Bounds().lo, list->aggregate()->Bounds().lo);
        EXPECT_EQ(grid->aggregate()->Bounds().hi, list->aggregate()->Bounds().hi);
        int hits = 0;
        for (int i = 0; i < 3000; ++i) {
            // Origins inside and outside the grid.
            const Ray ray = RandomRayAmong(rng, children, i, 9, 0.2);
            const double tMin = rng.Uniform() < 0.2 ? Uniform(rng, 0, 5) : kEpsilon;
            const double tMaxStart = rng.Uniform() < 0.2 ? Uniform(rng, 1, 10) : kFar;
            double tList = tMaxStart, tGrid = tMaxStart;
            HitRecord hList, hGrid;
            const bool fList = list->Intersect(ray, tMin, tList, hList);
            const bool fGrid = grid->Intersect(ray, tMin, tGrid, hGrid);
            ASSERT_EQ(fList, fGrid) << "ray " << i;
            if (!fList) continue;
            ++hits;
            ASSERT_EQ(tList, tGrid) << "ray " << i;
            ASSERT_EQ(hList.primitive, hGrid.primitive) << "ray " << i;
            ASSERT_EQ(hList.pathLength, hGrid.pathLength) << "ray " << i;
            for (int k = 0; k + 1 < hList.pathLength; ++k) ASSERT_EQ(hList.path[k], hGrid.path[k]);
        }
        EXPECT_GT(hits, 300);
    }
}

// Sparse scenes in fine grids (two dense clusters in opposite corners, a few small spheres
// scattered between, a large one at one edge), so most voxels are empty and the walk crosses
// long runs of them in single moves: every ray finds what the list finds, and occlusion agrees.
TEST(GridAggregate, CrossingEmptyRunsKeepsEveryHit) {
    for (uint64_t seed = 1; seed <= 10; ++seed) {
        SCOPED_TRACE(::testing::Message() << "seed " << seed);
        Rng rng(seed);
        std::vector<std::shared_ptr<Object>> children;
        for (int i = 0; i < 60; ++i) {
            const Vec3 c = i < 25 ? RandomPoint(rng, -10, -8) : i < 50 ? RandomPoint(rng, 8, 10)
                                                                       : RandomPoint(rng, -10, 10);
            children.push_back(
                Object::MakePrimitive(std::make_shared<TestSphere>(c, Uniform(rng, 0.05, 0.3))));
        }
        children.push_back(Object::MakePrimitive(std::make_shared<TestSphere>(Vec3{10, -10, 0}, 2)));
        const int n = 20 + static_cast<int>(rng.Uniform() * 40);
        auto list = Wrap(std::make_shared<ListAggregate>(), children);
        auto grid = Wrap(std::make_shared<GridAggregate>(n, n + 7, n / 2 + 3, Search::Voxels), children);
        int hits = 0;
        for (int i = 0; i < 4000; ++i) {
            const Ray ray = RandomRayAmong(rng, children, i, 14, 0.3);
            const double tMaxStart = rng.Uniform() < 0.2 ? Uniform(rng, 1, 20) : kFar;
            double tList = tMaxStart, tGrid = tMaxStart;
            HitRecord hList, hGrid;
            const bool fList = list->Intersect(ray, kEpsilon, tList, hList);
            ASSERT_EQ(fList, grid->Intersect(ray, kEpsilon, tGrid, hGrid)) << "ray " << i;
            ASSERT_EQ(fList, grid->Occluded(ray, kEpsilon, tMaxStart)) << "ray " << i;
            if (!fList) continue;
            ++hits;
            ASSERT_EQ(tList, tGrid) << "ray " << i;
            ASSERT_EQ(hList.primitive, hGrid.primitive) << "ray " << i;
        }
        EXPECT_GT(hits, 500);
    }
}

TEST(GridAggregate, TestsAChildSpanningManyVoxelsOncePerRay) {
    // The grid is [-5, 5]³ in 8×8×8 voxels of 1.25: the big sphere (radius 4) is registered
    // in every voxel; small spheres sit in two opposite corners.
    auto big = Object::MakePrimitive(std::make_shared<TestSphere>(Vec3{0, 0, 0}, 4, "BigSphere"));
    auto grid = Wrap(std::make_shared<GridAggregate>(8, 8, 8, Search::Voxels),
                     {big, Object::MakePrimitive(std::make_shared<TestSphere>(Vec3{-4, -4, -4}, 1)),
                      Object::MakePrimitive(std::make_shared<TestSphere>(Vec3{4, 4, 4}, 1))});
    ResetStats();
    HitRecord hit;
    double tMax = kFar;
    // Along x at y = 3.5, z = −3.5: crosses all 8 voxels of its row, 4.95 > 4 from the
    // big sphere's centre and more than 1 from both small ones, so nothing is hit.
    EXPECT_FALSE(grid->Intersect({{-6, 3.5, -3.5}, {1, 0, 0}}, kEpsilon, tMax, hit));
    EXPECT_EQ(CounterTotal("BigSphere tests"), 1u);
}

TEST(GridAggregate, StopsOnceTheHitLiesInTheCurrentVoxel) {
    // Spheres of radius 0.3 on the integer lattice {0..9}³: the grid box is [−0.3, 9.3]³
    // in 10³ voxels of 0.96, so each sphere occupies exactly one voxel. A ray along the x
    // axis hits the sphere at the origin at x = −0.3 inside the first voxel: one test.
    std::vector<std::shared_ptr<Object>> spheres;
    for (int x = 0; x < 10; ++x)
        for (int y = 0; y < 10; ++y)
            for (int z = 0; z < 10; ++z)
                spheres.push_back(Object::MakePrimitive(
                    std::make_shared<TestSphere>(Vec3(x, y, z), 0.3, "LatticeSphere")));
    auto grid = Wrap(std::make_shared<GridAggregate>(10, 10, 10, Search::Voxels), spheres);
    ResetStats();
    HitRecord hit;
    double tMax = kFar;
    ASSERT_TRUE(grid->Intersect({{-5, 0, 0}, {1, 0, 0}}, kEpsilon, tMax, hit));
    EXPECT_DOUBLE_EQ(hit.t(), 4.7);
    EXPECT_EQ(CounterTotal("LatticeSphere tests"), 1u);
    // At y = z = 0.25 the ray misses every sphere (0.25·√2 > 0.3) but meets the boxes of
    // the ten spheres (i, 0, 0), one per voxel it crosses: ten tests.
    ResetStats();
    tMax = kFar;
    EXPECT_FALSE(grid->Intersect({{-5, 0.25, 0.25}, {1, 0, 0}}, kEpsilon, tMax, hit));
    EXPECT_EQ(CounterTotal("LatticeSphere tests"), 10u);
    // At y = z = 0.5 the same voxels are crossed, but the ray misses every sphere's box.
    ResetStats();
    tMax = kFar;
    EXPECT_FALSE(grid->Intersect({{-5, 0.5, 0.5}, {1, 0, 0}}, kEpsilon, tMax, hit));
    EXPECT_EQ(CounterTotal("LatticeSphere tests"), 0u);
}

// Many small objects (flat triangles, some in axis planes, and spheres) spanning a few voxels
// each, in fine grids, against a brute-force loop over every child: the mailboxes and the
// per-child box rejection must never lose or change a hit, and no child may be tested
// twice by one call; nor may the hierarchy's search (odd seeds).
TEST(GridAggregate, MailboxesAndBoxRejectionKeepEveryHit) {
    for (uint64_t seed = 1; seed <= 12; ++seed) {
        SCOPED_TRACE(::testing::Message() << "seed " << seed);
        Rng rng(seed);
        std::vector<std::shared_ptr<Object>> children;
        const int count = 200 + static_cast<int>(rng.Uniform() * 800);
        for (int i = 0; i < count; ++i) {
            const Vec3 c = RandomPoint(rng, -3, 3);
            const double size = rng.Uniform() < 0.05 ? Uniform(rng, 1, 3) : Uniform(rng, 0.05, 0.4);
            if (i % 3 == 0) {
                children.push_back(Object::MakePrimitive(
                    std::make_shared<Sphere>(size * 0.5, c)));
                continue;
            }
            Triangle::Points p{c + RandomPoint(rng, -size, size), c + RandomPoint(rng, -size, size),
                               c + RandomPoint(rng, -size, size)};
            if (i % 4 == 1) {  // in the plane z = c.z: a flat box
                for (Vec3& v : p) v.z = c.z;
            }
            if (Triangle::IsDegenerate(p)) continue;
            children.push_back(Object::MakePrimitive(std::make_shared<Triangle>(p, false)));
        }
        const int n = 4 + static_cast<int>(rng.Uniform() * 28);
        const Search search = seed % 2 == 0 ? Search::Voxels : Search::Hierarchy;
        auto grid = Wrap(std::make_shared<GridAggregate>(n, n + 3, n / 2 + 1, search), children);
        int hits = 0;
        for (int i = 0; i < 2000; ++i) {
            const Ray ray = RandomRayAmong(rng, children, i, 5, 0.1);
            const double tMin = rng.Uniform() < 0.2 ? Uniform(rng, 0, 3) : kEpsilon;
            double tBrute = kFar, tGrid = kFar;
            HitRecord hBrute, hGrid;
            bool fBrute = false;
            for (const auto& child : children)
                if (child->Intersect(ray, tMin, tBrute, hBrute)) fBrute = true;
            const uint64_t testsBefore = CounterTotal("Triangle tests") + CounterTotal("Sphere tests");
            const bool fGrid = grid->Intersect(ray, tMin, tGrid, hGrid);
            const uint64_t tests =
                CounterTotal("Triangle tests") + CounterTotal("Sphere tests") - testsBefore;
            ASSERT_LE(tests, children.size()) << "ray " << i;
            ASSERT_EQ(fBrute, fGrid) << "ray " << i;
            if (!fBrute) continue;
            ++hits;
            ASSERT_EQ(tBrute, tGrid) << "ray " << i;
            ASSERT_EQ(hBrute.primitive, hGrid.primitive) << "ray " << i;
        }
        EXPECT_GT(hits, 500);
    }
}

// Each call tests a child at most once, however many voxels hold it, also when grids nest
// (the inner grid's calls take stamps of their own while the outer call is under way).
TEST(GridAggregate, NestedGridsTestEachChildOncePerCall) {
    auto wide = Object::MakePrimitive(
        std::make_shared<TestSphere>(Vec3{0, 0, 0}, 4, "WideSphere"));
    auto inner = Wrap(std::make_shared<GridAggregate>(6, 6, 6, Search::Voxels),
                      {wide, Object::MakePrimitive(std::make_shared<TestSphere>(Vec3{3, 3, 3}, 1))});
    auto outer = Wrap(std::make_shared<GridAggregate>(7, 7, 7, Search::Voxels),
                      {inner, Object::MakePrimitive(
                                  std::make_shared<TestSphere>(Vec3{-4, -4, -4}, 1, "CornerSphere"))});
    for (int i = 0; i < 3; ++i) {
        ResetStats();
        HitRecord hit;
        double tMax = kFar;
        // Along x at y = 3.5, z = −3.5: inside the outer and inner boxes, clear of every sphere.
        EXPECT_FALSE(outer->Intersect({{-6, 3.5, -3.5}, {1, 0, 0}}, kEpsilon, tMax, hit));
        EXPECT_EQ(CounterTotal("WideSphere tests"), 1u);
    }
}

class GridSearches : public ::testing::TestWithParam<Search> {};

TEST_P(GridSearches, UnboundedChildrenAreTestedSeparately) {
    auto plane = Object::MakePrimitive(std::make_shared<TestPlane>());
    auto sphere = Object::MakePrimitive(std::make_shared<TestSphere>(Vec3{0, 0, 5}, 1));
    auto grid = Wrap(std::make_shared<GridAggregate>(4, 4, 4, GetParam()), {sphere, plane});
    EXPECT_TRUE(grid->aggregate()->IsBounded());
    EXPECT_FALSE(grid->IsBounded());
    HitRecord hit;
    double tMax = kFar;
    ASSERT_TRUE(grid->Intersect({{50, 50, 2}, {0, 0, -1}}, kEpsilon, tMax, hit));
    EXPECT_DOUBLE_EQ(hit.t(), 2);
    EXPECT_EQ(hit.primitive, plane->primitive());
    tMax = kFar;
    ASSERT_TRUE(grid->Intersect({{0, 0, 10}, {0, 0, -1}}, kEpsilon, tMax, hit));
    EXPECT_DOUBLE_EQ(hit.t(), 4);
    EXPECT_EQ(hit.primitive, sphere->primitive());
}

TEST_P(GridSearches, OnlyUnboundedChildren) {
    auto grid = Wrap(std::make_shared<GridAggregate>(3, 3, 3, GetParam()),
                     {Object::MakePrimitive(std::make_shared<TestPlane>())});
    EXPECT_FALSE(grid->aggregate()->IsBounded());
    HitRecord hit;
    double tMax = kFar;
    ASSERT_TRUE(grid->Intersect({{0, 0, 1}, {0, 0, -2}}, kEpsilon, tMax, hit));
    EXPECT_DOUBLE_EQ(hit.t(), 0.5);
}

TEST_P(GridSearches, FlatChildrenAndFlatGrids) {
    // Two zero-thickness boxes in the plane z = 0 make a flat grid.
    auto a = Object::MakePrimitive(std::make_shared<TestBox>(Vec3{0, 0, 0}, Vec3{1, 1, 0}));
    auto b = Object::MakePrimitive(std::make_shared<TestBox>(Vec3{2, 0, 0}, Vec3{3, 1, 0}));
    auto grid = Wrap(std::make_shared<GridAggregate>(5, 5, 5, GetParam()), {a, b});
    HitRecord hit;
    double tMax = kFar;
    ASSERT_TRUE(grid->Intersect({{2.5, 0.5, 3}, {0, 0, -1}}, kEpsilon, tMax, hit));
    EXPECT_DOUBLE_EQ(hit.t(), 3);
    EXPECT_EQ(hit.primitive, b->primitive());
    // Grazing along the plane z = 0 from x = −1: box a's face x = 0 at t = 1.
    tMax = kFar;
    ASSERT_TRUE(grid->Intersect({{-1, 0.5, 0}, {1, 0, 0}}, kEpsilon, tMax, hit));
    EXPECT_DOUBLE_EQ(hit.t(), 1);
}

TEST_P(GridSearches, SizesBelowOneAreRaisedToOne) {
    auto s = Object::MakePrimitive(std::make_shared<TestSphere>(Vec3{0, 0, 0}, 1));
    auto grid = Wrap(std::make_shared<GridAggregate>(0, -3, 1, GetParam()), {s});
    HitRecord hit;
    double tMax = kFar;
    ASSERT_TRUE(grid->Intersect({{0, 0, -3}, {0, 0, 1}}, kEpsilon, tMax, hit));
    EXPECT_DOUBLE_EQ(hit.t(), 2);
}

// The hierarchy is rebuilt too, not extended: its walk starts at the new frame's root.
TEST_P(GridSearches, RebuildsForEachFrame) {
    // An animated instance: translated by (time, 0, 0).
    auto s = Object::MakePrimitive(std::make_shared<TestSphere>(Vec3{0, 0, 0}, 1));
    auto moving = Object::MakeInstance(s);
    moving->parentFromObject.AppendAnimated(
        [](double time) -> std::optional<Transform> { return Transform::Translate({time, 0, 0}); });
    auto anchor = Object::MakePrimitive(std::make_shared<TestSphere>(Vec3{0, 10, 0}, 1));
    auto grid = Wrap(std::make_shared<GridAggregate>(4, 4, 4, GetParam()), {moving, anchor});
    grid->PrepareFrame(5, 0);
    HitRecord hit;
    double tMax = kFar;
    // At time 5 the sphere is centred on x = 5; a ray down the z axis through x = 5.
    ASSERT_TRUE(grid->Intersect({{5, 0, 10}, {0, 0, -1}, 5}, kEpsilon, tMax, hit));
    EXPECT_DOUBLE_EQ(hit.t(), 9);
    tMax = kFar;
    EXPECT_FALSE(grid->Intersect({{0, 0, 10}, {0, 0, -1}, 5}, kEpsilon, tMax, hit));
}

INSTANTIATE_TEST_SUITE_P(VoxelsAndHierarchy, GridSearches,
                         ::testing::Values(Search::Voxels, Search::Hierarchy));

TEST(GridAggregate, BuildsTheSameWhateverLoopRunsItsTasks) {
    // Probes (never hit, so a walk visits every child it reaches, in its order) in more
    // chunks and slabs than one (grid.h kChunk, kSlabs), built serially and by two threads,
    // one running the first half of the tasks forwards, the other the second half backwards:
    // each ray must visit the same children in the same order, through the voxels (cell
    // lists in child order) and through the hierarchy.
    const ParallelLoop twoHalves = [](long count, const std::function<void(long)>& body) {
        std::thread helper([&] {
            for (long i = count - 1; i >= count / 2; --i) body(i);
        });
        for (long i = 0; i < count / 2; ++i) body(i);
        helper.join();
    };
    for (const Search search : {Search::Voxels, Search::Hierarchy}) {
        std::vector<int> logs[2];
        std::shared_ptr<Object> grids[2];
        for (int built = 0; built < 2; ++built) {
            Rng rng(31);
            std::vector<std::shared_ptr<Object>> probes;
            for (int i = 0; i < 9000; ++i) {
                const Vec3 c = RandomPoint(rng, -10, 10), h = RandomPoint(rng, 0.05, 0.8);
                probes.push_back(Object::MakePrimitive(
                    std::make_shared<Probe>(i, &logs[built], true, Bounds3{c - h, c + h})));
            }
            const ParallelBuildScope scope(built == 1 ? &twoHalves : nullptr);
            grids[built] = Wrap(std::make_shared<GridAggregate>(20, 24, 40, search), probes);
        }
        Rng rng(32);
        int reaching = 0;
        for (int r = 0; r < 100; ++r) {
            Ray ray;
            ray.origin = RandomPoint(rng, -14, 14);
            ray.dir = Normalize(RandomPoint(rng, -8, 8) - ray.origin);
            for (int built = 0; built < 2; ++built) {
                double tMax = 100;
                HitRecord hit;
                grids[built]->Intersect(ray, 0, tMax, hit);
            }
            reaching += !logs[0].empty();
            ASSERT_EQ(logs[0], logs[1]) << "ray " << r;
            logs[0].clear();
            logs[1].clear();
        }
        EXPECT_GT(reaching, 90);
    }
}

TEST(GridAggregate, AutomaticSearchTakesTheCheaperEstimate) {
    // A fine grid (80³ voxels of 0.12) over a sparse lattice of 1000 small spheres: a ray
    // crosses about 80 voxels, most empty, where the hierarchy needs a few node tests on
    // the way down to one sphere (about log4 1000 levels).
    std::vector<std::shared_ptr<Object>> lattice;
    for (int x = 0; x < 10; ++x)
        for (int y = 0; y < 10; ++y)
            for (int z = 0; z < 10; ++z)
                lattice.push_back(Object::MakePrimitive(std::make_shared<TestSphere>(Vec3(x, y, z), 0.3)));
    auto fine = Wrap(std::make_shared<GridAggregate>(80, 80, 80), lattice);
    EXPECT_FALSE(static_cast<const GridAggregate*>(fine->aggregate())->SearchesVoxels());
    // One voxel holding 40 nested spheres, all spanning the whole box: the hierarchy cannot
    // separate them (every node box is the root's), so it pays its node tests on top of
    // the 40 sphere visits, where the voxel walk checks 40 entries in one cell.
    std::vector<std::shared_ptr<Object>> nested;
    for (int i = 0; i < 40; ++i)
        nested.push_back(Object::MakePrimitive(std::make_shared<TestSphere>(Vec3{0.01 * i, 0, 0}, 5)));
    auto coarse = Wrap(std::make_shared<GridAggregate>(1, 1, 1), nested);
    EXPECT_TRUE(static_cast<const GridAggregate*>(coarse->aggregate())->SearchesVoxels());
}

}  // namespace
}  // namespace rs
