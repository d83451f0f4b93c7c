#include "libobj/torus.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "libcommon/constants.h"
#include "test_arg_reader.h"

namespace rs {
namespace {

using testing::ExpectVecNear;
using testing::HitT;
using testing::MustHit;
using testing::TestArgReader;

// R = 2, r = 0.5 about the z axis through the origin: crossing the x axis at ±1.5, ±2.5.
const Torus kTorus(2, 0.5, {0, 0, 0}, {0, 0, 1});

// The implicit function of the canonical torus (negative inside the tube).
double TorusF(const Vec3& q, double R, double r) {
    const double k = Dot(q, q) - R * R - r * r;
    return k * k + 4 * R * R * (q.z * q.z - r * r);
}

TEST(Torus, HitFromOutsideWithNonUnitDirection) {
    Ray ray{{-5, 0, 0}, {4, 0, 0}};
    PrimitiveHit hit = MustHit(kTorus, ray);
    EXPECT_NEAR(hit.t, 2.5 / 4, 1e-12);
    SurfaceNormals n = kTorus.Normal(ray.At(hit.t), hit);
    ExpectVecNear(n.geometric, {-1, 0, 0});
    EXPECT_TRUE(kTorus.Enters(ray, hit, n));
}

TEST(Torus, HitFromInsideTheTube) {
    Ray ray{{-2, 0, 0}, {1, 0, 0}};
    PrimitiveHit hit = MustHit(kTorus, ray);
    EXPECT_NEAR(hit.t, 0.5, 1e-12);
    SurfaceNormals n = kTorus.Normal(ray.At(hit.t), hit);
    ExpectVecNear(n.geometric, {1, 0, 0});
    EXPECT_FALSE(kTorus.Enters(ray, hit, n));
}

TEST(Torus, HitFromTheHoleAndFromAbove) {
    Ray fromCentre{{0, 0, 0}, {0, 1, 0}};
    PrimitiveHit hit = MustHit(kTorus, fromCentre);
    EXPECT_NEAR(hit.t, 1.5, 1e-12);
    ExpectVecNear(kTorus.Normal(fromCentre.At(hit.t), hit).geometric, {0, -1, 0});
    Ray fromAbove{{2, 0, 5}, {0, 0, -1}};
    hit = MustHit(kTorus, fromAbove);
    EXPECT_NEAR(hit.t, 4.5, 1e-12);
    ExpectVecNear(kTorus.Normal(fromAbove.At(hit.t), hit).geometric, {0, 0, 1});
}

TEST(Torus, Misses) {
    EXPECT_LT(HitT(kTorus, {{0, 0, 5}, {0, 0, -1}}), 0);  // through the hole
    EXPECT_LT(HitT(kTorus, {{-5, 0, 1}, {1, 0, 0}}), 0);  // above
    EXPECT_LT(HitT(kTorus, {{-5, 0, 0}, {-1, 0, 0}}), 0);  // away
}

TEST(Torus, RangeClippingVisitsLaterRoots) {
    Ray ray{{-5, 0, 0}, {1, 0, 0}};  // roots at t = 2.5, 3.5, 6.5, 7.5
    EXPECT_NEAR(HitT(kTorus, ray, 3), 3.5, 1e-12);
    EXPECT_NEAR(HitT(kTorus, ray, 3.5), 6.5, 1e-12);
    EXPECT_NEAR(HitT(kTorus, ray, 7), 7.5, 1e-12);
    EXPECT_LT(HitT(kTorus, ray, 7.5), 0);
    EXPECT_LT(HitT(kTorus, ray, 1e-5, 2.5), 0);
}

TEST(Torus, HitRecordsWhetherTheRayEnters) {
    // Along the x axis the ray enters the tube at t = 2.5 and 6.5 and leaves at 3.5 and 7.5.
    const Ray ray{{-5, 0, 0}, {1, 0, 0}};
    const double tMins[] = {1e-5, 3, 5, 7};
    const bool enters[] = {true, false, true, false};
    for (int i = 0; i < 4; ++i) {
        const PrimitiveHit hit = MustHit(kTorus, ray, tMins[i]);
        EXPECT_EQ(kTorus.EntersFromHit(hit), enters[i] ? 1 : 0) << "tMin " << tMins[i];
    }
    // The tangent ray of TangentRayFindsTheDoubleRoot: no trustworthy crossing direction.
    EXPECT_EQ(kTorus.EntersFromHit(MustHit(kTorus, {{-5, 0, 0.5}, {1, 0, 0}})), -1);
    // Wherever the hit decides, it agrees with the normal test, on a tilted torus too.
    const Torus tilted(2, 0.5, {1, 2, 3}, {1, -1, 2});
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> unit(-1, 1);
    int decided = 0;
    for (int i = 0; i < 2000; ++i) {
        const Vec3 origin = Vec3{1, 2, 3} + Vec3{4 * unit(rng), 4 * unit(rng), 4 * unit(rng)};
        const Vec3 target = Vec3{1, 2, 3} + Vec3{2.5 * unit(rng), 2.5 * unit(rng), 2.5 * unit(rng)};
        const Ray r{origin, target - origin};
        PrimitiveHit hit;
        if (!tilted.Intersect(r, 1e-5, 1e14, hit)) continue;
        const int known = tilted.EntersFromHit(hit);
        if (known < 0) continue;
        ++decided;
        EXPECT_EQ(known == 1, tilted.Enters(r, hit, tilted.Normal(r.At(hit.t), hit))) << i;
    }
    EXPECT_GT(decided, 500);
}

TEST(Torus, TangentRayFindsTheDoubleRoot) {
    // The plane z = r touches the torus along the circle ρ = R: a double root at x = −2.
    Ray ray{{-5, 0, 0.5}, {1, 0, 0}};
    PrimitiveHit hit = MustHit(kTorus, ray);
    EXPECT_NEAR(hit.t, 3, 1e-6);
    ExpectVecNear(kTorus.Normal(ray.At(hit.t), hit).geometric, {0, 0, 1}, 1e-6);
    // Just above the tangent plane the ray misses.
    EXPECT_LT(HitT(kTorus, {{-5, 0, 0.5 + 1e-6}, {1, 0, 0}}), 0);
}

TEST(Torus, DistantOriginKeepsPrecision) {
    EXPECT_NEAR(HitT(kTorus, {{-1e4, 0, 0}, {1, 0, 0}}), 1e4 - 2.5, 1e-8);
    EXPECT_NEAR(HitT(kTorus, {{-1e4, 0, 0}, {1e-3, 0, 0}}), (1e4 - 2.5) * 1e3, 1e-5);
}

TEST(Torus, TiltedAxis) {
    // Axis +x through (1, 2, 3): the tube crosses the z line through the centre at ±1.5, ±2.5.
    const Torus t(2, 0.5, {1, 2, 3}, {2, 0, 0});
    Ray ray{{1, 2, -2}, {0, 0, 1}};
    PrimitiveHit hit = MustHit(t, ray);
    EXPECT_NEAR(hit.t, 2.5, 1e-12);
    ExpectVecNear(t.Normal(ray.At(hit.t), hit).geometric, {0, 0, -1});
    ExpectVecNear(t.Bounds().lo, {0.5, -0.5, 0.5});
    ExpectVecNear(t.Bounds().hi, {1.5, 4.5, 5.5});
}

TEST(Torus, RandomRaysAgreeWithMarching) {
    // Seeded rays aimed near the torus; the first root is bracketed independently by
    // marching f along the ray in steps of 1e-3 and bisecting the first sign change.
    for (int seed = 0; seed < 300; ++seed) {
        std::mt19937_64 rng(seed);
        std::uniform_real_distribution<double> unit(-1, 1);
        const Vec3 origin{4 * unit(rng), 4 * unit(rng), 4 * unit(rng)};
        const Vec3 target{2.5 * unit(rng), 2.5 * unit(rng), 0.6 * unit(rng)};
        const Ray ray{origin, (target - origin) * (0.5 + unit(rng) * 0.25 + 0.25)};
        const double len = Length(ray.dir);
        const double step = 1e-3 / len;
        double expected = -1;
        double prev = TorusF(ray.At(1e-5), 2, 0.5);
        for (double t = 1e-5 + step; t < 20 / len; t += step) {
            const double f = TorusF(ray.At(t), 2, 0.5);
            if ((f < 0) != (prev < 0)) {
                double lo = t - step, hi = t;
                for (int i = 0; i < 60; ++i) {
                    const double mid = 0.5 * (lo + hi);
                    if ((TorusF(ray.At(mid), 2, 0.5) < 0) == (prev < 0)) {
                        lo = mid;
                    } else {
                        hi = mid;
                    }
                }
                expected = 0.5 * (lo + hi);
                break;
            }
            prev = f;
        }
        const double actual = HitT(kTorus, ray);
        // Marching can step over a pair of roots closer than a step (near-tangent rays);
        // then the solver finds a root the march missed, which must still be nearer.
        if (expected < 0) {
            if (actual >= 0) {
                EXPECT_NEAR(TorusF(ray.At(actual), 2, 0.5), 0, 1e-6) << "seed " << seed;
            }
            continue;
        }
        ASSERT_GE(actual, 0) << "seed " << seed;
        EXPECT_LE(actual, expected + 1e-9) << "seed " << seed;
        if (expected - actual > 1e-9) {
            EXPECT_NEAR(TorusF(ray.At(actual), 2, 0.5), 0, 1e-6) << "seed " << seed;
        } else {
            EXPECT_NEAR(actual, expected, 1e-9) << "seed " << seed;
        }
    }
}

TEST(Torus, UV) {
    SurfaceUV outer = kTorus.UV({2.5, 0, 0}, {1, 0, 0}, {});
    EXPECT_NEAR(outer.uv.u, 0, 1e-12);
    EXPECT_NEAR(outer.uv.v, 0.5, 1e-12);
    ExpectVecNear(outer.dpdu, {0, 1, 0});
    ExpectVecNear(outer.dpdv, {0, 0, 1});  // facing normal × ∂u, as in the original
    // Seen from inside the tube the facing normal points inward, and so ∂v turns over.
    ExpectVecNear(kTorus.UV({2.5, 0, 0}, {-1, 0, 0}, {}).dpdv, {0, 0, -1});
    EXPECT_NEAR(kTorus.UV({1.5, 0, 0}, {}, {}).uv.v, 0, 1e-12);   // innermost ring
    EXPECT_NEAR(kTorus.UV({2, 0, -0.5}, {}, {}).uv.v, 0.25, 1e-12);
    EXPECT_NEAR(kTorus.UV({2, 0, 0.5}, {}, {}).uv.v, 0.75, 1e-12);
    EXPECT_NEAR(kTorus.UV({0, 2.5, 0}, {}, {}).uv.u, 0.25, 1e-12);
    EXPECT_NEAR(kTorus.UV({0, -2.5, 0}, {}, {}).uv.u, 0.75, 1e-12);
    EXPECT_NEAR(kTorus.UV({-2.5, 0, 0}, {}, {}).uv.u, 0.5, 1e-12);
}

TEST(Torus, BoundsAndClosed) {
    ExpectVecNear(kTorus.Bounds().lo, {-2.5, -2.5, -0.5});
    ExpectVecNear(kTorus.Bounds().hi, {2.5, 2.5, 0.5});
    EXPECT_TRUE(kTorus.IsClosed());
}

TEST(Torus, CreateAndDegenerate) {
    TestArgReader good({2, 0.5, 0, 0, 0, 0, 0, 1});
    auto prim = Torus::Create(good);
    ASSERT_NE(prim, nullptr);
    EXPECT_TRUE(good.AllConsumed());
    EXPECT_NEAR(HitT(*prim, {{-5, 0, 0}, {1, 0, 0}}), 2.5, 1e-12);
    for (std::vector<double> bad : {std::vector<double>{0, 0.5, 0, 0, 0, 0, 0, 1},
                                    std::vector<double>{2, 1e-9, 0, 0, 0, 0, 0, 1},
                                    std::vector<double>{2, 0.5, 0, 0, 0, 0, 0, 0}}) {
        TestArgReader args(bad);
        EXPECT_EQ(Torus::Create(args), nullptr);
        EXPECT_EQ(args.warnings.size(), 1u);
    }
}

}  // namespace
}  // namespace rs
