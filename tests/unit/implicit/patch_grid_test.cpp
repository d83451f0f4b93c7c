// PatchGrid (patch_grid.h): the grid walk finds the nearest hit a brute-force pass over
// every item finds, and PatchesMethod walking a grid answers as with its hierarchy.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <vector>

#include "libobj/implicit/object_stats.h"
#include "libobj/implicit/patches_method.h"
#include "test_util.h"

namespace rs {
namespace {

using testing::RandomPoint;
using testing::RandomUnit;
using testing::Uniform;

struct Sphere {
    Vec3 centre;
    double radius;
};

// The first parameter in (tMin, tMax) where the ray enters or leaves the sphere.
std::optional<double> SphereHit(const Sphere& s, const Ray& ray, double tMin, double tMax) {
    const Vec3 oc = ray.origin - s.centre;
    const double a = LengthSquared(ray.dir), h = Dot(oc, ray.dir);
    const double disc = h * h - a * (LengthSquared(oc) - s.radius * s.radius);
    if (disc < 0) return std::nullopt;
    for (double t : {(-h - std::sqrt(disc)) / a, (-h + std::sqrt(disc)) / a}) {
        if (t > tMin && t < tMax) return t;
    }
    return std::nullopt;
}

// Spheres as items (boxed by their bounds, some boxes padded, sizes spread over 30×, a
// dense cluster and sparse outliers), rays from outside and from inside, some parallel to
// an axis: the walk's nearest hit is the brute-force nearest, bit for bit (the same
// computation on the same item), and no item is visited twice while the walk has met at
// most kVisitedItems distinct items.
TEST(PatchGrid, NearestHitEqualsBruteForce) {
    for (uint64_t seed = 1; seed <= 20; ++seed) {
        Rng rng(seed);
        const int count = 50 + static_cast<int>(seed) * 40;
        std::vector<Sphere> spheres;
        std::vector<Bounds3> boxes;
        for (int i = 0; i < count; ++i) {
            const bool outlier = i % 17 == 0;
            const Vec3 c = RandomPoint(rng, outlier ? -40 : -5, outlier ? 40 : 5);
            const double r = Uniform(rng, 0.1, 3);
            spheres.push_back({c, r});
            const double pad = i % 3 == 0 ? Uniform(rng, 0, 1) : 0;
            boxes.push_back(Bounds3(c - Vec3{r, r, r}, c + Vec3{r, r, r}).Padded(pad));
        }
        const PatchGrid grid(boxes);
        for (int k = 0; k < 300; ++k) {
            const Vec3 o = k % 4 == 0 ? RandomPoint(rng, -5, 5) : RandomUnit(rng) * 60;
            Vec3 d = k % 4 == 0 ? RandomUnit(rng) : Normalize(RandomPoint(rng, -6, 6) - o);
            if (k % 10 == 1) d = Vec3{0, 0, k % 20 == 1 ? 1.0 : -1.0};
            const Ray ray{o, d * Uniform(rng, 0.5, 2)};
            const double tMin = 1e-6, tMax = k % 5 == 0 ? Uniform(rng, 1, 40) : 1e30;
            std::optional<double> expected;
            for (const Sphere& s : spheres) {
                if (auto t = SphereHit(s, ray, tMin, expected.value_or(tMax))) expected = t;
            }
            double best = tMax;
            std::vector<int> visits(spheres.size(), 0);
            int distinct = 0;
            const bool found = grid.TraverseInEntryOrder(ray, tMin, best, [&](int item) {
                if (visits[item]++ == 0) {
                    ++distinct;
                } else {
                    EXPECT_GT(distinct, PatchGrid::kVisitedItems)
                        << "item " << item << " visited again, seed " << seed;
                }
                const std::optional<double> t = SphereHit(spheres[item], ray, tMin, best);
                if (!t) return false;
                best = *t;
                return true;
            });
            ASSERT_EQ(found, expected.has_value()) << "seed " << seed << " ray " << k;
            if (expected) {
                EXPECT_EQ(best, *expected) << "seed " << seed << " ray " << k;
            }
        }
    }
}

// A small fluid of Gascuel points, the grid forced on (threshold 0) against the hierarchy:
// the same hits at the same depths up to the tolerance (the visit order may pick another
// tolerance-sized root of the same sign change), on rays from outside and from inside.
TEST(PatchGrid, PatchesMethodAgreesWithHierarchy) {
    constexpr double kDepthTolerance = 1e-6;  // 10 × the default root tolerance, 1e-7
    for (uint64_t seed = 1; seed <= 4; ++seed) {
        Rng rng(seed);
        std::vector<FieldTerm> terms;
        Vec3 p{0, 0, 0};
        for (int i = 0; i < 80; ++i) {
            terms.push_back({"p", PointSkeleton{p}, Kernel::GascuelLinear(0.45, 2, 1), 1});
            p = p + RandomUnit(rng) * 0.6;
        }
        const Field field(terms);
        const ImplicitOptions options;
        const ImplicitObjectStats stats;
        const PatchesMethod bvh(field, options, stats);
        const PatchesMethod grid(field, options, stats, 0);
        ASSERT_FALSE(bvh.WalksGrid());
        ASSERT_TRUE(grid.WalksGrid());
        const Bounds3 box = bvh.Bounds(field);
        int hits = 0;
        for (int k = 0; k < 400; ++k) {
            const Vec3 o = k % 5 == 0 ? testing::RandomInBox(rng, box)
                                      : box.Center() + RandomUnit(rng) * 30;
            const Vec3 d = Normalize(testing::RandomInBox(rng, box) - o);
            const Ray ray{o, d};
            const std::optional<MethodHit> a = bvh.Intersect(ray, 1e-6, 1e30);
            const std::optional<MethodHit> b = grid.Intersect(ray, 1e-6, 1e30);
            ASSERT_EQ(a.has_value(), b.has_value()) << "seed " << seed << " ray " << k;
            if (!a) continue;
            ++hits;
            EXPECT_NEAR(a->t, b->t, kDepthTolerance) << "seed " << seed << " ray " << k;
        }
        EXPECT_GT(hits, 100) << "seed " << seed;  // the rays do reach the fluid
    }
}

}  // namespace
}  // namespace rs
