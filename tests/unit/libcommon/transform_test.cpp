#include "libcommon/transform.h"

#include <gtest/gtest.h>

namespace rs {
namespace {

void ExpectNear(const Vec3& a, const Vec3& b, double tol = 1e-12) {
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
}

TEST(Transform, RotateZNinetyMapsXToY) {
    Transform r = *Transform::Rotate({0, 0, 1}, 90);
    ExpectNear(r.ApplyPoint({1, 0, 0}), {0, 1, 0});
}

TEST(Transform, ListAppliesInWrittenOrder) {
    // translate then scale: (1,0,0) → (2,0,0) → (4,0,0); scale then translate → (3,0,0).
    TransformList a;
    a.Append(Transform::Translate({1, 0, 0}));
    a.Append(*Transform::Scale({2, 2, 2}));
    ExpectNear(a.Static().ApplyPoint({1, 0, 0}), {4, 0, 0});
    TransformList b;
    b.Append(*Transform::Scale({2, 2, 2}));
    b.Append(Transform::Translate({1, 0, 0}));
    ExpectNear(b.Static().ApplyPoint({1, 0, 0}), {3, 0, 0});
}

TEST(Transform, GeneralRowsAreAxisImages) {
    Transform t = *Transform::General({0, 1, 0}, {-1, 0, 0}, {0, 0, 1}, {5, 0, 0});
    ExpectNear(t.ApplyPoint({1, 0, 0}), {5, 1, 0});
    ExpectNear(t.ApplyPoint({0, 1, 0}), {4, 0, 0});
}

TEST(Transform, InverseUndoesForward) {
    Transform t = Transform::Translate({1, 2, 3})
                      .Then(*Transform::Rotate({1, 1, 0}, 33))
                      .Then(*Transform::Scale({2, 0.5, 3}));
    Vec3 p{0.3, -0.7, 2.5};
    ExpectNear(t.InversePoint(t.ApplyPoint(p)), p, 1e-12);
}

TEST(Transform, NormalStaysPerpendicularUnderNonUniformScale) {
    Transform t = *Transform::Scale({4, 1, 1});
    Vec3 tangent{1, -1, 0}, normal{1, 1, 0};  // perpendicular in object space
    EXPECT_NEAR(Dot(t.ApplyVector(tangent), t.ApplyNormal(normal)), 0, 1e-12);
}

TEST(Transform, SingularScaleIsRejected) {
    EXPECT_FALSE(Transform::Scale({1, 0, 1}).has_value());
    EXPECT_FALSE(Transform::Rotate({0, 0, 0}, 10).has_value());
}

TEST(Transform, RayDistancesArePreservedAcrossSpaces) {
    Transform t = *Transform::Scale({3, 3, 3});
    Ray world{{0, 0, -10}, {0, 0, 1}, 0};
    Ray local = t.InverseRay(world);
    // The world point at t = 7 maps to the local point at the same t.
    ExpectNear(t.InversePoint(world.At(7)), local.At(7));
}

TEST(TransformList, AnimatedStepEvaluatesAtTime) {
    TransformList l;
    l.Append(*Transform::Scale({2, 2, 2}));
    l.AppendAnimated([](double time) { return std::optional<Transform>(Transform::Translate({time, 0, 0})); });
    EXPECT_TRUE(l.IsAnimated());
    ExpectNear(l.At(3).ApplyPoint({1, 0, 0}), {5, 0, 0});
}

TEST(TransformList, PreparedTimeIsEvaluatedOnceAndOtherTimesAsBefore) {
    int evaluations = 0;
    TransformList l;
    l.Append(*Transform::Scale({2, 2, 2}));
    l.AppendAnimated([&](double time) {
        ++evaluations;
        return std::optional<Transform>(Transform::Translate({time, 0, 0}));
    });
    l.PrepareAt(3);
    EXPECT_EQ(evaluations, 1);
    for (int i = 0; i < 5; ++i) ExpectNear(l.At(3).ApplyPoint({1, 0, 0}), {5, 0, 0});
    EXPECT_EQ(evaluations, 1);  // the prepared time costs no evaluation
    ExpectNear(l.At(4).ApplyPoint({1, 0, 0}), {6, 0, 0});
    EXPECT_EQ(evaluations, 2);
    // Appending a step drops the prepared transform.
    l.Append(Transform::Translate({0, 1, 0}));
    ExpectNear(l.At(3).ApplyPoint({1, 0, 0}), {5, 1, 0});
    EXPECT_EQ(evaluations, 3);
}

TEST(TransformList, EmptyListIsTheIdentityUntilANonIdentityStep) {
    TransformList l;
    EXPECT_TRUE(l.IsIdentity());
    EXPECT_FALSE(l.IsAnimated());
    l.Append(Transform{});  // identity steps are dropped
    EXPECT_TRUE(l.IsIdentity());
    ExpectNear(l.Static().ApplyPoint({1, 2, 3}), {1, 2, 3});
    ExpectNear(l.At(5).ApplyPoint({1, 2, 3}), {1, 2, 3});
    l.Append(Transform::Translate({1, 0, 0}));
    EXPECT_FALSE(l.IsIdentity());
}

TEST(TransformList, CopiesAreIndependent) {
    TransformList a;
    a.Append(Transform::Translate({1, 0, 0}));
    TransformList b = a;
    b.Append(*Transform::Scale({2, 2, 2}));
    ExpectNear(a.Static().ApplyPoint({0, 0, 0}), {1, 0, 0});
    ExpectNear(b.Static().ApplyPoint({0, 0, 0}), {2, 0, 0});
    TransformList c;
    c = b;
    b = TransformList{};
    EXPECT_TRUE(b.IsIdentity());
    ExpectNear(c.Static().ApplyPoint({0, 0, 0}), {2, 0, 0});
}

TEST(TransformList, AppendingAListToItselfAppliesItTwice) {
    TransformList l;
    l.Append(Transform::Translate({1, 0, 0}));
    l.AppendAnimated([](double time) { return std::optional<Transform>(Transform::Translate({0, time, 0})); });
    l.Append(l);
    ExpectNear(l.At(3).ApplyPoint({0, 0, 0}), {2, 6, 0});
}

TEST(Bounds, ClipRayHandlesAxisParallelDirections) {
    Bounds3 b({-1, -1, -1}, {1, 1, 1});
    Ray r{{0, 0, -5}, {0, 0, 2}, 0};
    double t0 = 0, t1 = 100;
    ASSERT_TRUE(b.ClipRay(r, t0, t1));
    EXPECT_DOUBLE_EQ(t0, 2);
    EXPECT_DOUBLE_EQ(t1, 3);
    Ray miss{{2, 0, -5}, {0, 0, 1}, 0};
    t0 = 0;
    t1 = 100;
    EXPECT_FALSE(b.ClipRay(miss, t0, t1));
}

}  // namespace
}  // namespace rs
