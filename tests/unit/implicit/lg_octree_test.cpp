#include "libobj/implicit/lg_octree.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <optional>

#include "libcommon/error.h"
#include "libcommon/stats.h"
#include "test_util.h"

namespace rs {
namespace {

using testing::RandomPoint;
using testing::RandomUnit;
using testing::Uniform;

// Eight point terms at random places in [-0.7, 0.7]^3, term i with kernel(i), weight 1.
template <class KernelOf>
std::vector<FieldTerm> RandomPointTerms(Rng& rng, KernelOf kernel) {
    std::vector<FieldTerm> terms;
    for (int i = 0; i < 8; ++i)
        terms.push_back({"p", PointSkeleton{RandomPoint(rng, -0.7, 0.7)}, kernel(i), 1});
    return terms;
}

// First t > tMin where the ray o + t·d meets the sphere (c, rho), or nothing.
std::optional<double> SphereHit(const Ray& ray, const Vec3& c, double rho, double tMin) {
    Vec3 oc = ray.origin - c;
    double a = Dot(ray.dir, ray.dir), b = Dot(oc, ray.dir), cc = Dot(oc, oc) - rho * rho;
    double disc = b * b - a * cc;
    if (disc < 0) return std::nullopt;
    double s = std::sqrt(disc);
    for (double t : {(-b - s) / a, (-b + s) / a}) {
        if (t > tMin) return t;
    }
    return std::nullopt;
}

struct Scene {
    Field field;
    LGOctree tree;
    Scene(std::vector<FieldTerm> terms, double threshold, OctreeSettings s = {})
        : field(std::move(terms)), tree(field, threshold, field.SupportBounds(), s) {}
    std::optional<double> Hit(const Ray& ray, double tMin = 1e-5, double tMax = 1e9) const {
        return tree.FirstRoot(ray, tMin, tMax);
    }
};

std::vector<Kernel> SphereKernels() {
    return {Kernel::GascuelLinear(0.5, 2, 1.2), Kernel::GascuelQuadratic(0.5, 2, 1.2),
            Kernel::GascuelQuadratic(0.7, 0.3, 2.0)};
}

// A lone point skeleton is a sphere of radius exactly e (research note §2.1).
TEST(LGOctree, PointSkeletonIsSphereOfRadiusE) {
    for (const Kernel& k : SphereKernels()) {
        for (bool kb89 : {false, true}) {
            Vec3 c{0.2, -0.1, 0.3};
            Scene scene({{"p", PointSkeleton{c}, k, 1}}, 1.0,
                        kb89 ? OctreeSettings({}, OctreeHeuristics::Kb89()) : OctreeSettings{});
            for (uint64_t seed = 1; seed <= 200; ++seed) {
                Rng rng(seed);
                Vec3 o = c + RandomUnit(rng) * Uniform(rng, 2, 6);
                Vec3 target = c + RandomPoint(rng, -0.6, 0.6);
                Ray ray{o, Normalize(target - o)};
                auto want = SphereHit(ray, c, k.Thickness(), 1e-5);
                auto got = scene.Hit(ray);
                ASSERT_EQ(want.has_value(), got.has_value()) << "seed " << seed;
                if (want) {
                    EXPECT_NEAR(*got, *want, 1e-7) << "seed " << seed;
                }
            }
        }
    }
}

// Blob kernel s(1 − r²/R²)² at threshold T: radius R·sqrt(1 − sqrt(T/s)).
TEST(LGOctree, BlobPointIsSphereOfAnalyticRadius) {
    double s = 1.5, big = 1.2, threshold = 0.5;
    double radius = big * std::sqrt(1 - std::sqrt(threshold / s));
    Scene scene({{"b", PointSkeleton{{0, 0, 0}}, Kernel::Blob(s, big), 1}}, threshold);
    for (uint64_t seed = 1; seed <= 200; ++seed) {
        Rng rng(seed);
        Vec3 o = RandomUnit(rng) * 4;
        Ray ray{o, Normalize(RandomPoint(rng, -0.8, 0.8) - o)};
        auto want = SphereHit(ray, {0, 0, 0}, radius, 1e-5);
        auto got = scene.Hit(ray);
        ASSERT_EQ(want.has_value(), got.has_value()) << "seed " << seed;
        if (want) {
            EXPECT_NEAR(*got, *want, 1e-7) << "seed " << seed;
        }
    }
}

// A segment skeleton is a capsule of radius e.
TEST(LGOctree, SegmentSkeletonIsCapsule) {
    double e = 0.4;
    Scene scene(
        {{"s", SegmentSkeleton{{-1, 0, 0}, {1, 0, 0}}, Kernel::GascuelQuadratic(e, 2, 1), 1}}, 1.0);
    auto side = scene.Hit({{0.3, 0, -5}, {0, 0, 1}});
    ASSERT_TRUE(side.has_value());
    EXPECT_NEAR(*side, 5 - e, 1e-7);
    auto cap = scene.Hit({{-5, 0, 0}, {1, 0, 0}});
    ASSERT_TRUE(cap.has_value());
    EXPECT_NEAR(*cap, 5 - 1 - e, 1e-7);
    auto capOff = scene.Hit({{5, 0.3, 0}, {-1, 0, 0}});  // cap sphere at (1,0,0)
    ASSERT_TRUE(capOff.has_value());
    EXPECT_NEAR(*capOff, 5 - 1 - std::sqrt(e * e - 0.09), 1e-7);
    EXPECT_FALSE(scene.Hit({{0, 0.41, -5}, {0, 0, 1}}).has_value());
}

// Rays passing at distance b = e(1 ∓ δ) from the centre: just inside hit (at the analytic
// near root), just outside miss.
TEST(LGOctree, GrazingRaysJustInsideHitJustOutsideMiss) {
    for (const Kernel& k : SphereKernels()) {
        double e = k.Thickness();
        Scene scene({{"p", PointSkeleton{{0, 0, 0}}, k, 1}}, 1.0);
        for (double delta : {1e-2, 1e-4, 1e-6, 1e-8, 1e-10}) {
            for (Vec3 axis : {Vec3{1, 0, 0}, Normalize(Vec3{1, 1, 0.3})}) {
                Vec3 side = Normalize(Cross(axis, {0, 0, 1}));
                Ray ray{side * (e * (1 - delta)) - axis * 5, axis};
                auto want = SphereHit(ray, {0, 0, 0}, e, 1e-5);
                ASSERT_TRUE(want.has_value());
                auto got = scene.Hit(ray);
                ASSERT_TRUE(got.has_value()) << "delta " << delta;
                EXPECT_NEAR(*got, *want, 1e-7) << "delta " << delta;
                Ray out{side * (e * (1 + delta)) - axis * 5, axis};
                EXPECT_FALSE(scene.Hit(out).has_value()) << "delta " << delta;
            }
        }
    }
}

// A coarse tree whose leaves contain a linear kernel's skeleton (G infinite there): the
// search bounds each segment's own box instead, so grazing rays stay exact and cheap.
TEST(LGOctree, InfiniteCurvatureLeavesStayExactAndCheap) {
    double e = 0.5;
    OctreeSettings s;
    s.maxDepth = 1;
    Scene scene({{"p", PointSkeleton{{0, 0, 0}}, Kernel::GascuelLinear(e, 2, 1.2), 1}}, 1.0, s);
    for (double delta : {1e-3, 1e-6, 1e-9}) {
        ResetStats();
        Ray ray{{e * (1 - delta), -5, 0.0}, {0, 1, 0}};
        auto got = scene.Hit(ray);
        ASSERT_TRUE(got.has_value()) << delta;
        EXPECT_NEAR(*got, 5 - e * std::sqrt(delta * (2 - delta)), 1e-7) << delta;
        EXPECT_LT(CounterTotal("Implicit field evaluations"), 2000u) << delta;
        EXPECT_GT(CounterTotal("Implicit segment bounds"), 0u) << delta;
        EXPECT_FALSE(scene.Hit({{e * (1 + delta), -5, 0.0}, {0, 1, 0}}).has_value()) << delta;
    }
}

TEST(LGOctree, RaysStartingInsideFindTheExit) {
    for (const Kernel& k : SphereKernels()) {
        double e = k.Thickness();
        Scene scene({{"p", PointSkeleton{{0, 0, 0}}, k, 1}}, 1.0);
        for (uint64_t seed = 1; seed <= 100; ++seed) {
            Rng rng(seed);
            Vec3 o = RandomUnit(rng) * Uniform(rng, 0, 0.9 * e);
            Ray ray{o, RandomUnit(rng)};
            auto want = SphereHit(ray, {0, 0, 0}, e, 1e-5);
            auto got = scene.Hit(ray);
            ASSERT_TRUE(got.has_value()) << "seed " << seed;
            EXPECT_NEAR(*got, *want, 1e-7) << "seed " << seed;
        }
    }
}

// Secondary rays near the surface (research note §11): just outside heading in must find
// the far side (the entry lies below tMin); on the surface heading out finds nothing.
TEST(LGOctree, SecondaryRaysNearTheSurface) {
    double e = 0.5;
    Scene scene({{"p", PointSkeleton{{0, 0, 0}}, Kernel::GascuelQuadratic(e, 2, 1.2), 1}}, 1.0);
    for (double gap : {1e-9, 1e-7, -1e-9}) {
        Ray in{{0, 0, -(e + gap)}, {0, 0, 1}};
        auto got = scene.Hit(in, 1e-5);
        ASSERT_TRUE(got.has_value()) << gap;
        EXPECT_NEAR(*got, 2 * e + gap, 1e-7);
        Ray out{{0, 0, -(e + gap)}, {0, 0, -1}};
        EXPECT_FALSE(scene.Hit(out, 1e-5).has_value()) << gap;
    }
}

TEST(LGOctree, NonUnitDirectionsMeasureTInDirectionUnits) {
    Scene scene({{"p", PointSkeleton{{0, 0, 0}}, Kernel::GascuelQuadratic(0.5, 2, 1.2), 1}}, 1.0);
    auto got = scene.Hit({{0, 0, -5}, {0, 0, 4}});
    ASSERT_TRUE(got.has_value());
    EXPECT_NEAR(*got, 4.5 / 4, 1e-7);
}

// Octree cells marked Empty/Full agree with the sign of g at dense random samples.
TEST(LGOctree, CellClassesAgreeWithSampling) {
    for (uint64_t seed = 1; seed <= 20; ++seed) {
        Rng rng(seed);
        std::vector<FieldTerm> terms;
        for (int i = 0; i < 6; ++i) {
            terms.push_back({"p", PointSkeleton{RandomPoint(rng, -1, 1)},
                             Kernel::GascuelQuadratic(0.35, 2.4, 0.9), i == 5 ? -0.5 : 1.0});
        }
        OctreeSettings s;
        s.maxDepth = 5;
        Scene scene(terms, 1.0, s);
        for (int i = 0; i < 5000; ++i) {
            Vec3 p = testing::RandomInBox(rng, scene.tree.Box());
            CellClass c = scene.tree.Classify(p);
            double g = scene.field.Value(p) - 1.0;
            if (c == CellClass::Full) {
                ASSERT_GT(g, 0) << "seed " << seed;
            } else if (c == CellClass::Empty) {
                ASSERT_LT(g, 0) << "seed " << seed;
            }
        }
        EXPECT_GT(scene.tree.LeafCount(), 0);
    }
}

// Every point classified as a leaf lies in LeafBox(), and rays that miss that box find no
// root (patch trees, where the patch rule makes it much smaller than the patch box).
TEST(LGOctree, LeafBoxHoldsEveryLeafCell) {
    Rng rng(7);
    const std::vector<FieldTerm> terms = RandomPointTerms(rng, [](int) { return Kernel::Blob(1, 0.9); });
    int leafPoints = 0, missingRays = 0;
    for (const Patch& patch : BuildPatches(Field(terms), BlendMode::Automatic)) {
        LGOctree tree = BuildPatchOctree(patch, 0.6, OctreeSettings{});
        const Bounds3& leafBox = tree.LeafBox();
        for (int i = 0; i < 20000; ++i) {
            Vec3 p = testing::RandomInBox(rng, tree.Box());
            if (tree.Classify(p) != CellClass::Leaf) continue;
            ++leafPoints;
            ASSERT_TRUE(leafBox.Contains(p));
        }
        for (int i = 0; i < 2000; ++i) {
            Ray ray{RandomPoint(rng, -3, 3), RandomUnit(rng)};
            double t0 = 0, t1 = 1e9;
            if (!leafBox.IsEmpty() && leafBox.ClipRay(ray, t0, t1)) continue;
            ++missingRays;
            double b0 = 0, b1 = 1e9;
            if (!tree.Box().ClipRay(ray, b0, b1)) continue;
            bool anyLeaf = false;
            tree.Traverse(ray, 0, 1e9, [&](const LeafSpan&) { return anyLeaf = true; });
            ASSERT_FALSE(anyLeaf);
        }
    }
    EXPECT_GT(leafPoints, 1000);
    EXPECT_GT(missingRays, 1000);
}

// OwnExcluded(box, terms) holds only where no point of the box predominates (dense samples
// in random small boxes), and it does fire.
TEST(LGOctree, ExcludedBoxesHoldNoPredominantPoint) {
    Rng rng(11);
    const std::vector<FieldTerm> terms = RandomPointTerms(rng, [](int i) {
        return i % 2 ? Kernel::Blob(1, 0.9) : Kernel::GascuelQuadratic(0.35, 2.4, 0.9);
    });
    int excluded = 0;
    for (const Patch& patch : BuildPatches(Field(terms), BlendMode::Automatic)) {
        LGOctree tree = BuildPatchOctree(patch, 0.6, OctreeSettings{});
        for (int i = 0; i < 400; ++i) {
            Vec3 a = testing::RandomInBox(rng, tree.Box());
            Bounds3 box(a, a + RandomPoint(rng, -0.2, 0.2));
            // The box's active terms (what the search passes) answer as all rows do.
            std::vector<int32_t> active;
            tree.GetField().ActiveTerms(box, tree.GetField().Rows(), active);
            const bool all = tree.OwnExcluded(box, tree.GetField().Rows());
            ASSERT_EQ(tree.OwnExcluded(box, active), all);
            if (!all) continue;
            ++excluded;
            for (int k = 0; k < 200; ++k) {
                ASSERT_FALSE(patch.Predominates(testing::RandomInBox(rng, box)));
            }
        }
    }
    EXPECT_GT(excluded, 200);
}

// Patch trees: a cell is Empty only where g < 0 or the own term cannot predominate.
TEST(LGOctree, PatchRuleCellsHoldNoAcceptableRoot) {
    Rng rng(5);
    const std::vector<FieldTerm> terms =
        RandomPointTerms(rng, [](int) { return Kernel::GascuelQuadratic(0.35, 2.4, 0.9); });
    int pruned = 0;
    for (const Patch& patch : BuildPatches(Field(terms), BlendMode::Automatic)) {
        LGOctree tree = BuildPatchOctree(patch, 1.0, OctreeSettings{});
        for (int i = 0; i < 3000; ++i) {
            Vec3 p = testing::RandomInBox(rng, tree.Box());
            CellClass c = tree.Classify(p);
            double g = patch.GetField().Value(p) - 1.0;
            if (c == CellClass::Full) {
                ASSERT_GT(g, 0);
            } else if (c == CellClass::Empty && g >= 0) {
                ASSERT_FALSE(patch.Predominates(p));
                ++pruned;
            }
        }
    }
    EXPECT_GT(pruned, 100);  // the rule does fire inside the surface of other patches
}

TEST(LGOctree, MemoryBudgetDegradesWithWarningAndStaysExact) {
    std::vector<Diagnostic> seen;
    ErrorSink old = SetErrorSink([&seen](const Diagnostic& d) { seen.push_back(d); });
    OctreeSettings s;
    s.memoryBudget = 100;
    s.maxDepth = 8;
    Scene scene({{"p", PointSkeleton{{0, 0, 0}}, Kernel::GascuelQuadratic(0.5, 2, 1.2), 1}}, 1.0,
                s);
    SetErrorSink(old);
    EXPECT_TRUE(scene.tree.Degraded());
    EXPECT_LE(scene.tree.MemoryBytes(), 100u);
    EXPECT_EQ(scene.tree.LeafCount(), 1);
    ASSERT_EQ(seen.size(), 1u);
    EXPECT_EQ(seen[0].severity, Severity::Warn);
    auto got = scene.Hit({{0.1, 0.2, -5}, {0, 0, 1}});
    ASSERT_TRUE(got.has_value());
    EXPECT_NEAR(*got, 5 - std::sqrt(0.25 - 0.05), 1e-7);
}

// UpperFloat returns a float >= x, one float step at most above the nearest float, and
// +infinity beyond the float range.
TEST(LGOctree, UpperFloatIsTheNextFloatUp) {
    Rng rng(11);
    for (int i = 0; i < 100000; ++i) {
        const double x = std::ldexp(rng.Uniform(), static_cast<int>(rng.Uniform() * 300) - 150);
        const float f = UpperFloat(x);
        ASSERT_GE(static_cast<double>(f), x) << x;
        ASSERT_LT(static_cast<double>(std::nextafter(f, 0.0f)), x) << x;
    }
    EXPECT_EQ(UpperFloat(0), 0.0f);
    EXPECT_EQ(UpperFloat(1), 1.0f);
    EXPECT_EQ(UpperFloat(1e300), std::numeric_limits<float>::infinity());
    EXPECT_EQ(UpperFloat(std::numeric_limits<double>::infinity()),
              std::numeric_limits<float>::infinity());
}

// The L and G a leaf hands the search (stored rounded up to floats) bound the field along
// every ray piece in the leaf: the analytic directional derivative at sampled parameters
// and central second differences (h = 1e-3 of the span; slack 1e-6 absolute and relative
// for round-off, as in the field's bound tests).
TEST(LGOctree, LeafBoundsHoldAlongRayPieces) {
    int checked = 0;
    for (uint64_t seed = 1; seed <= 20; ++seed) {
        Rng rng(seed);
        auto kernel = [&rng](int) {
            return rng.Uniform() < 0.5 ? Kernel::Blob(1, Uniform(rng, 0.6, 1.2))
                                       : Kernel::GascuelQuadratic(0.4, 2, 1.1);
        };
        Scene scene(RandomPointTerms(rng, kernel), 0.6);
        for (int r = 0; r < 50; ++r) {
            Ray ray{RandomPoint(rng, -3, 3), RandomUnit(rng) * Uniform(rng, 0.5, 2)};
            scene.tree.Traverse(ray, -1e9, 1e9, [&](const LeafSpan& span) {
                const double len = Length(ray.dir), lambda = span.tExit - span.tEnter;
                if (!(lambda > 1e-6)) return false;
                const double h = 1e-3 * lambda;
                for (int i = 0; i < 20; ++i) {
                    const double t = span.tEnter + h + (lambda - 2 * h) * rng.Uniform();
                    const Vec3 p = ray.At(t);
                    const double slope = Dot(scene.field.Gradient(p), ray.dir);
                    EXPECT_LE(std::abs(slope), span.L * len * (1 + 1e-12) + 1e-12);
                    if (!std::isfinite(span.G)) continue;
                    const double second = (scene.field.Value(ray.At(t - h)) -
                                           2 * scene.field.Value(p) +
                                           scene.field.Value(ray.At(t + h))) /
                                          (h * h);
                    EXPECT_LE(std::abs(second), span.G * len * len * (1 + 1e-6) + 1e-6);
                    ++checked;
                }
                return false;
            });
        }
    }
    EXPECT_GT(checked, 1000);
}

TEST(LGOctree, CountsWork) {
    ResetStats();
    Scene scene({{"p", PointSkeleton{{0, 0, 0}}, Kernel::GascuelQuadratic(0.5, 2, 1.2), 1}}, 1.0);
    ASSERT_TRUE(scene.Hit({{0.1, 0.2, -5}, {0, 0, 1}}).has_value());
    EXPECT_GT(CounterTotal("Implicit cells visited"), 0u);
    EXPECT_GT(CounterTotal("Implicit field evaluations"), 0u);
    EXPECT_GT(CounterTotal("Implicit Ridders iterations"), 0u);
    EXPECT_GT(CounterTotal("Implicit octree cells built"), 0u);
}

// Random blended skeletons (the research note's 60-blob sweep parameters, fewer skeletons):
// the union of automatic patches gives the same first hits as one octree over the plain
// sum, and no sampled sign change of the plain sum lies before the reported hit.
TEST(LGOctree, AutomaticPatchesMatchPlainSum) {
    for (uint64_t sceneSeed = 1; sceneSeed <= 4; ++sceneSeed) {
        Rng rng(sceneSeed);
        std::vector<FieldTerm> terms;
        for (int i = 0; i < 14; ++i) {
            Skeleton s = i % 5 == 4 ? Skeleton(SegmentSkeleton{RandomPoint(rng, -1, 1),
                                                               RandomPoint(rng, -1, 1)})
                                    : Skeleton(PointSkeleton{RandomPoint(rng, -1, 1)});
            Kernel k = i % 2 ? Kernel::GascuelQuadratic(0.35, 2.4, 0.9)
                             : Kernel::GascuelLinear(0.3, 2.0, 0.9);
            terms.push_back({StringPrintf("t%d", i), s, k, 1});
        }
        Scene plain(terms, 1.0);
        std::vector<Patch> patches = BuildPatches(Field(terms), BlendMode::Automatic);
        std::vector<LGOctree> trees;
        for (const Patch& p : patches)
            trees.push_back(BuildPatchOctree(p, 1.0, OctreeSettings{}));
        int hits = 0;
        for (uint64_t seed = 1; seed <= 400; ++seed) {
            Rng r(sceneSeed * 1000 + seed);
            Vec3 o = RandomUnit(r) * 5;
            Ray ray{o, Normalize(RandomPoint(r, -1.2, 1.2) - o)};
            auto want = plain.Hit(ray);
            std::optional<double> got;
            for (size_t i = 0; i < patches.size(); ++i) {
                auto t = PatchFirstRoot(patches[i], trees[i], ray, 1e-5, got ? *got : 1e9);
                if (t && (!got || *t < *got)) got = t;
            }
            ASSERT_EQ(want.has_value(), got.has_value())
                << "scene " << sceneSeed << " seed " << seed;
            double end = want ? *want - 1e-6 : 10.0;
            for (double t = 1e-5; t < end; t += 1e-3) {
                ASSERT_LE(plain.field.Value(ray.At(t)), 1.0)
                    << "missed earlier crossing; scene " << sceneSeed << " seed " << seed;
            }
            if (!want) continue;
            ++hits;
            EXPECT_NEAR(*got, *want, 2e-7) << "scene " << sceneSeed << " seed " << seed;
            EXPECT_GT(plain.field.Value(ray.At(*want + 1e-6)), 1.0 - 1e-9);
        }
        EXPECT_GT(hits, 100);
    }
}

// Every heuristic and test is an optimisation: switching any one off (or all of them, the
// KB89 preset) changes the work, never the first hits.
TEST(LGOctree, EverySwitchPreservesTheFirstHits) {
    Rng rng(99);
    std::vector<FieldTerm> terms;
    for (int i = 0; i < 10; ++i) {
        terms.push_back({"p", PointSkeleton{RandomPoint(rng, -1, 1)},
                         Kernel::GascuelQuadratic(0.35, 2.4, 0.9), i == 9 ? -0.7 : 1.0});
    }
    std::vector<OctreeSettings> variants(14);
    variants[1].useValueRange = false;
    variants[2].useHeuristic1 = false;
    variants[3].useHeuristic1bis = false;
    variants[4].useHeuristic3 = false;
    variants[5].useHeuristic3bis = false;
    variants[6].useHeuristic4 = false;
    variants[7].useHeuristic5 = false;
    variants[8].useTest0bis = false;
    variants[9].useTest1 = false;
    variants[10].useTest2bis = false;
    variants[11].useTest3 = false;
    variants[12] = OctreeSettings({}, OctreeHeuristics::Kb89());
    variants[13].maxDepth = 0;
    std::vector<Scene> scenes;
    for (const OctreeSettings& s : variants) scenes.emplace_back(terms, 1.0, s);
    int hits = 0;
    for (uint64_t seed = 1; seed <= 150; ++seed) {
        Rng r(seed);
        Vec3 o = RandomUnit(r) * 4;
        Ray ray{o, Normalize(RandomPoint(r, -1, 1) - o)};
        auto want = scenes[0].Hit(ray);
        hits += want ? 1 : 0;
        for (size_t v = 1; v < scenes.size(); ++v) {
            auto got = scenes[v].Hit(ray);
            ASSERT_EQ(want.has_value(), got.has_value()) << "variant " << v << " seed " << seed;
            if (want) {
                EXPECT_NEAR(*got, *want, 2e-7) << "variant " << v << " seed " << seed;
            }
        }
    }
    EXPECT_GT(hits, 50);
}

// Random objects mixing every skeleton kind and kernel (with carving terms) against a
// brute-force reference: march at step 1e-3, then bisect the first sign change. The octree
// hit may not lie beyond the reference crossing, and must itself be a sign change (the
// march can step over a crossing pair thinner than its step, never the octree search).
TEST(LGOctree, AllSkeletonKindsMatchBruteForce) {
    int hits = 0;
    for (uint64_t sceneSeed = 1; sceneSeed <= 12; ++sceneSeed) {
        Rng rng(sceneSeed);
        std::vector<FieldTerm> terms;
        for (int i = 0; i < 5; ++i) {
            Kernel k = i % 3 == 0   ? Kernel::GascuelLinear(0.25, 2.0, 0.8)
                       : i % 3 == 1 ? Kernel::GascuelQuadratic(0.3, 1.5, 0.9)
                                    : Kernel::Blob(2.0, 0.9);
            terms.push_back({"t",
                             testing::RandomSkeleton(rng, (i + static_cast<int>(sceneSeed)) % 7), k,
                             i == 4 ? -0.5 : 1.0});
        }
        Scene scene(terms, 1.0);
        for (uint64_t seed = 1; seed <= 60; ++seed) {
            Rng r(sceneSeed * 100 + seed);
            Vec3 o = RandomUnit(r) * 5;
            Ray ray{o, Normalize(RandomPoint(r, -1, 1) - o)};
            auto g = [&](double t) { return scene.field.Value(ray.At(t)) - 1.0; };
            std::optional<double> ref;
            double prev = 1e-5;
            for (double t = 1e-5; t < 10; t += 1e-3) {
                if (g(t) > 0) {
                    double lo = prev, hi = t;
                    for (int it = 0; it < 60; ++it) {
                        double mid = 0.5 * (lo + hi);
                        (g(mid) > 0 ? hi : lo) = mid;
                    }
                    ref = hi;
                    break;
                }
                prev = t;
            }
            auto got = scene.Hit(ray);
            std::string where = StringPrintf("scene %d seed %d", int(sceneSeed), int(seed));
            if (ref) {
                ASSERT_TRUE(got.has_value()) << where;
                EXPECT_LE(*got, *ref + 2e-7) << where;
            }
            if (got) {
                ++hits;
                EXPECT_LE(g(*got - 2e-7), 0) << where;
                EXPECT_GT(g(*got + 2e-7), 0) << where;
            }
        }
    }
    EXPECT_GT(hits, 150);
}

// Explicit blend graph with no declared pair: the union of separate spheres; with the
// pair declared, the blended surface bulges between them.
TEST(LGOctree, ExplicitBlendListsGiveUnionOfSpheres) {
    double e = 0.5;
    Kernel k = Kernel::GascuelQuadratic(e, 2, 1.2);
    std::vector<FieldTerm> terms{{"a", PointSkeleton{{-0.3, 0, 0}}, k, 1},
                                 {"b", PointSkeleton{{0.3, 0, 0}}, k, 1},
                                 {"c", PointSkeleton{{0.3, 2, 0}}, k, 1}};
    auto firstHit = [](const std::vector<Patch>& patches, const std::vector<LGOctree>& trees,
                       const Ray& ray) {
        std::optional<double> best;
        for (size_t i = 0; i < patches.size(); ++i) {
            auto t = PatchFirstRoot(patches[i], trees[i], ray, 1e-5, 1e9);
            if (t && (!best || *t < *best)) best = t;
        }
        return best;
    };
    std::vector<Patch> separate = BuildPatches(Field(terms), BlendMode::Explicit, {{1, 2}});
    std::vector<LGOctree> trees;
    for (const Patch& p : separate)
        trees.push_back(BuildPatchOctree(p, 1.0, OctreeSettings{}));
    for (uint64_t seed = 1; seed <= 300; ++seed) {
        Rng rng(seed);
        Vec3 o = Vec3{0, 0, 0} + RandomUnit(rng) * 4;
        if (o.y > 0.5) o.y = -o.y;  // stay on the side of a and b, away from c's blend
        Ray ray{o, Normalize(RandomPoint(rng, -0.8, 0.8) - o)};
        auto ha = SphereHit(ray, {-0.3, 0, 0}, e, 1e-5);
        auto hb = SphereHit(ray, {0.3, 0, 0}, e, 1e-5);
        std::optional<double> want = ha;
        if (hb && (!want || *hb < *want)) want = hb;
        // b blends with c, which perturbs b's sphere only where c's support reaches
        // (|p − c| < R), and c has its own surface; skip rays whose hits lie there.
        auto got = firstHit(separate, trees, ray);
        Vec3 c{0.3, 2, 0};
        if ((want && Length(ray.At(*want) - c) < 1.2) || (got && Length(ray.At(*got) - c) < 1.2)) {
            continue;
        }
        ASSERT_EQ(want.has_value(), got.has_value()) << "seed " << seed;
        if (want) {
            EXPECT_NEAR(*got, *want, 1e-7) << "seed " << seed;
        }
    }
    // Through the crease at x = 0: the union gives y = ±sqrt(e² − 0.3²) = ±0.4.
    Ray crease{{0, -5, 0}, {0, 1, 0}};
    auto t = firstHit(separate, trees, crease);
    ASSERT_TRUE(t.has_value());
    EXPECT_NEAR(*t, 5 - 0.4, 1e-7);
    std::vector<Patch> blended = BuildPatches(Field(terms), BlendMode::Automatic);
    std::vector<LGOctree> blendedTrees;
    for (const Patch& p : blended)
        blendedTrees.push_back(BuildPatchOctree(p, 1.0, OctreeSettings{}));
    auto tb = firstHit(blended, blendedTrees, crease);
    ASSERT_TRUE(tb.has_value());
    EXPECT_LT(*tb, 5 - 0.4 - 0.01);  // blending fills the crease
}

}  // namespace
}  // namespace rs
