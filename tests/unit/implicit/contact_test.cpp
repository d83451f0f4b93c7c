#include "libobj/implicit/contact.h"

#include <gtest/gtest.h>

#include <cmath>

#include "libcommon/error.h"
#include "test_util.h"

namespace rs {
namespace {

using testing::Uniform;

constexpr double kPi = 3.14159265358979323846;

// ---------------------------------------------------------------------------------------
// The profile δ against its defining formulas.

TEST(BulgeProfile, EndConditionsAndPeak) {
    for (double eta : {0.0, 0.25, 0.5, 1.0}) {
        const double w = 0.7;
        BulgeProfile p(w, eta);
        EXPECT_EQ(p.Value(0), 0);
        EXPECT_EQ(p.Derivative(0), 1);
        EXPECT_NEAR(p.Derivative(1e-12), 1, 1e-9) << "eta " << eta;
        EXPECT_EQ(p.Value(-0.3), -0.3);  // compression: δ(u) = u
        EXPECT_EQ(p.Derivative(-0.3), 1);
        EXPECT_NEAR(p.Value(w * (1 - 1e-9)), 0, 1e-15) << "eta " << eta;
        EXPECT_NEAR(p.Derivative(w * (1 - 1e-9)), 0, 1e-8) << "eta " << eta;
        EXPECT_EQ(p.Value(w), 0);
        EXPECT_EQ(p.Value(2 * w), 0);
        // δ = u(1 − s)²(1 + 2ηs) at s = 0.4.
        double s = 0.4, u = s * w;
        EXPECT_NEAR(p.Value(u), u * (1 - s) * (1 - s) * (1 + 2 * eta * s), 1e-15);
    }
    // η = 0: the cubic u(1 − u/w)², peak 4w/27 at w/3.
    BulgeProfile cubic(0.9, 0);
    EXPECT_NEAR(cubic.PeakU(), 0.3, 1e-15);
    EXPECT_NEAR(cubic.Value(cubic.PeakU()), 4 * 0.9 / 27, 1e-15);
    // η = 1: q' = (s − 1)(8s² − s − 1), peak at s = (1 + √33)/16.
    BulgeProfile high(1, 1);
    double sStar = (1 + std::sqrt(33.0)) / 16;
    EXPECT_NEAR(high.PeakU(), sStar, 1e-14);
    EXPECT_NEAR(high.Value(sStar), sStar * (1 - sStar) * (1 - sStar) * (1 + 2 * sStar), 1e-14);
    // Compression only.
    BulgeProfile none;
    EXPECT_EQ(none.Value(-0.5), -0.5);
    EXPECT_EQ(none.Value(0.5), 0);
}

// δ(u) <= u everywhere (the no-overlap property), and δ', δ'' match finite differences.
TEST(BulgeProfile, BelowIdentityAndDerivatives) {
    for (uint64_t seed = 1; seed <= 200; ++seed) {
        Rng rng(seed);
        BulgeProfile p(Uniform(rng, 0.01, 2), rng.Uniform());
        for (int i = 0; i < 200; ++i) {
            double u = Uniform(rng, -0.5, 1.2 * p.Width());
            ASSERT_LE(p.Value(u), u + 1e-15) << "seed " << seed << " u " << u;
            ASSERT_GE(p.Value(u), std::min(u, 0.0)) << "seed " << seed;
            double h = 1e-6 * p.Width();
            if (u - h > 0 && u + h < p.Width()) {
                ASSERT_NEAR(p.Derivative(u), (p.Value(u + h) - p.Value(u - h)) / (2 * h), 1e-6)
                    << "seed " << seed;
                ASSERT_NEAR(p.SecondDerivative(u),
                            (p.Derivative(u + h) - p.Derivative(u - h)) / (2 * h), 1e-5 / p.Width())
                    << "seed " << seed;
            }
        }
    }
}

// ProfileBounds hold on dense samples of random intervals, and are attained (tight).
TEST(BulgeProfile, BoundsHoldOnDenseSamples) {
    for (uint64_t seed = 1; seed <= 400; ++seed) {
        Rng rng(seed);
        const double w = seed % 10 == 0 ? 0 : Uniform(rng, 0.05, 2);
        BulgeProfile p(w, seed % 4 == 0 ? 0 : rng.Uniform());
        double u0 = Uniform(rng, -0.5, 1.3 * w + 0.1), u1 = u0 + Uniform(rng, 0, w + 0.2);
        ProfileBounds pb = p.Bounds(u0, u1);
        double vMin = 1e300, vMax = -1e300, slope = 0, second = 0;
        const int n = 4000;
        for (int i = 0; i <= n; ++i) {
            double u = u0 + (u1 - u0) * i / n;
            double v = p.Value(u);
            ASSERT_GE(v, pb.valueMin - 1e-15) << "seed " << seed;
            ASSERT_LE(v, pb.valueMax + 1e-15) << "seed " << seed;
            ASSERT_LE(std::abs(p.Derivative(u)), pb.maxSlope + 1e-15) << "seed " << seed;
            ASSERT_LE(std::abs(p.SecondDerivative(u)), pb.maxSecond * (1 + 1e-12))
                << "seed " << seed;
            vMin = std::min(vMin, v);
            vMax = std::max(vMax, v);
            slope = std::max(slope, std::abs(p.Derivative(u)));
            second = std::max(second, std::abs(p.SecondDerivative(u)));
        }
        // Tightness: the bounds are extrema over the closed interval, so dense samples get
        // within one sample spacing of them (second derivative: one-sided end values).
        double du = (u1 - u0) / n;
        EXPECT_NEAR(vMin, pb.valueMin, du + 1e-12) << "seed " << seed;
        EXPECT_NEAR(vMax, pb.valueMax, du + 1e-12) << "seed " << seed;
        EXPECT_NEAR(slope, pb.maxSlope, 30 * du / (w + 1e-3) + 1e-12) << "seed " << seed;
    }
}

// ---------------------------------------------------------------------------------------
// The deformation term over random opponents and boxes.

// Mostly quadratic and blob kernels (finite G), sometimes linear (infinite G at the
// skeleton, which the deformation's bounds must carry through without NaN).
Kernel RandomSmoothKernel(Rng& rng) {
    double e = Uniform(rng, 0.2, 0.7), big = e + Uniform(rng, 0.3, 1.0);
    double k = Uniform(rng, 0.3, 3.0 / (big - e));
    double pick = rng.Uniform();
    if (pick < 0.2) return Kernel::Blob(Uniform(rng, 0.8, 2), big);
    if (pick < 0.3) return Kernel::GascuelLinear(e, k, big);
    return Kernel::GascuelQuadratic(e, k, big);
}

Field RandomOpponent(Rng& rng) {
    std::vector<FieldTerm> terms;
    int n = 1 + static_cast<int>(rng.Uniform() * 3);
    for (int i = 0; i < n; ++i) {
        FieldTerm t;
        t.name = StringPrintf("o%d", i);
        t.skeleton = testing::RandomSkeleton(rng, rng.Uniform() < 0.5 ? 0 : 1);
        t.kernel = RandomSmoothKernel(rng);
        t.weight = rng.Uniform() < 0.2 ? -Uniform(rng, 0.1, 0.5) : Uniform(rng, 0.5, 1.5);
        terms.push_back(t);
    }
    return Field(terms);
}

// Checks value, L and G of `field` over `box` on dense random samples: values in the range,
// |∇F| <= L, and the difference quotient of the directional derivative along random unit
// directions (by the mean value theorem, an average of the second directional derivative
// over a segment inside the box) within G.
void CheckBounds(const Field& field, const Bounds3& box, Rng& rng, uint64_t seed) {
    FieldBound fb = field.Bound(box);
    for (int i = 0; i < 300; ++i) {
        Vec3 p = testing::RandomInBox(rng, box);
        double v = field.Value(p);
        ASSERT_GE(v, fb.valueMin - 1e-12) << "seed " << seed;
        ASSERT_LE(v, fb.valueMax + 1e-12) << "seed " << seed;
        ASSERT_LE(Length(field.Gradient(p)), fb.L * (1 + 1e-9) + 1e-12) << "seed " << seed;
        Vec3 dir = testing::RandomUnit(rng);
        double h = 1e-4 * Length(box.Extent());
        Vec3 a = p - dir * h, b = p + dir * h;
        if (!box.Contains(a) || !box.Contains(b)) continue;
        double second = Dot(field.Gradient(b) - field.Gradient(a), dir) / (2 * h);
        ASSERT_FALSE(std::isnan(fb.G)) << "seed " << seed;
        ASSERT_LE(std::abs(second), fb.G * (1 + 1e-6) + 1e-6) << "seed " << seed;
    }
}

TEST(ContactDeformation, BoundsHoldOnDenseSamples) {
    for (uint64_t seed = 1; seed <= 300; ++seed) {
        Rng rng(seed);
        Field opponent = RandomOpponent(rng);
        const double threshold = Uniform(rng, 0.3, 1);
        BulgeProfile profile(seed % 5 == 0 ? 0 : Uniform(rng, 0.05, threshold), rng.Uniform());
        auto deformation = std::make_shared<ContactDeformation>(opponent, threshold, profile);
        Field alone;
        alone.SetDeformation(deformation);
        Bounds3 box = testing::RandomBox(rng, -2, 1.5, seed % 3 == 0 ? 2.0 : 0.4);
        CheckBounds(alone, box, rng, seed);
        // The deformed field of a patch: its own terms plus the deformation.
        Field own = RandomOpponent(rng);
        Field deformed(own.Terms());
        deformed.SetDeformation(deformation);
        CheckBounds(deformed, box, rng, seed);
    }
}

// The zone box holds every point where the term is non-zero.
TEST(ContactDeformation, ZoneContainsSupport) {
    for (uint64_t seed = 1; seed <= 100; ++seed) {
        Rng rng(seed);
        Field opponent = RandomOpponent(rng);
        const double threshold = Uniform(rng, 0.3, 1);
        BulgeProfile profile(Uniform(rng, 0, threshold), rng.Uniform());
        ContactDeformation d(opponent, threshold, profile);
        for (int i = 0; i < 2000; ++i) {
            Vec3 p = testing::RandomPoint(rng, -3, 3);
            double exact = profile.Value(threshold - opponent.Value(p));
            if (exact != 0) {
                ASSERT_TRUE(d.Zone().Contains(p)) << "seed " << seed;
            }
            ASSERT_EQ(d.Value(p), exact) << "seed " << seed;
        }
    }
}

// ---------------------------------------------------------------------------------------
// Two identical point-skeleton spheres pushed into each other symmetrically.

struct TwoSpheres {
    static constexpr double kCentre = 0.8;  // centres at ±kCentre on x; radius e = 1
    std::vector<FieldTerm> terms;
    std::vector<Patch> patches;
    std::vector<LGOctree> trees;
    std::vector<DeformedPatch> deformed;
    OctreeSettings settings;

    // Propagation width (0: compression only) and height for both spheres.
    TwoSpheres(double width, double height) {
        for (double x : {-kCentre, kCentre}) {
            FieldTerm t;
            t.name = x < 0 ? "a" : "b";
            t.skeleton = PointSkeleton{{x, 0, 0}};
            t.kernel = Kernel::GascuelQuadratic(1, 1, 2);
            terms.push_back(t);
        }
        patches = BuildPatches(Field(terms), BlendMode::Automatic, {}, {{0, 1}});
        for (const Patch& p : patches) trees.push_back(BuildPatchOctree(p, 1, settings));
        std::vector<Propagation> props;
        if (width > 0) props = {{0, width, height}, {1, width, height}};
        deformed = ApplyContacts(terms, {{0, 1}}, props, 1, settings, patches, trees);
    }
    std::optional<double> Root(int patch, const Ray& ray) const {
        return PatchFirstRoot(patches[patch], trees[patch], ray, 0, 10);
    }
    Vec3 Normal(int patch, const Vec3& p) const {
        return Normalize(-patches[patch].GetField().Gradient(p));
    }
};

TEST(ContactSpheres, ContactsAreDeclaredSeparateAndMeasured) {
    TwoSpheres s(0.3, 0.5);
    ASSERT_EQ(s.patches.size(), 2u);
    EXPECT_EQ(s.patches[0].Members().size(), 1u);  // no blending between a and b
    ASSERT_EQ(s.deformed.size(), 2u);
    for (const DeformedPatch& d : s.deformed) {
        EXPECT_TRUE(d.interpenetrates);
        EXPECT_TRUE(d.deformed);
        // The ray from a's centre enters b's sphere at x = −0.2, the zone edge is 0.3
        // before it, at distance 1.3 from b's centre: w = 1 − f(1.3) for the default kernel
        // (outer cubic, ℓ = 1, m = 1, s = 0.3: 2s³ − 3s² + 1 − (s³ − 2s² + s)).
        double sp = 0.3, f = 2 * sp * sp * sp - 3 * sp * sp + 1 - (sp * sp * sp - 2 * sp * sp + sp);
        EXPECT_NEAR(d.fieldWidth, 1 - f, 1e-6);
    }
}

// The affected box holds every point where the deformed and undeformed fields of a patch lie
// on different sides of the threshold.
TEST(ContactSpheres, AffectedBoxHoldsEveryChangedPoint) {
    for (double width : {0.0, 0.3}) {
        TwoSpheres s(width, 1.0);
        Field undeformed = s.patches[0].GetField();  // shares the terms
        undeformed.SetDeformation(nullptr);
        const Bounds3& affected = s.deformed[0].affected;
        Rng rng(5);
        int changed = 0;
        for (int i = 0; i < 200000; ++i) {
            Vec3 p = testing::RandomInBox(rng, s.patches[0].Box());
            bool before = undeformed.Value(p) > 1, after = s.patches[0].GetField().Value(p) > 1;
            if (before == after) continue;
            ++changed;
            ASSERT_TRUE(affected.Contains(p)) << "width " << width << " sample " << i;
        }
        EXPECT_GT(changed, 100);
        // The box stays near the contact: within the slab |x| < 0.6 around the plane.
        EXPECT_GT(affected.lo.x, -0.6);
        EXPECT_LT(affected.hi.x, 0.6);
    }
}

// Rays from many directions through the contact disk: the exit from a and the entry into b
// are both on the symmetry plane x = 0, to the tolerance, and coincide (no gap, no overlap).
TEST(ContactSpheres, ContactSurfaceIsTheSymmetryPlane) {
    for (double width : {0.0, 0.3}) {
        TwoSpheres s(width, 0.5);
        const double tol = s.settings.tolerance;
        Rng rng(7);
        int tested = 0;
        for (int i = 0; i < 3000; ++i) {
            // The contact disk is x = 0, y² + z² < 1 − 0.8² = 0.36.
            Vec3 target{0, Uniform(rng, -0.55, 0.55), Uniform(rng, -0.55, 0.55)};
            if (target.y * target.y + target.z * target.z > 0.33) continue;
            Vec3 dir = testing::RandomUnit(rng);
            if (dir.x < 0) dir = -dir;
            // Start at x = −0.1, within the cylinder ρ² <= 0.33 whose slab x in [−0.1, 0] lies
            // inside a's deformed volume (distance to a's centre at most 0.906 < 1), so the
            // first root of a is its exit through the disk.
            Vec3 origin = target - dir * (0.1 / dir.x);
            if (origin.y * origin.y + origin.z * origin.z > 0.33) continue;
            Ray ray{origin, dir};
            std::optional<double> exitA = s.Root(0, ray), entryB = s.Root(1, ray);
            ASSERT_TRUE(exitA && entryB) << "width " << width << " ray " << i;
            Vec3 pa = ray.At(*exitA), pb = ray.At(*entryB);
            ASSERT_LE(std::abs(pa.x), tol) << "width " << width << " ray " << i;
            ASSERT_LE(std::abs(pb.x), tol) << "width " << width << " ray " << i;
            ASSERT_LE(std::abs(*exitA - *entryB), 2 * tol) << "width " << width << " ray " << i;
            // Opposite normals: a's points into b and b's into a, both along x.
            EXPECT_GT(s.Normal(0, pa).x, 0.999);
            EXPECT_LT(s.Normal(1, pb).x, -0.999);
            ++tested;
        }
        EXPECT_GT(tested, 500);
    }
}

// Along the outside of the pair the two deformed volumes never overlap: a ray that enters
// one of them first meets the other, if at all, no earlier than its own exit.
TEST(ContactSpheres, DeformedVolumesAreDisjoint) {
    TwoSpheres s(0.3, 1.0);
    Rng rng(11);
    for (int i = 0; i < 2000; ++i) {
        Vec3 origin = testing::RandomUnit(rng) * 4;
        Vec3 dir = Normalize(testing::RandomPoint(rng, -0.6, 0.6) - origin);
        Ray ray{origin, dir};
        // Sample the ray: no point is inside both deformed fields.
        for (int k = 0; k <= 400; ++k) {
            Vec3 p = ray.At(2 + 4.0 * k / 400);
            bool inA = s.patches[0].GetField().Value(p) > 1;
            bool inB = s.patches[1].GetField().Value(p) > 1;
            ASSERT_FALSE(inA && inB) << "ray " << i << " sample " << k;
        }
    }
}

// Normal continuity across the rim of the contact zone. A fan of rays from a's centre in
// the xz-plane, at angles θ from +x, crosses the rim (θ = atan(0.6/0.8) ≈ 36.9°) going from
// the contact disk onto the bulge. The largest angle between the normals of consecutive
// hits measures the jump. With the bulge the surface is G1: the largest jump shrinks in
// proportion to the step (it is curvature × arc step); with compression alone there is a
// crease of about 37° (the angle between the plane's normal and the sphere's at the rim).
double LargestNormalJump(const TwoSpheres& s, int rays, double& jumpAtRim) {
    const double rim = std::atan2(0.6, 0.8);
    double largest = 0;
    jumpAtRim = 0;
    Vec3 previous;
    double previousTheta = 0;
    for (int i = 0; i <= rays; ++i) {
        double theta = (10 + 50.0 * i / rays) * kPi / 180;  // 10° to 60°
        Ray ray{{-TwoSpheres::kCentre, 0, 0}, {std::cos(theta), 0, std::sin(theta)}};
        std::optional<double> t = s.Root(0, ray);
        EXPECT_TRUE(t);
        if (!t) return 180;
        Vec3 n = s.Normal(0, ray.At(*t));
        if (i > 0) {
            double jump = std::acos(std::clamp(Dot(n, previous), -1.0, 1.0)) * 180 / kPi;
            largest = std::max(largest, jump);
            if (previousTheta <= rim && theta >= rim) jumpAtRim = jump;
        }
        previous = n;
        previousTheta = theta;
    }
    return largest;
}

TEST(ContactSpheres, NormalsContinuousAcrossTheRim) {
    double rimCoarse, rimFine, rimCrease;
    TwoSpheres bulge(0.3, 0.5);
    double coarse = LargestNormalJump(bulge, 1000, rimCoarse);  // 0.05° steps
    double fine = LargestNormalJump(bulge, 4000, rimFine);      // 0.0125° steps
    // Measured: 0.90° and 0.23° over the whole fan (the bulge's tightest bend turns the
    // normal 18 times faster than the ray), 0.047° and 0.008° between the two rays on either
    // side of the rim: the jump falls with the step, as for any C¹ surface.
    EXPECT_LT(coarse, 1.2);
    EXPECT_LT(fine, 0.3);
    EXPECT_LT(fine, coarse / 3);
    EXPECT_LT(rimCoarse, 0.1);
    EXPECT_LT(rimFine, 0.02);
    // Without propagation the rim is a crease that refinement does not close.
    TwoSpheres crease(0, 0);
    LargestNormalJump(crease, 4000, rimCrease);
    EXPECT_GT(rimCrease, 36.8);  // atan(0.6/0.8) = 36.87°
}

// The bulge is switched off when the volumes do not interpenetrate along the measuring ray.
TEST(ContactSpheres, NoBulgeWithoutInterpenetration) {
    std::vector<FieldTerm> terms;
    for (double x : {-1.1, 1.1}) {
        FieldTerm t;
        t.name = x < 0 ? "a" : "b";
        t.skeleton = PointSkeleton{{x, 0, 0}};
        t.kernel = Kernel::GascuelQuadratic(1, 1, 2);
        terms.push_back(t);
    }
    OctreeSettings settings;
    std::vector<Patch> patches = BuildPatches(Field(terms), BlendMode::Automatic, {}, {{0, 1}});
    std::vector<LGOctree> trees;
    for (const Patch& p : patches) trees.push_back(BuildPatchOctree(p, 1, settings));
    std::vector<DeformedPatch> d =
        ApplyContacts(terms, {{0, 1}}, {{0, 0.3, 0.5}}, 1, settings, patches, trees);
    ASSERT_EQ(d.size(), 2u);
    EXPECT_FALSE(d[0].interpenetrates);
    EXPECT_EQ(d[0].fieldWidth, 0);
    EXPECT_FALSE(d[0].deformed);
    EXPECT_FALSE(d[1].deformed);
    EXPECT_EQ(patches[0].GetField().Deformation(), nullptr);
    // The surfaces are the undeformed spheres: the ray along x leaves a at x = −0.1.
    Ray ray{{-1.1, 0, 0}, {1, 0, 0}};
    std::optional<double> t = PatchFirstRoot(patches[0], trees[0], ray, 0, 10);
    ASSERT_TRUE(t);
    EXPECT_NEAR(*t, 1, 1e-7);
}

// The deformed octree search against dense sampling, on random colliding pairs of point and
// segment skeletons: along random rays through the contact region, the first root the
// search returns for each deformed patch is no later than the first sign change seen by
// sampling the deformed field every 1e-3, and is itself a sign change (to the tolerance).
TEST(ContactPairs, DeformedSearchFindsTheFirstSignChange) {
    for (uint64_t seed = 1; seed <= 40; ++seed) {
        Rng rng(seed);
        std::vector<FieldTerm> terms;
        for (int i = 0; i < 2; ++i) {
            FieldTerm t;
            t.name = i == 0 ? "a" : "b";
            Vec3 c{i == 0 ? -0.45 : 0.45, Uniform(rng, -0.2, 0.2), Uniform(rng, -0.2, 0.2)};
            if (rng.Uniform() < 0.5) {
                t.skeleton = PointSkeleton{c};
            } else {
                Vec3 d = testing::RandomUnit(rng) * 0.4;
                t.skeleton = SegmentSkeleton{c - d, c + d};
            }
            double e = Uniform(rng, 0.5, 0.8), big = e + Uniform(rng, 0.4, 1.0);
            t.kernel = Kernel::GascuelQuadratic(e, Uniform(rng, 0.5, 3.0 / (big - e)), big);
            terms.push_back(t);
        }
        OctreeSettings settings;
        std::vector<Patch> patches = BuildPatches(Field(terms), BlendMode::Automatic, {}, {{0, 1}});
        std::vector<LGOctree> trees;
        for (const Patch& p : patches) trees.push_back(BuildPatchOctree(p, 1, settings));
        double width = seed % 4 == 0 ? 0 : Uniform(rng, 0.05, 0.4);
        std::vector<Propagation> props{{0, width, rng.Uniform()}, {1, width, rng.Uniform()}};
        ApplyContacts(terms, {{0, 1}}, props, 1, settings, patches, trees);
        for (int r = 0; r < 60; ++r) {
            Vec3 target = testing::RandomPoint(rng, -0.5, 0.5);
            Vec3 dir = testing::RandomUnit(rng);
            Ray ray{target - dir * 3, dir};
            for (int k = 0; k < 2; ++k) {
                const Field& field = patches[k].GetField();
                double first = -1;
                double previous = field.Value(ray.At(0)) - 1;
                for (int i = 1; i <= 6000; ++i) {
                    double g = field.Value(ray.At(i * 1e-3)) - 1;
                    if ((g > 0) != (previous > 0)) {
                        first = i * 1e-3;
                        break;
                    }
                    previous = g;
                }
                std::optional<double> t = PatchFirstRoot(patches[k], trees[k], ray, 0, 6);
                if (first < 0) continue;  // sampling saw nothing (the search may see more)
                ASSERT_TRUE(t) << "seed " << seed << " ray " << r << " patch " << k;
                ASSERT_LE(*t, first + 1e-7) << "seed " << seed << " ray " << r << " patch " << k;
                double below = field.Value(ray.At(*t - 1e-6)) - 1;
                double above = field.Value(ray.At(*t + 1e-6)) - 1;
                ASSERT_TRUE((below > 0) != (above > 0) || std::abs(below) < 1e-9 ||
                            std::abs(above) < 1e-9)
                    << "seed " << seed << " ray " << r << " patch " << k;
            }
        }
    }
}

}  // namespace
}  // namespace rs

namespace rs {
namespace {

// Two lone quadratic points (e = 0.5, T = 1): each volume is the ball of radius e around
// its point (f(e) = 1, f decreasing), so they interpenetrate exactly when the points are
// closer than 2e = 1. The search resolves cells of 1/128 of the overlap box (about 0.02
// here): lenses 0.05 thick are found, and no overlap is ever invented.
TEST(AutomaticContacts, LoneBallsInterpenetrateBelowTwiceTheThickness) {
    const Kernel k = Kernel::GascuelQuadratic(0.5, 1.5, 1.2);
    for (const auto& [distance, expected] :
         std::vector<std::pair<double, bool>>{{0.6, true}, {0.95, true}, {1.05, false},
                                              {1.5, false}}) {
        std::vector<FieldTerm> terms{{"a", PointSkeleton{{0, 0, 0}}, k, 1},
                                     {"b", PointSkeleton{{distance, 0.1, -0.2}}, k, 1}};
        // Explicit mode with no pair: nothing blends.
        std::vector<Patch> patches = BuildPatches(Field(terms), BlendMode::Explicit);
        ASSERT_EQ(patches.size(), 2u);
        EXPECT_EQ(VolumesInterpenetrate(patches[0], patches[1], 1.0), expected) << distance;
        const std::vector<ContactPair> pairs = AutomaticContacts(patches, 1.0);
        ASSERT_EQ(pairs.size(), expected ? 1u : 0u) << distance;
        if (expected) {
            EXPECT_EQ(pairs[0].a, 0);
            EXPECT_EQ(pairs[0].b, 1);
        }
    }
}

// Pairs that blend are never put in contact, however deep they overlap.
TEST(AutomaticContacts, BlendingPairsAreLeftAlone) {
    const Kernel k = Kernel::GascuelQuadratic(0.5, 1.5, 1.2);
    std::vector<FieldTerm> terms{{"a", PointSkeleton{{0, 0, 0}}, k, 1},
                                 {"b", PointSkeleton{{0.5, 0, 0}}, k, 1},
                                 {"c", PointSkeleton{{0.25, 0.5, 0}}, k, 1}};
    std::vector<Patch> patches = BuildPatches(Field(terms), BlendMode::Explicit, {{0, 1}});
    const std::vector<ContactPair> pairs = AutomaticContacts(patches, 1.0);
    ASSERT_EQ(pairs.size(), 2u);
    EXPECT_EQ(pairs[0].a, 0);
    EXPECT_EQ(pairs[0].b, 2);
    EXPECT_EQ(pairs[1].a, 1);
    EXPECT_EQ(pairs[1].b, 2);
    EXPECT_TRUE(AutomaticContacts(BuildPatches(Field(terms), BlendMode::Automatic), 1.0).empty());
}

// The search clears cells by bounds (field <= T, or an own term that cannot predominate),
// which must never clear a point inside both volumes: wherever a brute-force test of the
// centres of the first five subdivision levels of the overlap box (every centre the search
// would test there if it cleared nothing) finds a point inside both, the search must answer
// yes. Random pairs of points and segments that do not blend but both blend with a hub
// skeleton between them, so the hub's volume, where neither own term predominates, fills
// much of the overlap.
TEST(AutomaticContacts, PruningNeverClearsAPointInsideBoth) {
    Rng rng(19);
    int positives = 0;
    for (int trial = 0; trial < 300; ++trial) {
        std::vector<FieldTerm> terms;
        for (const char* name : {"a", "b", "hub"}) {
            FieldTerm t;
            t.name = name;
            t.skeleton = testing::RandomSkeleton(rng, rng.Uniform() < 0.5 ? 0 : 1);
            t.kernel = RandomSmoothKernel(rng);
            t.weight = Uniform(rng, 0.5, 1.5);
            terms.push_back(t);
        }
        const std::vector<Patch> patches =
            BuildPatches(Field(terms), BlendMode::Explicit, {{0, 2}, {1, 2}});
        ASSERT_EQ(patches.size(), 3u);
        const Patch& a = patches[0];
        const Patch& b = patches[1];
        const double threshold = 1;
        const Bounds3 overlap = Intersection(a.Box(), b.Box());
        if (overlap.IsEmpty()) continue;
        bool found = false;
        for (int level = 0; level <= 4 && !found; ++level) {
            const int n = 1 << level;
            const Vec3 step = overlap.Extent() / n;
            for (int i = 0; i < n * n * n && !found; ++i) {
                const Vec3 p = overlap.lo + Vec3{(i % n + 0.5) * step.x,
                                                 ((i / n) % n + 0.5) * step.y,
                                                 (i / (n * n) + 0.5) * step.z};
                found = a.GetField().Value(p) > threshold && b.GetField().Value(p) > threshold &&
                        a.Predominates(p) && b.Predominates(p);
            }
        }
        positives += found;
        if (found) {
            EXPECT_TRUE(VolumesInterpenetrate(a, b, threshold)) << "trial " << trial;
        }
    }
    EXPECT_GT(positives, 20);  // the property is exercised
}

}  // namespace
}  // namespace rs
