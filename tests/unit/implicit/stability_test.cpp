// The research note's stability categories (§11), each against a closed form.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>

#include "libobj/implicit/lg_octree.h"

namespace rs {
namespace {

// First hit of the union of automatic patches (the primitive's algorithm).
std::optional<double> PatchesHit(const std::vector<FieldTerm>& terms, double threshold,
                                 const Ray& ray, double tMin = 1e-5) {
    std::vector<Patch> patches = BuildPatches(Field(terms), BlendMode::Automatic);
    std::optional<double> best;
    for (const Patch& p : patches) {
        LGOctree tree = BuildPatchOctree(p, threshold, OctreeSettings{});
        auto t = PatchFirstRoot(p, tree, ray, tMin, best ? *best : 1e12);
        if (t) best = t;
    }
    return best;
}

// N coincident blob skeletons: N·s(1 − r²/R²)² = T at r = R·sqrt(1 − sqrt(T/(N s))), and
// exactly one patch (the lowest index) accepts each root.
TEST(Stability, CoincidentSkeletons) {
    for (int n = 1; n <= 5; ++n) {
        std::vector<FieldTerm> terms(
            n, FieldTerm{"p", PointSkeleton{{0, 0, 0}}, Kernel::Blob(1, 1), 1});
        double radius = std::sqrt(1 - std::sqrt(0.5 / n));
        auto t = PatchesHit(terms, 0.5, {{0.1, 0, -5}, {0, 0, 1}});
        ASSERT_TRUE(t.has_value()) << n;
        EXPECT_NEAR(*t, 5 - std::sqrt(radius * radius - 0.01), 1e-7) << n;
        std::vector<Patch> patches = BuildPatches(Field(terms), BlendMode::Automatic);
        int accepting = 0;
        for (const Patch& p : patches) accepting += p.Predominates({0.1, 0, -radius}) ? 1 : 0;
        EXPECT_EQ(accepting, 1);
    }
}

// Concentric positive blob (s = 1, R = 2) and negative blob (weight −1, s = 1, R = 1) at
// T = 1/4: outer sphere r² = 2; inside r < 1, F(u = r²) = 1.5u − 15u²/16, so the cavity
// has u = (1.5 − sqrt(1.3125))/1.875. The cavity is visible from inside.
TEST(Stability, HollowShellFromNegativeField) {
    std::vector<FieldTerm> terms{{"outer", PointSkeleton{{0, 0, 0}}, Kernel::Blob(1, 2), 1},
                                 {"hole", PointSkeleton{{0, 0, 0}}, Kernel::Blob(1, 1), -1}};
    double outer = std::sqrt(2.0), inner = std::sqrt((1.5 - std::sqrt(1.3125)) / 1.875);
    auto t = PatchesHit(terms, 0.25, {{0, 0, -5}, {0, 0, 1}});
    ASSERT_TRUE(t.has_value());
    EXPECT_NEAR(*t, 5 - outer, 1e-7);
    auto fromCentre = PatchesHit(terms, 0.25, {{0, 0, 0}, {0.6, 0.8, 0}});
    ASSERT_TRUE(fromCentre.has_value());
    EXPECT_NEAR(*fromCentre, inner, 1e-7);
    auto inShell = PatchesHit(terms, 0.25, {{0.8, 0, 0}, {1, 0, 0}});
    ASSERT_TRUE(inShell.has_value());
    EXPECT_NEAR(*inShell, outer - 0.8, 1e-7);
    // A lone negative skeleton gives no surface.
    std::vector<FieldTerm> negative{terms[1]};
    EXPECT_FALSE(PatchesHit(negative, 0.25, {{0, 0, -5}, {0, 0, 1}}).has_value());
}

// A skeleton scaled by σ (e, R × σ, k ÷ σ) is a sphere of radius σe.
TEST(Stability, TinyComponents) {
    for (double sigma : {1e-1, 1e-3, 1e-5}) {
        std::vector<FieldTerm> terms{{"p", PointSkeleton{{0, 0, 0}},
                                      Kernel::GascuelQuadratic(0.5 * sigma, 2 / sigma, 1.2 * sigma),
                                      1}};
        auto t = PatchesHit(terms, 1, {{0, 0, -5}, {0, 0, 1}});
        ASSERT_TRUE(t.has_value()) << sigma;
        EXPECT_NEAR(*t, 5 - 0.5 * sigma, 1e-7) << sigma;
    }
}

// Far cameras: t = D − sqrt(e² − b²) to the tolerance plus the spacing of doubles at D.
TEST(Stability, FarCameras) {
    std::vector<FieldTerm> terms{
        {"p", PointSkeleton{{0, 0, 0}}, Kernel::GascuelLinear(0.5, 2, 1.2), 1}};
    for (double d : {1e1, 1e3, 1e5, 1e6}) {
        auto t = PatchesHit(terms, 1, {{0.3, 0, -d}, {0, 0, 1}});
        ASSERT_TRUE(t.has_value()) << d;
        EXPECT_NEAR(*t, d - 0.4, 1e-7 + 8 * d * 2.3e-16) << d;
    }
}

// Thin necks: equal blobs at ±a, T = 1/2: the bisecting plane has F = 2f(sqrt(a² + ρ²)),
// so the neck radius is sqrt(d² − a²) with f(d) = T/2, d = R·sqrt(1 − sqrt(T/(2s))).
TEST(Stability, ThinNecks) {
    double d = std::sqrt(1 - std::sqrt(0.25));
    for (double neck : {1e-1, 1e-3, 1e-5}) {
        double a = std::sqrt(d * d - neck * neck);
        std::vector<FieldTerm> terms{{"l", PointSkeleton{{-a, 0, 0}}, Kernel::Blob(1, 1), 1},
                                     {"r", PointSkeleton{{a, 0, 0}}, Kernel::Blob(1, 1), 1}};
        auto t = PatchesHit(terms, 0.5, {{0, -5, 0}, {0, 1, 0}});
        ASSERT_TRUE(t.has_value()) << neck;
        EXPECT_NEAR(*t, 5 - neck, 1e-7) << neck;
    }
}

// Pinch point (a = d): F = T with ∇F = 0 at the origin only. The policy reports a hit only
// where a sign change is seen; whatever it reports must be finite and near the pinch.
TEST(Stability, PinchPointIsHandled) {
    double d = std::sqrt(1 - std::sqrt(0.25));
    std::vector<FieldTerm> terms{{"l", PointSkeleton{{-d, 0, 0}}, Kernel::Blob(1, 1), 1},
                                 {"r", PointSkeleton{{d, 0, 0}}, Kernel::Blob(1, 1), 1}};
    auto t = PatchesHit(terms, 0.5, {{0, -5, 0}, {0, 1, 0}});
    if (t) {
        EXPECT_TRUE(std::isfinite(*t));
        EXPECT_NEAR(*t, 5, 1e-3);
    }
    // Along x the far lobe does not reach (|x − d| >= R there), so the hit is the single
    // blob's radius sqrt(1 − sqrt(T/s)) beyond −d.
    auto tx = PatchesHit(terms, 0.5, {{-5, 0, 0}, {1, 0, 0}});
    ASSERT_TRUE(tx.has_value());
    EXPECT_NEAR(*tx, 5 - d - std::sqrt(1 - std::sqrt(0.5)), 1e-7);
}

}  // namespace
}  // namespace rs
