#include "libobj/list.h"

#include <atomic>
#include <cmath>
#include <functional>
#include <thread>

#include <gtest/gtest.h>

#include "libcommon/constants.h"
#include "libcommon/parallel_build.h"
#include "libcommon/random.h"
#include "libcommon/stats.h"
#include "libobj/object.h"
#include "libsurf/surface.h"
#include "test_shapes.h"

namespace rs {
namespace {

using testing::Probe;
using testing::TestPlane;
using testing::TestSphere;

std::shared_ptr<Object> Sphere(const Vec3& c, double r) {
    return Object::MakePrimitive(std::make_shared<TestSphere>(c, r));
}

std::shared_ptr<Object> MakeList(std::vector<std::shared_ptr<Object>> children) {
    auto list = std::make_shared<ListAggregate>();
    for (auto& c : children) list->AddChild(std::move(c));
    auto node = Object::MakeAggregate(list);
    node->PrepareFrame(0, 0);
    return node;
}

// A build loop on two real threads, which take indices from a shared counter.
void RunOnTwoThreads(long count, const std::function<void(long)>& body) {
    std::atomic<long> next{0};
    const auto work = [&] {
        for (long i; (i = next.fetch_add(1)) < count;) body(i);
    };
    std::thread helper(work);
    work();
    helper.join();
}

// HasPrimitive agrees with PrimitiveCount() > 0 through empty lists and instances.
TEST(ListAggregate, HasPrimitiveLooksThroughEmptyListsAndInstances) {
    const auto empty = MakeList({});
    EXPECT_FALSE(empty->HasPrimitive());
    const auto nested = MakeList({MakeList({}), MakeList({MakeList({})})});
    EXPECT_FALSE(nested->HasPrimitive());
    EXPECT_FALSE(Object::MakeInstance(nested)->HasPrimitive());
    const auto deep = MakeList({MakeList({}), Object::MakeInstance(MakeList({Sphere({0, 0, 0}, 1)}))});
    EXPECT_TRUE(deep->HasPrimitive());
    EXPECT_EQ(deep->PrimitiveCount(), 1);
    EXPECT_TRUE(Sphere({0, 0, 0}, 1)->HasPrimitive());
}

// A list of enough primitive children has them prepared in chunks on the build's threads
// (here two real ones): every child's box in the list, moved by its own transform, and the
// list's box are those of a serial preparation.
TEST(ListAggregate, ChildrenPreparedConcurrentlyGetTheirOwnBoxes) {
    const auto makeChildren = [] {
        std::vector<std::shared_ptr<Object>> children;
        for (int i = 0; i < 40000; ++i) {
            auto child = Sphere({0.001 * i, std::sin(i), 0}, 0.01 + 0.001 * (i % 7));
            child->parentFromObject.Append(Transform::Translate({0, 0, 0.5 * (i % 3)}));
            children.push_back(std::move(child));
        }
        return children;
    };
    const auto serialChildren = makeChildren();
    const auto serial = MakeList(serialChildren);
    const ParallelLoop twoThreads = RunOnTwoThreads;
    const auto children = makeChildren();
    std::shared_ptr<Object> list;
    {
        const ParallelBuildScope scope(&twoThreads);
        list = MakeList(children);
    }
    for (size_t i = 0; i < children.size(); ++i) {
        ASSERT_EQ(children[i]->BoundsInParent().lo, serialChildren[i]->BoundsInParent().lo) << i;
        ASSERT_EQ(children[i]->BoundsInParent().hi, serialChildren[i]->BoundsInParent().hi) << i;
    }
    EXPECT_EQ(list->BoundsInParent().lo, serial->BoundsInParent().lo);
    EXPECT_EQ(list->BoundsInParent().hi, serial->BoundsInParent().hi);
    EXPECT_NEAR(children[4]->BoundsInParent().lo.z, 0.5 - 0.014, 1e-12);  // its transform applied
}

// PrepareFrame's answers about the children (the list is bounded only when every child is;
// a transparent surface anywhere below, instances looking into their targets) are the same
// whether a large list's children are prepared on one thread or in chunks on two, with the
// children that are not plain primitives (instances, a plane) prepared after the chunks.
TEST(ListAggregate, ChildrenSummaryIsTheSameSeriallyAndInChunks) {
    const auto opaque = std::make_shared<Surface>(Surface::Default());
    auto clear = std::make_shared<Surface>(Surface::Default());
    clear->transp = 0.5;
    auto nearlyOpaque = std::make_shared<Surface>(Surface::Default());
    nearlyOpaque->transp = 0.5 * kEpsilon;  // below the shadows' threshold
    const ParallelLoop twoThreads = RunOnTwoThreads;
    struct Case {
        const char* what;
        std::shared_ptr<Surface> at17000;  // the surface of child 17000 (others: opaque)
        bool transparentInstance;          // child 30000 an instance of a clear sphere
        bool plane;                        // child 25000 an unbounded plane
        bool transparent, bounded;         // expected
    };
    const Case cases[] = {
        {"all opaque", opaque, false, false, false, true},
        {"one clear child", clear, false, false, true, true},
        {"transp below the threshold", nearlyOpaque, false, false, false, true},
        {"a clear instanced target", opaque, true, false, true, true},
        {"an unbounded child", opaque, false, true, false, false},
    };
    for (const Case& c : cases) {
        for (const bool parallel : {false, true}) {
            SCOPED_TRACE(::testing::Message() << c.what << (parallel ? ", in chunks" : ", serially"));
            std::vector<std::shared_ptr<Object>> children;
            for (int i = 0; i < 40000; ++i) {
                std::shared_ptr<Object> child = Sphere({0.001 * i, 0, 0}, 0.01);
                child->surface = i == 17000 ? c.at17000 : opaque;
                if (i == 30000 && c.transparentInstance) {
                    auto target = std::make_shared<ListAggregate>();
                    target->AddChild(Sphere({0, 1, 0}, 0.5));
                    auto targetNode = Object::MakeAggregate(target);
                    targetNode->surface = clear;
                    child = Object::MakeInstance(targetNode);
                }
                if (i == 25000 && c.plane) child = Object::MakePrimitive(std::make_shared<TestPlane>());
                children.push_back(std::move(child));
            }
            std::shared_ptr<Object> list;
            {
                const ParallelBuildScope scope(parallel ? &twoThreads : nullptr);
                list = MakeList(children);
            }
            EXPECT_EQ(list->HasTransparentSurfaceBelow(), c.transparent);
            EXPECT_EQ(list->IsBounded(), c.bounded);
        }
    }
    // The aggregate's own surface counts too.
    const auto clearList = Object::MakeAggregate(std::make_shared<ListAggregate>());
    clearList->surface = clear;
    clearList->PrepareFrame(0, 0);
    EXPECT_TRUE(clearList->HasTransparentSurfaceBelow());
}

// The list's surface-area hierarchy against a brute-force loop over the children, on clouds
// of spheres of very different sizes and on a geometric series of nested positions (which
// makes the heuristic cut off one item at a time, down to its depth limit).
TEST(ListAggregate, HierarchyFindsTheNearestHitOfEveryChild) {
    for (uint64_t seed = 1; seed <= 8; ++seed) {
        SCOPED_TRACE(::testing::Message() << "seed " << seed);
        Rng rng(seed);
        const auto uniform = [&](double lo, double hi) { return lo + (hi - lo) * rng.Uniform(); };
        std::vector<std::shared_ptr<Object>> children;
        const int count = 50 + static_cast<int>(rng.Uniform() * 1500);
        for (int i = 0; i < count; ++i) {
            if (seed % 2 == 0) {  // x = 2^-i: ever closer to the origin, ever smaller
                const double x = std::ldexp(1.0, -(i % 60));
                children.push_back(Sphere({x, uniform(-0.1, 0.1), 0}, x * 0.3));
            } else {
                const double r = rng.Uniform() < 0.05 ? uniform(1, 3) : uniform(0.01, 0.3);
                children.push_back(Sphere({uniform(-5, 5), uniform(-5, 5), uniform(-1, 1)}, r));
            }
        }
        auto list = MakeList(children);
        int hits = 0;
        for (int i = 0; i < 1000; ++i) {
            const Vec3 origin{uniform(-6, 6), uniform(-6, 6), uniform(-6, 6)};
            const auto& target = children[static_cast<size_t>(rng.Uniform() * children.size())];
            Vec3 aim = target->BoundsInParent().Center();
            aim += Vec3{uniform(-0.2, 0.2), uniform(-0.2, 0.2), uniform(-0.2, 0.2)} *
                   (i % 3 == 0 ? 10.0 : 1.0);
            const Ray ray{origin, Normalize(aim - origin), 0};
            double tBrute = kFar, tList = kFar;
            HitRecord hBrute, hList;
            bool fBrute = false;
            for (const auto& child : children)
                if (child->Intersect(ray, kEpsilon, tBrute, hBrute)) fBrute = true;
            ASSERT_EQ(list->Intersect(ray, kEpsilon, tList, hList), fBrute) << "ray " << i;
            ASSERT_EQ(list->Occluded(ray, kEpsilon, kFar), fBrute) << "ray " << i;
            if (!fBrute) continue;
            ++hits;
            ASSERT_EQ(tList, tBrute) << "ray " << i;
            ASSERT_EQ(hList.primitive, hBrute.primitive) << "ray " << i;
        }
        EXPECT_GT(hits, 100);
    }
}

TEST(ListAggregate, KeepsNearestHitWhateverTheOrder) {
    auto s5 = Sphere({5, 0, 0}, 1), s10 = Sphere({10, 0, 0}, 1), s15 = Sphere({15, 0, 0}, 1);
    auto list = MakeList({s15, s5, s10});
    HitRecord hit;
    double tMax = kFar;
    ASSERT_TRUE(list->Intersect({{0, 0, 0}, {1, 0, 0}}, kEpsilon, tMax, hit));
    EXPECT_DOUBLE_EQ(tMax, 4);  // sphere at x = 5 of radius 1
    EXPECT_DOUBLE_EQ(hit.t(), 4);
    EXPECT_EQ(hit.primitive, s5->primitive());
    ASSERT_EQ(hit.pathLength, 2);
    EXPECT_EQ(hit.path[0], s5.get());
    EXPECT_EQ(hit.path[1], list.get());
}

TEST(ListAggregate, MissLeavesTMaxAndHitUntouched) {
    auto list = MakeList({Sphere({5, 0, 0}, 1)});
    HitRecord hit;
    hit.pathLength = 7;
    double tMax = 3.5;  // the sphere's first hit is at t = 4
    EXPECT_FALSE(list->Intersect({{0, 0, 0}, {1, 0, 0}}, kEpsilon, tMax, hit));
    EXPECT_EQ(tMax, 3.5);
    EXPECT_EQ(hit.pathLength, 7);
}

TEST(ListAggregate, RespectsOpenInterval) {
    auto list = MakeList({Sphere({5, 0, 0}, 1)});
    HitRecord hit;
    double tMax = kFar;
    // tMin = 4 exactly excludes the entry hit: the exit at t = 6 is next.
    ASSERT_TRUE(list->Intersect({{0, 0, 0}, {1, 0, 0}}, 4, tMax, hit));
    EXPECT_DOUBLE_EQ(hit.t(), 6);
    tMax = 6;
    EXPECT_FALSE(list->Intersect({{0, 0, 0}, {1, 0, 0}}, 4, tMax, hit));
}

TEST(ListAggregate, TestsUnboundedChildrenFirst) {
    std::vector<int> log;
    auto list = MakeList({Object::MakePrimitive(std::make_shared<Probe>(1, &log, true)),
                          Object::MakePrimitive(std::make_shared<Probe>(2, &log, false)),
                          Object::MakePrimitive(std::make_shared<Probe>(3, &log, true))});
    HitRecord hit;
    double tMax = kFar;
    EXPECT_FALSE(list->aggregate()->Intersect({{-5, 0, 0}, {1, 0, 0}}, 0, tMax, hit));
    EXPECT_EQ(log, (std::vector<int>{2, 1, 3}));
}

TEST(ListAggregate, SkipsBoundedChildrenWhenTheRayMissesTheirBox) {
    std::vector<int> log;
    auto list = MakeList({Object::MakePrimitive(std::make_shared<Probe>(1, &log, true)),
                          Object::MakePrimitive(std::make_shared<Probe>(2, &log, false))});
    HitRecord hit;
    double tMax = kFar;
    // The bounded probe's box is [-1, 1]³; this ray passes at y = 5.
    list->aggregate()->Intersect({{-5, 5, 0}, {1, 0, 0}}, 0, tMax, hit);
    EXPECT_EQ(log, (std::vector<int>{2}));
    // A segment ending before the box is skipped too.
    log.clear();
    tMax = 3;  // the box starts at t = 4
    list->aggregate()->Intersect({{-5, 0, 0}, {1, 0, 0}}, 0, tMax, hit);
    EXPECT_EQ(log, (std::vector<int>{2}));
}

TEST(ListAggregate, UnboundedHitShrinksTheSegmentBeforeTheBoxTest) {
    // Plane z = 0 hit at t = 1; the sphere box (around z = -3) starts at t = 2.
    auto sphere = Sphere({0, 0, -3}, 1);
    auto plane = Object::MakePrimitive(std::make_shared<TestPlane>());
    auto list = MakeList({sphere, plane});
    HitRecord hit;
    double tMax = kFar;
    ASSERT_TRUE(list->Intersect({{0, 0, 1}, {0, 0, -1}}, kEpsilon, tMax, hit));
    EXPECT_DOUBLE_EQ(hit.t(), 1);
    EXPECT_EQ(hit.primitive, plane->primitive());
}

TEST(ListAggregate, BoundsDescribeTheBoundedChildren) {
    auto list = MakeList({Sphere({0, 0, 0}, 1), Sphere({4, 0, 0}, 2),
                          Object::MakePrimitive(std::make_shared<TestPlane>())});
    const Aggregate& agg = *list->aggregate();
    EXPECT_TRUE(agg.IsBounded());
    EXPECT_EQ(agg.Bounds().lo, (Vec3{-1, -2, -2}));
    EXPECT_EQ(agg.Bounds().hi, (Vec3{6, 2, 2}));
    // The node holding an unbounded child is unbounded as a whole.
    EXPECT_FALSE(list->IsBounded());

    auto planesOnly = MakeList({Object::MakePrimitive(std::make_shared<TestPlane>())});
    EXPECT_FALSE(planesOnly->aggregate()->IsBounded());
    EXPECT_FALSE(planesOnly->IsBounded());

    auto spheresOnly = MakeList({Sphere({0, 0, 0}, 1)});
    EXPECT_TRUE(spheresOnly->IsBounded());
    EXPECT_EQ(spheresOnly->BoundsInParent().hi, (Vec3{1, 1, 1}));
}

TEST(ListAggregate, NestedUnboundedChildIsNotClippedToTheSiblingsBox) {
    // World = list{ inner list{ plane, small sphere }, sphere far away }: a ray hitting the
    // plane far from both spheres must see it (spec §6: the original's clipping is a bug).
    auto inner = MakeList({Object::MakePrimitive(std::make_shared<TestPlane>()),
                           Sphere({0, 0, 5}, 1)});
    auto world = MakeList({inner, Sphere({0, 0, 10}, 1)});
    HitRecord hit;
    double tMax = kFar;
    ASSERT_TRUE(world->Intersect({{100, 100, 3}, {0, 0, -1}}, kEpsilon, tMax, hit));
    EXPECT_DOUBLE_EQ(hit.t(), 3);
    ASSERT_EQ(hit.pathLength, 3);
    EXPECT_EQ(hit.path[1], inner.get());
    EXPECT_EQ(hit.path[2], world.get());
}

TEST(ListAggregate, InstancesMapRaysIntoTheirSpace) {
    // A unit sphere at the origin, instanced scaled by 2 then moved to x = 10.
    auto shared = Sphere({0, 0, 0}, 1);
    auto instance = Object::MakeInstance(shared);
    instance->parentFromObject.Append(*Transform::Scale({2, 2, 2}));
    instance->parentFromObject.Append(Transform::Translate({10, 0, 0}));
    auto world = MakeList({shared, instance});
    HitRecord hit;
    double tMax = kFar;
    // From x = 20 toward −x: the instance spans x ∈ [8, 12], so the first hit is t = 8.
    ASSERT_TRUE(world->Intersect({{20, 0, 0}, {-1, 0, 0}}, kEpsilon, tMax, hit));
    EXPECT_DOUBLE_EQ(hit.t(), 8);
    ASSERT_EQ(hit.pathLength, 3);
    EXPECT_EQ(hit.path[0], shared.get());
    EXPECT_EQ(hit.path[1], instance.get());
    EXPECT_EQ(world->BoundsInParent().lo, (Vec3{-1, -2, -2}));
    EXPECT_EQ(world->BoundsInParent().hi, (Vec3{12, 2, 2}));
}

}  // namespace
}  // namespace rs
