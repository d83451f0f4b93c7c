#include "libobj/implicit/field.h"

#include <gtest/gtest.h>

#include <cmath>

#include "libcommon/error.h"
#include "test_util.h"

namespace rs {
namespace {

using testing::Uniform;

// A random valid kernel: Gascuel (m = k(R − e) <= 3) or blob.
Kernel RandomKernel(Rng& rng) {
    double e = Uniform(rng, 0.1, 0.6), big = e + Uniform(rng, 0.1, 1.0);
    double k = Uniform(rng, 0.05, 3.0 / (big - e));
    switch (static_cast<int>(rng.Uniform() * 3)) {
        case 0:
            return Kernel::GascuelLinear(e, k, big);
        case 1:
            return Kernel::GascuelQuadratic(e, k, big);
        default:
            return Kernel::Blob(Uniform(rng, 0.5, 2), big);
    }
}

Field RandomField(Rng& rng, bool convexOnly) {
    std::vector<FieldTerm> terms;
    int n = 1 + static_cast<int>(rng.Uniform() * 4);
    for (int i = 0; i < n; ++i) {
        int kind = static_cast<int>(rng.Uniform() * testing::kSkeletonKinds);
        if (convexOnly && (kind == 2 || kind == 3)) kind = 1;
        FieldTerm t;
        t.name = StringPrintf("t%d", i);
        t.skeleton = testing::RandomSkeleton(rng, kind);
        t.kernel = RandomKernel(rng);
        t.weight = rng.Uniform() < 0.25 ? -Uniform(rng, 0.2, 1) : Uniform(rng, 0.5, 2);
        terms.push_back(t);
    }
    return Field(std::move(terms));
}

TEST(Field, SinglePointFieldIsTheKernel) {
    Kernel k = Kernel::GascuelQuadratic(0.5, 2, 1.2);
    Field f({{"p", PointSkeleton{{1, 1, 1}}, k, 2}});
    EXPECT_DOUBLE_EQ(f.Value({1, 1, 1.3}), 2 * k.Value(0.3));
    // Gradient of 2 f(r) at (1,1,1.3): 2 f'(0.3) along +z.
    Vec3 g = f.Gradient({1, 1, 1.3});
    EXPECT_NEAR(g.z, 2 * k.Derivative(0.3), 1e-12);
    EXPECT_NEAR(g.x, 0, 1e-12);
}

TEST(Field, GradientMatchesCentralDifferences) {
    for (uint64_t seed = 1; seed <= 300; ++seed) {
        Rng rng(seed);
        Field f = RandomField(rng, true);
        for (int i = 0; i < 30; ++i) {
            Vec3 p = testing::RandomPoint(rng, -2, 2);
            double h = 1e-6;
            Vec3 fd{(f.Value(p + Vec3{h, 0, 0}) - f.Value(p - Vec3{h, 0, 0})) / (2 * h),
                    (f.Value(p + Vec3{0, h, 0}) - f.Value(p - Vec3{0, h, 0})) / (2 * h),
                    (f.Value(p + Vec3{0, 0, h}) - f.Value(p - Vec3{0, 0, h})) / (2 * h)};
            // Skip points within a few h of a skeleton (the linear kernel's cone point).
            bool nearSkeleton = false;
            for (const FieldTerm& t : f.Terms()) {
                nearSkeleton |= SkeletonDistance(t.skeleton, p) < 1e-4;
            }
            if (nearSkeleton) continue;
            Vec3 g = f.Gradient(p);
            ASSERT_NEAR(g.x, fd.x, 1e-5) << "seed " << seed;
            ASSERT_NEAR(g.y, fd.y, 1e-5) << "seed " << seed;
            ASSERT_NEAR(g.z, fd.z, 1e-5) << "seed " << seed;
        }
    }
}

TEST(Field, CircleGradientMatchesCentralDifferencesOffAxis) {
    Field f({{"c", CircleSkeleton{{0, 0, 0}, {0, 0, 1}, 1}, Kernel::Blob(1, 1), 1}});
    for (Vec3 p : {Vec3{1.3, 0.2, 0.1}, Vec3{0.5, 0.4, -0.3}, Vec3{-0.8, 0.9, 0.2}}) {
        double h = 1e-6;
        Vec3 fd{(f.Value(p + Vec3{h, 0, 0}) - f.Value(p - Vec3{h, 0, 0})) / (2 * h),
                (f.Value(p + Vec3{0, h, 0}) - f.Value(p - Vec3{0, h, 0})) / (2 * h),
                (f.Value(p + Vec3{0, 0, h}) - f.Value(p - Vec3{0, 0, h})) / (2 * h)};
        Vec3 g = f.Gradient(p);
        EXPECT_NEAR(g.x, fd.x, 1e-6);
        EXPECT_NEAR(g.y, fd.y, 1e-6);
        EXPECT_NEAR(g.z, fd.z, 1e-6);
    }
}

// Every bound of Bound(box) holds at dense random samples of random boxes, for random
// fields of every skeleton kind, kernel and weight sign. Second directional derivatives by
// central second differences with h = 1e-3 (which average F'' over [−h, h], so they obey
// the same bound); stated slack: 1e-6 absolute plus 1e-6 relative for round-off
// (≈ 4ε|F|/h² ≈ 1e-9).
TEST(Field, BoundHoldsOnDenseSamples) {
    int secondChecks = 0;
    for (uint64_t seed = 1; seed <= 600; ++seed) {
        Rng rng(seed);
        Field f = RandomField(rng, false);
        Bounds3 box = testing::RandomBox(rng, -2, 1.5, seed % 3 == 0 ? 2.0 : 0.4);
        FieldBound fb = f.Bound(box);
        double h = 1e-3;
        for (int i = 0; i < 300; ++i) {
            Vec3 p = i < 8 ? box.Corner(i) : testing::RandomInBox(rng, box);
            double v = f.Value(p);
            ASSERT_GE(v, fb.valueMin - 1e-12) << "seed " << seed;
            ASSERT_LE(v, fb.valueMax + 1e-12) << "seed " << seed;
            ASSERT_LE(Length(f.Gradient(p)), fb.L * (1 + 1e-12) + 1e-12) << "seed " << seed;
            if (!std::isfinite(fb.G)) continue;
            Vec3 u = testing::RandomUnit(rng);
            Vec3 a = p - u * h, b = p + u * h;
            if (!box.Contains(a) || !box.Contains(b)) continue;
            double second = (f.Value(a) - 2 * v + f.Value(b)) / (h * h);
            ASSERT_LE(std::abs(second), fb.G * (1 + 1e-6) + 1e-6)
                << "seed " << seed << " at sample " << i;
            ++secondChecks;
        }
    }
    EXPECT_GT(secondChecks, 50000);  // most boxes have a finite G
}

// A Subset sums its rows of the shared table in the given order: bit-identical to a field
// made from copies of those terms, for values, gradients, bounds and term ranges.
TEST(Field, SubsetEqualsAFieldOfCopiedTerms) {
    for (uint64_t seed = 1; seed <= 200; ++seed) {
        Rng rng(seed);
        Field all = RandomField(rng, false);
        std::vector<int> rows;
        for (int i = all.Size() - 1; i >= 0; --i) {
            if (rng.Uniform() < 0.7) rows.push_back(i);  // descending: not the table's order
        }
        std::vector<FieldTerm> copies;
        for (int i : rows) copies.push_back(all.Terms()[i]);
        const Field subset = all.Subset(rows), copied(std::move(copies));
        ASSERT_EQ(subset.Rows(), rows);
        Bounds3 box = testing::RandomBox(rng, -2, 1.5, 1.0);
        FieldBound a = subset.Bound(box), b = copied.Bound(box);
        EXPECT_EQ(a.valueMin, b.valueMin);
        EXPECT_EQ(a.valueMax, b.valueMax);
        EXPECT_EQ(a.L, b.L);
        EXPECT_EQ(a.G, b.G);
        EXPECT_EQ(subset.SupportBounds().lo, copied.SupportBounds().lo);
        EXPECT_EQ(subset.SupportBounds().hi, copied.SupportBounds().hi);
        for (int i = 0; i < 50; ++i) {
            Vec3 p = testing::RandomInBox(rng, box);
            EXPECT_EQ(subset.Value(p), copied.Value(p)) << "seed " << seed;
            Vec3 ga = subset.Gradient(p), gb = copied.Gradient(p);
            EXPECT_EQ(ga.x, gb.x);
            EXPECT_EQ(ga.y, gb.y);
            EXPECT_EQ(ga.z, gb.z);
        }
        for (size_t k = 0; k < rows.size(); ++k) {
            double lo1, hi1, lo2, hi2;
            subset.TermRange(rows[k], box, lo1, hi1);
            copied.TermRange(static_cast<int>(k), box, lo2, hi2);
            EXPECT_EQ(lo1, lo2);
            EXPECT_EQ(hi1, hi2);
        }
    }
}

// A TermsMeeting list made for a box serves every box and point inside it: bounds, term
// ranges, active lists and sums from it equal the full ones bit for bit (the octree build
// hands each cell's list to its children).
TEST(Field, TermsMeetingListServesSubBoxes) {
    for (uint64_t seed = 1; seed <= 300; ++seed) {
        Rng rng(seed);
        Field f = RandomField(rng, false);
        Bounds3 outer = testing::RandomBox(rng, -2, 1.5, seed % 2 ? 2.0 : 0.5);
        std::vector<int32_t> meeting;
        f.TermsMeeting(outer, f.Rows(), meeting);
        for (int b = 0; b < 10; ++b) {
            Bounds3 inner(testing::RandomInBox(rng, outer), testing::RandomInBox(rng, outer));
            std::vector<TermValueRange> ranges;
            FieldBound full = f.Bound(inner), listed = f.Bound(inner, meeting, &ranges);
            EXPECT_EQ(full.valueMin, listed.valueMin) << "seed " << seed;
            EXPECT_EQ(full.valueMax, listed.valueMax);
            EXPECT_EQ(full.L, listed.L);
            EXPECT_EQ(full.G, listed.G);
            EXPECT_EQ(full.minDistance, listed.minDistance);
            EXPECT_EQ(full.activeTerms, listed.activeTerms);
            ASSERT_EQ(ranges.size(), meeting.size());
            for (size_t k = 0; k < meeting.size(); ++k) {
                double lo, hi;
                f.TermRange(meeting[k], inner, lo, hi);
                EXPECT_EQ(ranges[k].lo, lo);
                EXPECT_EQ(ranges[k].hi, hi);
            }
            std::vector<int32_t> activeFull, activeListed;
            f.ActiveTerms(inner, f.Rows(), activeFull);
            f.ActiveTerms(inner, meeting, activeListed);
            EXPECT_EQ(activeFull, activeListed);
            for (int i = 0; i < 20; ++i) {
                Vec3 p = i < 8 ? inner.Corner(i) : testing::RandomInBox(rng, inner);
                EXPECT_EQ(f.Value(p), f.Value(p, meeting)) << "seed " << seed;
                Vec3 ga = f.Gradient(p), gb = f.Gradient(p, meeting);
                EXPECT_EQ(ga.x, gb.x);
                EXPECT_EQ(ga.y, gb.y);
                EXPECT_EQ(ga.z, gb.z);
            }
        }
    }
}

TEST(Field, TermsOutsideTheBoxContributeNothing) {
    Field f({{"a", PointSkeleton{{0, 0, 0}}, Kernel::Blob(1, 1), 1},
             {"b", PointSkeleton{{10, 0, 0}}, Kernel::Blob(1, 1), 1}});
    FieldBound fb = f.Bound(Bounds3({-0.1, -0.1, -0.1}, {0.1, 0.1, 0.1}));
    EXPECT_EQ(fb.activeTerms, 1);
    EXPECT_NEAR(fb.valueMax, 1, 1e-15);
    EXPECT_TRUE(f.SupportBounds().Contains({11, 0, 0}));
}

}  // namespace
}  // namespace rs
