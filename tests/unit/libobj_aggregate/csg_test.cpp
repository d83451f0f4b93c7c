#include "libobj/csg.h"

#include <cmath>

#include <gtest/gtest.h>

#include "libcommon/constants.h"
#include "libobj/hit_classify.h"
#include "libobj/list.h"
#include "libobj/object.h"
#include "test_shapes.h"

namespace rs {
namespace {

using testing::TestBox;
using testing::TestSphere;
using Op = CsgAggregate::Op;

struct Crossing {
    double t;
    bool enters;
};

std::shared_ptr<Object> Sphere(const Vec3& c, double r) {
    return Object::MakePrimitive(std::make_shared<TestSphere>(c, r));
}

std::shared_ptr<Object> Csg(Op op, std::vector<std::shared_ptr<Object>> operands) {
    auto csg = std::make_shared<CsgAggregate>(op);
    for (auto& o : operands) csg->AddChild(std::move(o));
    auto node = Object::MakeAggregate(csg);
    node->PrepareFrame(0, 0);
    return node;
}

// Every boundary crossing of `node` along `ray` after tMin, front to back, with the
// enter/leave classification a renderer would see.
std::vector<Crossing> Walk(const Object& node, const Ray& ray, double tMin = kEpsilon) {
    std::vector<Crossing> out;
    for (;;) {
        HitRecord hit;
        double tMax = kFar;
        if (!node.Intersect(ray, tMin, tMax, hit)) return out;
        EXPECT_EQ(tMax, hit.t());
        out.push_back({hit.t(), HitEnters(ray, hit)});
        tMin = hit.t();
        if (out.size() > 16) return out;
    }
}

void ExpectCrossings(const std::vector<Crossing>& actual, const std::vector<Crossing>& expected) {
    ASSERT_EQ(actual.size(), expected.size());
    for (size_t i = 0; i < actual.size(); ++i) {
        EXPECT_NEAR(actual[i].t, expected[i].t, 1e-12) << "crossing " << i;
        EXPECT_EQ(actual[i].enters, expected[i].enters) << "crossing " << i;
    }
}

// A: unit sphere at the origin; B: unit sphere at (1, 0, 0). On the x axis A covers
// [−1, 1] and B covers [0, 2].
class TwoSpheres : public ::testing::Test {
  protected:
    std::shared_ptr<Object> a = Sphere({0, 0, 0}, 1);
    std::shared_ptr<Object> b = Sphere({1, 0, 0}, 1);
    const Ray alongX{{-5, 0, 0}, {1, 0, 0}};
    const Ray backwards{{5, 0, 0}, {-1, 0, 0}};
};

TEST_F(TwoSpheres, Union) {
    auto u = Csg(Op::Union, {a, b});
    ExpectCrossings(Walk(*u, alongX), {{4, true}, {7, false}});      // x = −1, 2
    ExpectCrossings(Walk(*u, backwards), {{3, true}, {6, false}});   // x = 2, −1
}

TEST_F(TwoSpheres, Intersect) {
    auto i = Csg(Op::Intersect, {a, b});
    ExpectCrossings(Walk(*i, alongX), {{5, true}, {6, false}});      // x = 0, 1
    ExpectCrossings(Walk(*i, backwards), {{4, true}, {5, false}});   // x = 1, 0
}

TEST_F(TwoSpheres, Difference) {
    auto ab = Csg(Op::Difference, {a, b});
    ExpectCrossings(Walk(*ab, alongX), {{4, true}, {5, false}});     // x = −1, 0 (B inverted)
    ExpectCrossings(Walk(*ab, backwards), {{5, true}, {6, false}});  // x = 0 (B inverted), −1
    auto ba = Csg(Op::Difference, {b, a});
    ExpectCrossings(Walk(*ba, alongX), {{6, true}, {7, false}});     // x = 1 (A inverted), 2
}

TEST_F(TwoSpheres, OffAxisRay) {
    // y = 0.5: the chords are x ∈ [−h, h] for A and [1 − h, 1 + h] for B, h = √0.75.
    const double h = std::sqrt(0.75);
    const Ray ray{{-5, 0.5, 0}, {1, 0, 0}};
    ExpectCrossings(Walk(*Csg(Op::Union, {a, b}), ray), {{5 - h, true}, {6 + h, false}});
    ExpectCrossings(Walk(*Csg(Op::Intersect, {a, b}), ray), {{6 - h, true}, {5 + h, false}});
    ExpectCrossings(Walk(*Csg(Op::Difference, {a, b}), ray), {{5 - h, true}, {6 - h, false}});
}

TEST_F(TwoSpheres, NonUnitDirectionScalesT) {
    const Ray ray{{-5, 0, 0}, {2, 0, 0}};
    ExpectCrossings(Walk(*Csg(Op::Union, {a, b}), ray), {{2, true}, {3.5, false}});
    ExpectCrossings(Walk(*Csg(Op::Difference, {a, b}), ray), {{2, true}, {2.5, false}});
}

TEST_F(TwoSpheres, RayStartingInsideOneOperand) {
    // From x = −0.5 (inside A only): A leaves at t = 1.5, B enters at 0.5 and leaves at 2.5.
    const Ray ray{{-0.5, 0, 0}, {1, 0, 0}};
    ExpectCrossings(Walk(*Csg(Op::Union, {a, b}), ray), {{2.5, false}});
    ExpectCrossings(Walk(*Csg(Op::Intersect, {a, b}), ray), {{0.5, true}, {1.5, false}});
    ExpectCrossings(Walk(*Csg(Op::Difference, {a, b}), ray), {{0.5, false}});
    ExpectCrossings(Walk(*Csg(Op::Difference, {b, a}), ray), {{1.5, true}, {2.5, false}});
}

TEST_F(TwoSpheres, RayStartingInsideBothOperands) {
    // From x = 0.5: A leaves at t = 0.5, B at t = 1.5.
    const Ray ray{{0.5, 0, 0}, {1, 0, 0}};
    ExpectCrossings(Walk(*Csg(Op::Union, {a, b}), ray), {{1.5, false}});
    ExpectCrossings(Walk(*Csg(Op::Intersect, {a, b}), ray), {{0.5, false}});
    ExpectCrossings(Walk(*Csg(Op::Difference, {a, b}), ray), {});
    ExpectCrossings(Walk(*Csg(Op::Difference, {b, a}), ray), {{0.5, true}, {1.5, false}});
}

TEST_F(TwoSpheres, RespectsTheSegment) {
    auto u = Csg(Op::Union, {a, b});
    HitRecord hit;
    double tMax = 3.9;  // the union starts at t = 4
    EXPECT_FALSE(u->Intersect(alongX, kEpsilon, tMax, hit));
    EXPECT_EQ(tMax, 3.9);
    tMax = 4.5;
    ASSERT_TRUE(u->Intersect(alongX, kEpsilon, tMax, hit));
    EXPECT_DOUBLE_EQ(tMax, 4);
    EXPECT_EQ(hit.enterOverride, 1);
    ASSERT_EQ(hit.pathLength, 2);
    EXPECT_EQ(hit.path[0], a.get());
    EXPECT_EQ(hit.path[1], u.get());
    // The intersection's first crossing (t = 5) lies beyond tMax = 4.5: rejected hits on
    // the way there do not count.
    tMax = 4.5;
    EXPECT_FALSE(Csg(Op::Intersect, {a, b})->Intersect(alongX, kEpsilon, tMax, hit));
}

TEST_F(TwoSpheres, Bounds) {
    auto u = Csg(Op::Union, {a, b});
    EXPECT_EQ(u->BoundsInParent().lo, (Vec3{-1, -1, -1}));
    EXPECT_EQ(u->BoundsInParent().hi, (Vec3{2, 1, 1}));
    auto i = Csg(Op::Intersect, {a, b});
    EXPECT_EQ(i->BoundsInParent().lo, (Vec3{0, -1, -1}));
    EXPECT_EQ(i->BoundsInParent().hi, (Vec3{1, 1, 1}));
    auto d = Csg(Op::Difference, {a, b});
    EXPECT_EQ(d->BoundsInParent().lo, (Vec3{-1, -1, -1}));
    EXPECT_EQ(d->BoundsInParent().hi, (Vec3{1, 1, 1}));
    EXPECT_TRUE(u->IsClosed());
    EXPECT_TRUE(u->IsBounded());
    EXPECT_STREQ(u->aggregate()->TypeName(), "union");
}

TEST_F(TwoSpheres, OperandCountOtherThanTwoHitsNothing) {
    auto one = std::make_shared<CsgAggregate>(Op::Union);
    one->AddChild(a);
    EXPECT_FALSE(one->HasTwoOperands());
    auto three = std::make_shared<CsgAggregate>(Op::Union);
    for (const auto& o : {a, b, a}) three->AddChild(o);
    EXPECT_FALSE(three->HasTwoOperands());
    for (const auto& csg : {one, three}) {
        auto node = Object::MakeAggregate(csg);
        node->PrepareFrame(0, 0);
        HitRecord hit;
        double tMax = kFar;
        EXPECT_FALSE(node->Intersect(alongX, kEpsilon, tMax, hit));
    }
}

TEST(Csg, BoxMinusSphere) {
    // Box [−1, 1]³ minus the sphere of radius 0.5 at (1, 0, 0): along x the box is entered
    // at x = −1; the sphere is entered at x = 0.5 inside the box (a leaving crossing); the
    // box's face x = 1 lies inside the sphere and the sphere's exit x = 1.5 outside the box.
    auto box = Object::MakePrimitive(std::make_shared<TestBox>(Vec3{-1, -1, -1}, Vec3{1, 1, 1}));
    auto hole = Sphere({1, 0, 0}, 0.5);
    auto d = Csg(Op::Difference, {box, hole});
    ExpectCrossings(Walk(*d, {{-5, 0, 0}, {1, 0, 0}}), {{4, true}, {5.5, false}});
    // From x = 1.25 (inside the sphere, outside the box) toward −x: the box face x = 1 lies
    // inside the sphere; the sphere's exit x = 0.5 lies in the box (entering the result).
    ExpectCrossings(Walk(*d, {{1.25, 0, 0}, {-1, 0, 0}}), {{0.75, true}, {2.25, false}});
}

TEST(Csg, NestedCsg) {
    // (A ∪ B) − C with C of radius 0.25 at (0.5, 0, 0): along x the solid is
    // [−1, 0.25] ∪ [0.75, 2].
    auto u = Csg(Op::Union, {Sphere({0, 0, 0}, 1), Sphere({1, 0, 0}, 1)});
    auto d = Csg(Op::Difference, {u, Sphere({0.5, 0, 0}, 0.25)});
    const Ray ray{{-5, 0, 0}, {1, 0, 0}};
    ExpectCrossings(Walk(*d, ray), {{4, true}, {5.25, false}, {5.75, true}, {7, false}});
    // Starting inside the hole.
    ExpectCrossings(Walk(*d, {{0.5, 0, 0}, {1, 0, 0}}), {{0.25, true}, {1.5, false}});

    // The same union intersected with a copy of itself moved by 0.5 along x:
    // [−1, 2] ∩ [−0.5, 2.5] = [−0.5, 2].
    auto moved = Object::MakeInstance(u);
    moved->parentFromObject.Append(Transform::Translate({0.5, 0, 0}));
    auto i = Csg(Op::Intersect, {u, moved});
    ExpectCrossings(Walk(*i, ray), {{4.5, true}, {7, false}});
}

TEST(Csg, InstancedThroughTransforms) {
    // The nested solid above (crossings at x = −1, 0.25, 0.75, 2 on its axis), instanced
    // scaled by 2 then moved to y = 3: on the line y = 3 it crosses x = −2, 0.5, 1.5, 4.
    auto u = Csg(Op::Union, {Sphere({0, 0, 0}, 1), Sphere({1, 0, 0}, 1)});
    auto d = Csg(Op::Difference, {u, Sphere({0.5, 0, 0}, 0.25)});
    auto instance = Object::MakeInstance(d);
    instance->parentFromObject.Append(*Transform::Scale({2, 2, 2}));
    instance->parentFromObject.Append(Transform::Translate({0, 3, 0}));
    auto world = std::make_shared<ListAggregate>();
    world->AddChild(instance);
    auto worldNode = Object::MakeAggregate(world);
    worldNode->PrepareFrame(0, 0);
    const Ray ray{{-10, 3, 0}, {1, 0, 0}};
    ExpectCrossings(Walk(*worldNode, ray), {{8, true}, {10.5, false}, {11.5, true}, {14, false}});
    EXPECT_EQ(worldNode->BoundsInParent().lo, (Vec3{-2, 1, -2}));
    EXPECT_EQ(worldNode->BoundsInParent().hi, (Vec3{4, 5, 2}));

    // Rotated a quarter turn about z, the solid's axis becomes the y axis.
    auto turned = Object::MakeInstance(d);
    turned->parentFromObject.Append(*Transform::Rotate({0, 0, 1}, 90));
    turned->PrepareFrame(0, 0);
    const std::vector<Crossing> got = Walk(*turned, {{0, -5, 0}, {0, 1, 0}});
    ExpectCrossings(got, {{4, true}, {5.25, false}, {5.75, true}, {7, false}});
}

TEST(Csg, ResumedNestedWalkMatchesAFreshSearch) {
    // An operand reaching, through a scaling instance, a CSG node with a CSG operand of its
    // own is walked incrementally; behind a list the same operand is searched afresh for
    // each hit. Both must give exactly the same crossings.
    auto u = Csg(Op::Union, {Sphere({0, 0, 0}, 1), Sphere({1, 0, 0}, 1)});
    auto d = Csg(Op::Difference, {u, Sphere({0.5, 0, 0}, 0.25)});
    auto scaled = Object::MakeInstance(d);
    scaled->parentFromObject.Append(*Transform::Scale({2, 2, 2}));
    auto list = std::make_shared<ListAggregate>();
    list->AddChild(scaled);
    auto listed = Object::MakeAggregate(list);
    // Along x the instance covers [−2, 0.5] ∪ [1.5, 4]; the hole removes [1, 2], so the
    // instance's crossing at x = 1.5 is rejected and its walk resumed past it.
    auto hole = Sphere({1.5, 0, 0}, 0.5);
    auto resumed = Csg(Op::Difference, {scaled, hole});
    auto fresh = Csg(Op::Difference, {listed, hole});
    const Ray rays[] = {{{-10, 0, 0}, {1, 0, 0}},
                        {{10, 0, 0}, {-1, 0, 0}},
                        {{1.25, 0, 0}, {-1, 0, 0}},  // from inside the hole
                        {{-10, 0.3, 0.2}, {1, 0, 0}}};
    ExpectCrossings(Walk(*resumed, rays[0]), {{8, true}, {10.5, false}, {12, true}, {14, false}});
    for (const Ray& ray : rays) {
        const std::vector<Crossing> a = Walk(*resumed, ray), b = Walk(*fresh, ray);
        ASSERT_EQ(a.size(), b.size());
        for (size_t i = 0; i < a.size(); ++i) {
            EXPECT_EQ(a[i].t, b[i].t) << "crossing " << i;
            EXPECT_EQ(a[i].enters, b[i].enters) << "crossing " << i;
        }
    }
}

TEST(Csg, APrimitiveHitInFrontClearsTheOverride) {
    auto u = Csg(Op::Union, {Sphere({0, 0, 0}, 1), Sphere({1, 0, 0}, 1)});
    auto front = Sphere({-3, 0, 0}, 0.5);
    auto list = std::make_shared<ListAggregate>();
    list->AddChild(u);
    list->AddChild(front);
    auto node = Object::MakeAggregate(list);
    node->PrepareFrame(0, 0);
    HitRecord hit;
    double tMax = kFar;
    ASSERT_TRUE(node->Intersect({{-5, 0, 0}, {1, 0, 0}}, kEpsilon, tMax, hit));
    EXPECT_DOUBLE_EQ(hit.t(), 1.5);
    EXPECT_EQ(hit.enterOverride, -1);
}

TEST(HitEnters, FollowsThePathThroughTransforms) {
    // A unit sphere instanced scaled by 3: from x = −10 the ray enters at t = 7; from the
    // centre it leaves at t = 3.
    auto s = Sphere({0, 0, 0}, 1);
    auto instance = Object::MakeInstance(s);
    instance->parentFromObject.Append(*Transform::Scale({3, 3, 3}));
    instance->PrepareFrame(0, 0);
    HitRecord hit;
    double tMax = kFar;
    const Ray outside{{-10, 0, 0}, {1, 0, 0}};
    ASSERT_TRUE(instance->Intersect(outside, kEpsilon, tMax, hit));
    EXPECT_DOUBLE_EQ(hit.t(), 7);
    EXPECT_TRUE(HitEnters(outside, hit));
    hit.enterOverride = 0;
    EXPECT_FALSE(HitEnters(outside, hit));

    HitRecord inner;
    tMax = kFar;
    const Ray inside{{0, 0, 0}, {1, 0, 0}};
    ASSERT_TRUE(instance->Intersect(inside, kEpsilon, tMax, inner));
    EXPECT_DOUBLE_EQ(inner.t(), 3);
    EXPECT_FALSE(HitEnters(inside, inner));
}

}  // namespace
}  // namespace rs
