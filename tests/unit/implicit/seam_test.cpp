// The seam rule (patch.h, Patch::PredominatesNear): the patches method never loses a root
// that lies on, or next to, the seam between two patches. Checked against the long-double
// ground truth (exact_method.h) on families of rays swept across the seam of every pair of
// skeleton kinds: each family is bisected until the skeleton owning the exact hit changes
// (the seam), and the ray found is then offset by 0, ±1e-12 and ±1e-9 of the scene's size.
// Eye rays start outside the object, secondary rays inside it (the exit through the seam
// that refracted rays meet); every tolerance setting must agree with exact to within its
// tolerance, with no lost root and no false hit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include "libobj/implicit/exact_method.h"
#include "libobj/implicit/lg_octree.h"
#include "test_util.h"

namespace rs {
namespace {

constexpr int kKinds = 7;  // the Skeleton variant's alternatives
constexpr double kThreshold = 1;
constexpr double kSceneSize = 2.4;  // the two skeletons' supports span about this much

// A skeleton of kind `kind` a few tenths across around `centre`, turned by the orthonormal
// frame (u, v, w) so that each pair of kinds meets along a differently curved seam.
Skeleton SkeletonAround(int kind, const Vec3& centre, const Vec3& u, const Vec3& v,
                        const Vec3& w) {
    auto at = [&](double a, double b, double c) { return centre + u * a + v * b + w * c; };
    switch (kind) {
        case 0:
            return PointSkeleton{centre};
        case 1:
            return SegmentSkeleton{at(0, -0.3, 0), at(0, 0.3, 0)};
        case 2:
            return PolylineSkeleton{{at(0, -0.3, 0), at(0.1, 0, 0.1), at(0, 0.3, 0)}};
        case 3:
            return CircleSkeleton{centre, w, 0.3};
        case 4:
            return TriangleSkeleton{at(0, -0.3, -0.2), at(0, 0.3, -0.2), at(0.1, 0, 0.3)};
        case 5: {
            // Axis-aligned by definition: the frame only moves its centre.
            const Vec3 half{0.1, 0.2, 0.15};
            return BoxSkeleton{centre - half, centre + half};
        }
        default:
            return CylinderSkeleton{at(0, 0, -0.25), at(0, 0, 0.25), 0.1};
    }
}

struct Frame {
    Vec3 u, v, w;
};

Frame RandomFrame(Rng& rng) {
    const Vec3 u = testing::RandomUnit(rng);
    Vec3 v = Cross(u, testing::RandomUnit(rng));
    while (LengthSquared(v) < 1e-2) v = Cross(u, testing::RandomUnit(rng));
    v = Normalize(v);
    return {u, v, Cross(u, v)};
}

// One configuration: two blending skeletons A (term 0, left) and B (term 1, right).
class SeamScene {
  public:
    SeamScene(std::vector<FieldTerm> terms, BlendMode mode)
        : field_(std::move(terms)),
          exact_(field_, MethodParams{kThreshold, 1e-7, 0}),
          patches_(BuildPatches(field_, mode, {{0, 1}})) {}

    const Field& GetField() const { return field_; }
    std::optional<double> Exact(const Ray& ray, double tMin) const {
        return exact_.FirstRoot(ray, tMin, 1e9);
    }
    // The union of the patches' first roots, as the primitive searches it.
    std::optional<double> Patches(const std::vector<LGOctree>& trees, const Ray& ray,
                                  double tMin) const {
        std::optional<double> best;
        for (size_t i = 0; i < patches_.size(); ++i) {
            auto t = PatchFirstRoot(patches_[i], trees[i], ray, tMin, best ? *best : 1e9);
            if (t) best = t;
        }
        return best;
    }
    std::vector<LGOctree> Trees(const OctreeSettings& settings) const {
        std::vector<LGOctree> trees;
        for (const Patch& patch : patches_) {
            trees.push_back(BuildPatchOctree(patch, kThreshold, settings));
        }
        return trees;
    }

  private:
    Field field_;
    ExactMethod exact_;
    std::vector<Patch> patches_;
};

// A ray aimed between two targets: from `origin` towards lerp(qa, qb, s).
struct RayFamily {
    Vec3 origin, qa, qb;
    double tMin;
    Ray At(double s) const { return {origin, Normalize(qa + (qb - qa) * s - origin), 0}; }
};

// The exact hit along the family at s, or nothing on a miss or a grazing hit (the surface
// crossed at less than 3° from the ray, where the owner is ill-defined along s).
std::optional<Vec3> HitAt(const SeamScene& scene, const RayFamily& family, double s) {
    const Ray ray = family.At(s);
    const std::optional<double> t = scene.Exact(ray, family.tMin);
    if (!t) return std::nullopt;
    const Vec3 p = ray.At(*t);
    const Vec3 gradient = scene.GetField().Gradient(p);
    if (!(std::abs(Dot(gradient, ray.dir)) > 0.05 * Length(gradient))) return std::nullopt;
    return p;
}

// c_A − c_B at p: A (term 0) owns the surface where it is >= 0 (ties to the lower index).
double Lead(const SeamScene& scene, const Vec3& p) {
    return scene.GetField().TermValue(0, p) - scene.GetField().TermValue(1, p);
}

// Narrows the family to the seam: the largest s found whose hit A owns, next to one (within
// 1e-14 in s) that B owns, the two hit points within 1e-9 (otherwise the owner changed at a
// silhouette, not a seam). Regula falsi with the Illinois modification on the lead.
std::optional<double> SeamOf(const SeamScene& scene, const RayFamily& family) {
    const std::optional<Vec3> pa = HitAt(scene, family, 0), pb = HitAt(scene, family, 1);
    if (!pa || !pb) return std::nullopt;
    double lo = 0, hi = 1, leadLo = Lead(scene, *pa), leadHi = Lead(scene, *pb);
    if (!(leadLo >= 0 && leadHi < 0)) return std::nullopt;
    int side = 0;  // which end stayed last time (Illinois halves its value when it stays twice)
    Vec3 pLo = *pa, pHi = *pb;
    for (int i = 0; i < 100 && hi - lo > 1e-14; ++i) {
        double s = (lo * leadHi - hi * leadLo) / (leadHi - leadLo);
        // Keep the probe strictly inside and away from stagnation at one end.
        const double margin = 0.01 * (hi - lo);
        s = std::clamp(s, lo + margin, hi - margin);
        if (i % 4 == 3) s = 0.5 * (lo + hi);  // a bisection step now and then
        const std::optional<Vec3> p = HitAt(scene, family, s);
        if (!p) return std::nullopt;
        const double lead = Lead(scene, *p);
        if (lead >= 0) {
            lo = s, leadLo = lead, pLo = *p;
            if (side == -1) leadHi *= 0.5;
            side = -1;
        } else {
            hi = s, leadHi = lead, pHi = *p;
            if (side == 1) leadLo *= 0.5;
            side = 1;
        }
    }
    if (!(hi - lo <= 1e-14) || !(Length(pHi - pLo) < 1e-9)) return std::nullopt;
    return lo;
}

struct Tally {
    long rays = 0, lost = 0, falseHits = 0, wrongDepth = 0;
};

// The settings swept: a fine and a coarse fixed tolerance, and the automatic tolerance on
// rays carrying a pixel footprint (a 512-pixel, 30° camera about 4 units away).
struct ToleranceCase {
    const char* name;
    double tolerance;
    bool automatic;
};
constexpr ToleranceCase kToleranceCases[] = {
    {"1e-7", 1e-7, false}, {"1e-3", 1e-3, false}, {"auto", 1e-7, true}};
constexpr double kFootprintSpread = 0.5236 / 512;  // radians per pixel

// `exact`: the ground truth's answer for the ray (it has no tolerance and ignores the
// footprint).
void CheckRay(const SeamScene& scene, const std::vector<LGOctree>& trees,
              const ToleranceCase& tc, Ray ray, double tMin, std::optional<double> exact,
              Tally& tally) {
    if (tc.automatic) ray.footprintSpread = kFootprintSpread;
    const std::optional<double> got = scene.Patches(trees, ray, tMin);
    ++tally.rays;
    if (exact && !got) {
        ++tally.lost;
        ADD_FAILURE() << "lost root at t = " << *exact << " (tolerance " << tc.name << ") ray "
                      << ray.origin.x << " " << ray.origin.y << " " << ray.origin.z << " "
                      << ray.dir.x << " " << ray.dir.y << " " << ray.dir.z;
        return;
    }
    if (!exact && got) {
        ++tally.falseHits;
        ADD_FAILURE() << "false hit at t = " << *got << " (tolerance " << tc.name << ")";
        return;
    }
    if (!exact) return;
    // The allowed depth error along the unit ray: the tolerance, or for the automatic one
    // an eighth of the footprint's width at the hit (OctreeSettings::footprintFraction).
    const double allowed =
        (tc.automatic ? std::max(tc.tolerance, 0.125 * kFootprintSpread * *exact)
                      : tc.tolerance) *
            (1 + 1e-6) +
        1e-12;
    if (!(std::abs(*got - *exact) <= allowed)) {
        ++tally.wrongDepth;
        ADD_FAILURE() << "root at " << *got << ", exact " << *exact << " (tolerance "
                      << tc.name << ") ray " << ray.origin.x << " " << ray.origin.y << " "
                      << ray.origin.z << " " << ray.dir.x << " " << ray.dir.y << " "
                      << ray.dir.z;
    }
}

// A unit vector orthogonal to d.
Vec3 Orthogonal(const Vec3& d) {
    const Vec3 a = std::abs(d.x) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
    return Normalize(Cross(d, a));
}

// Sweeps `families` eye and `families` secondary ray families across the seam of each pair
// of kinds, in both blend modes, and checks every seam ray at five offsets.
Tally SweepSeams(int families) {
    Tally tally;
    Rng rng(20261201);
    const double offsets[] = {0, 1e-12, -1e-12, 1e-9, -1e-9};
    for (int kindA = 0; kindA < kKinds; ++kindA) {
        for (int kindB = kindA; kindB < kKinds; ++kindB) {
            for (BlendMode mode : {BlendMode::Automatic, BlendMode::Explicit}) {
                const Frame fa = RandomFrame(rng), fb = RandomFrame(rng);
                const Vec3 ca{-0.5, 0, 0}, cb{0.5, 0, 0};
                // Automatic: one quadratic kernel for both (the minimal case);
                // declared blend: a linear kernel against a quadratic one, so the seam is
                // not where the two distances are equal.
                const Kernel kernelA = mode == BlendMode::Automatic
                                           ? Kernel::GascuelQuadratic(0.6, 1.5, 1.2)
                                           : Kernel::GascuelLinear(0.55, 1.2, 1.3);
                const Kernel kernelB = Kernel::GascuelQuadratic(0.6, 1.5, 1.2);
                const SeamScene scene(
                    {{"a", SkeletonAround(kindA, ca, fa.u, fa.v, fa.w), kernelA, 1},
                     {"b", SkeletonAround(kindB, cb, fb.u, fb.v, fb.w), kernelB, 1}},
                    mode);
                std::vector<std::vector<LGOctree>> trees;
                for (const ToleranceCase& tc : kToleranceCases) {
                    OctreeSettings settings;
                    settings.tolerance = tc.tolerance;
                    settings.minWidth = tc.tolerance;
                    settings.autoTolerance = tc.automatic;
                    trees.push_back(scene.Trees(settings));
                }
                int found = 0;
                for (int attempt = 0; found < 2 * families && attempt < 40 * families;
                     ++attempt) {
                    const bool secondary = found >= families;
                    RayFamily family;
                    if (secondary) {
                        // From inside A (its centre, on or near the skeleton), out through
                        // the neck between the parts.
                        family = {ca + testing::RandomPoint(rng, -0.05, 0.05),
                                  Vec3{0, 0, 0} + testing::RandomPoint(rng, -0.4, 0.4),
                                  cb + testing::RandomPoint(rng, -0.4, 0.4), 1e-5};
                        family.qb = family.qb + testing::RandomUnit(rng) * 0.8;
                    } else {
                        family = {testing::RandomUnit(rng) * 4,
                                  ca + testing::RandomPoint(rng, -0.3, 0.3),
                                  cb + testing::RandomPoint(rng, -0.3, 0.3), 0};
                    }
                    const std::optional<double> seam = SeamOf(scene, family);
                    if (!seam) continue;
                    ++found;
                    const Ray ray = family.At(*seam);
                    const Vec3 side = Orthogonal(ray.dir);
                    for (double offset : offsets) {
                        Ray shifted = ray;
                        shifted.origin = ray.origin + side * (offset * kSceneSize);
                        const std::optional<double> exact = scene.Exact(shifted, family.tMin);
                        for (size_t c = 0; c < std::size(kToleranceCases); ++c) {
                            CheckRay(scene, trees[c], kToleranceCases[c], shifted, family.tMin,
                                     exact, tally);
                        }
                    }
                }
                EXPECT_EQ(found, 2 * families)
                    << "too few seam rays for kinds " << kindA << ", " << kindB;
            }
        }
    }
    return tally;
}

// 28 pairs of kinds × 2 blend modes × 2·60 seam rays × 5 offsets × 3 tolerances = 100,800.
TEST(Seams, NoRootLostAtPatchSeams) {
    const Tally tally = SweepSeams(60);
    EXPECT_GE(tally.rays, 100000);
    EXPECT_EQ(tally.lost, 0);
    EXPECT_EQ(tally.falseHits, 0);
    EXPECT_EQ(tally.wrongDepth, 0);
    std::printf("seam rays %ld: lost %ld, false hits %ld, wrong depth %ld\n", tally.rays,
                tally.lost, tally.falseHits, tally.wrongDepth);
}

// The minimal case: two quadratic points, one ray through the plane x = 0, where
// both patches rejected their roots before the seam rule.
TEST(Seams, MinimalCaseOnTheMidPlane) {
    const SeamScene scene({{"a", PointSkeleton{{-0.5, 0, 0}}, Kernel::GascuelQuadratic(0.6, 1.5, 1.2), 1},
                           {"b", PointSkeleton{{0.5, 0, 0}}, Kernel::GascuelQuadratic(0.6, 1.5, 1.2), 1}},
                          BlendMode::Automatic);
    const Ray ray{{-2.423521488664322, 2.0929282836720935, -1.0700833416550681},
                  {0.8078404962214455, -0.4692150935213818, 0.3566944472183573},
                  0};
    const std::optional<double> exact = scene.Exact(ray, 0);
    ASSERT_TRUE(exact.has_value());
    EXPECT_NEAR(*exact, 3.0, 1e-9);
    const std::optional<double> got = scene.Patches(scene.Trees(OctreeSettings{}), ray, 0);
    ASSERT_TRUE(got.has_value());
    EXPECT_NEAR(*got, *exact, 1e-7);
}

// PredominatesNear against its closed form: two equal points at x = ∓0.5, p at distance δ
// beyond the mid-plane on B's side. The rival's lead is c_b − c_a = f(0.5 − δ) − f(0.5 + δ)
// ≈ 2δ·|f'(0.5)|, under the slack 2·max|f'|·u for any uncertainty u >= δ, above it for u
// well below δ·|f'(0.5)|/max|f'|.
TEST(Seams, PredominatesNearMatchesTheLipschitzSlack) {
    const Kernel k = Kernel::GascuelQuadratic(0.6, 1.5, 1.2);
    std::vector<Patch> patches =
        BuildPatches(Field({{"a", PointSkeleton{{-0.5, 0, 0}}, k, 1},
                            {"b", PointSkeleton{{0.5, 0, 0}}, k, 1}}),
                     BlendMode::Automatic);
    ASSERT_EQ(patches.size(), 2u);
    const double maxSlope = k.Bounds(0, k.Radius()).maxSlope;
    const double slopeHere = std::abs(k.Derivative(0.5));
    for (double delta : {1e-9, 1e-6, 1e-3}) {
        const Vec3 p{delta, 0.1, 0};
        EXPECT_FALSE(patches[0].Predominates(p));
        EXPECT_TRUE(patches[0].PredominatesNear(p, delta)) << delta;
        EXPECT_TRUE(patches[0].PredominatesNear(p, 1.5 * delta)) << delta;
        EXPECT_FALSE(patches[0].PredominatesNear(p, 0.5 * delta * slopeHere / maxSlope))
            << delta;
        EXPECT_TRUE(patches[1].PredominatesNear(p, 0));
    }
}

}  // namespace
}  // namespace rs
