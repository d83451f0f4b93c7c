// The reach of moving skeletons (implicit_motion.h) against sampled Hausdorff distances:
// points of each skeleton at many times of the shutter lie within the reach of the
// reference skeleton (middle time) and the reference's points within the reach of the
// moved skeleton, for every kind, including rotating circle normals and cylinder axes
// (numbers given as TIME, the token reader's time-varying number, so t itself).
#include "libobj/implicit/implicit_motion.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "libobj/implicit/implicit_block.h"
#include "test_util.h"
#include "token_reader.h"

namespace rs {
namespace {

// A unit vector orthogonal to n, and n × it.
void Frame(const Vec3& n, Vec3& u, Vec3& v) {
    u = Normalize(std::abs(n.x) < 0.9 ? Cross(n, Vec3{1, 0, 0}) : Cross(n, Vec3{0, 1, 0}));
    v = Cross(n, u);
}

// A random point of the skeleton's point set.
Vec3 SamplePoint(const Skeleton& skeleton, Rng& rng) {
    const double a = rng.Uniform(), b = rng.Uniform(), angle = 2 * M_PI * rng.Uniform();
    if (const auto* p = std::get_if<PointSkeleton>(&skeleton)) return p->center;
    if (const auto* s = std::get_if<SegmentSkeleton>(&skeleton)) return s->a + (s->b - s->a) * a;
    if (const auto* c = std::get_if<CircleSkeleton>(&skeleton)) {
        Vec3 u, v;
        Frame(c->normal, u, v);
        return c->center + (u * std::cos(angle) + v * std::sin(angle)) * c->radius;
    }
    if (const auto* t = std::get_if<TriangleSkeleton>(&skeleton)) {
        const double s = std::sqrt(a);
        return t->a * (1 - s) + t->b * (s * (1 - b)) + t->c * (s * b);
    }
    if (const auto* x = std::get_if<BoxSkeleton>(&skeleton)) {
        const Vec3 e = x->hi - x->lo;
        return x->lo + Vec3{e.x * a, e.y * b, e.z * rng.Uniform()};
    }
    if (const auto* l = std::get_if<PolylineSkeleton>(&skeleton)) {
        const size_t i = static_cast<size_t>(a * (l->points.size() - 1));
        return l->points[i] + (l->points[i + 1] - l->points[i]) * b;
    }
    const auto& y = std::get<CylinderSkeleton>(skeleton);
    Vec3 u, v;
    Frame(Normalize(y.b - y.a), u, v);
    return y.a + (y.b - y.a) * a + (u * std::cos(angle) + v * std::sin(angle)) * (y.radius * b);
}

TEST(ImplicitMotion, ReachBoundsTheSampledHausdorffDistance) {
    const std::string block =
        "point p TIME 0 0 "
        "segment s 0 0 0 1 TIME 0 "
        "polyline l 3 0 0 0 TIME 1 0 2 0 TIME "
        "circle c 1 0 TIME 0 0 TIME 1 "
        "triangle t 0 0 0 1 0 TIME 0 1 0 "
        "box b 0 0 0 1 TIME 1 "
        "cylinder y 0.5 0 0 0 TIME 0 2 weight TIME end";
    TokenReader reader(block);
    BuiltImplicitBlock built = BuildImplicitBlock(ReadImplicitBlock(reader), reader);
    ASSERT_TRUE(built.description);
    const double t0 = 0.2, t1 = 1.4, tm = 0.5 * (t0 + t1);
    MovingTerms moving = BuildMovingTerms(built.description, built.termsAt(tm), t0, t1);
    ASSERT_EQ(moving.error, "");
    Rng rng(2024);
    for (size_t i = 0; i < moving.reference.size(); ++i) {
        const TermMotion& m = moving.motion->Of(static_cast<int>(i));
        ASSERT_TRUE(m.moving);
        const Skeleton& reference = moving.reference[i].skeleton;
        double measured = 0;
        for (int k = 0; k <= 200; ++k) {
            const double t = t0 + (t1 - t0) * k / 200.0;
            const Skeleton moved = built.termsAt(t)[i].skeleton;
            for (int s = 0; s < 50; ++s) {
                measured = std::max(measured, SkeletonDistance(reference, SamplePoint(moved, rng)));
                measured = std::max(measured, SkeletonDistance(moved, SamplePoint(reference, rng)));
            }
        }
        EXPECT_LE(measured, m.reach) << moving.reference[i].name;
        EXPECT_GT(measured, 0.25 * m.reach) << moving.reference[i].name << ": loose bound";
    }
    // The cylinder's weight is TIME: its interval is the shutter's.
    const TermMotion& y = moving.motion->Of(6);
    EXPECT_LE(y.weightLo, t0);
    EXPECT_GE(y.weightHi, t1);
    EXPECT_NEAR(y.weightLo, t0, 1e-12);
    EXPECT_NEAR(y.weightHi, t1, 1e-12);
}

TEST(ImplicitMotion, RefusesWhatCannotBeBounded) {
    struct Case {
        const char* block;
        const char* message;
    } cases[] = {
        // (The token reader's only time-varying number is t itself, so kernels and circle
        // radii, invalid at 0 where the block is first built, are not tried here.)
        {"point p 0 0 0 weight TIME end", "weight changes sign"},
        {"cylinder y TIME 0 0 0 0 0 1 end", "radius may be negative"},
    };
    for (const Case& c : cases) {
        TokenReader reader(c.block);
        BuiltImplicitBlock built = BuildImplicitBlock(ReadImplicitBlock(reader), reader);
        ASSERT_TRUE(built.description) << c.block;
        MovingTerms moving = BuildMovingTerms(built.description, built.termsAt(0.5), -0.5, 1.5);
        EXPECT_NE(moving.error.find(c.message), std::string::npos) << c.block << ": " << moving.error;
    }
}

}  // namespace
}  // namespace rs
