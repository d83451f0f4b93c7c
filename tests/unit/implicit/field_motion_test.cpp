// Swept bounds of a moving field (field_motion.h) against dense sampling over space and
// time: random skeletons of every kind translated at random velocities during [0, 1]
// (reference at 0.5, reach |v|/2: the exact Hausdorff distance of a translation; a point's
// centre box, the box of the segment it sweeps), with weights varying by ±15% and, for
// half the terms, kernels of every kind whose parameters change by up to ±30% (their
// KernelBox). Every box function must hold at every sampled (point, time),
// and point evaluations at a ray time must equal the static field of that time, bit for
// bit.
#include "libobj/implicit/field.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "libcommon/error.h"
#include "test_util.h"

namespace rs {
namespace {

using testing::Uniform;

// The skeleton moved by `offset` (every defining point; radii and normals kept).
Skeleton Translated(Skeleton s, const Vec3& offset) {
    std::visit(
        [&](auto& k) {
            using K = std::decay_t<decltype(k)>;
            if constexpr (std::is_same_v<K, PointSkeleton>) {
                k.center += offset;
            } else if constexpr (std::is_same_v<K, PolylineSkeleton>) {
                for (Vec3& p : k.points) p += offset;
            } else if constexpr (std::is_same_v<K, CircleSkeleton>) {
                k.center += offset;
            } else if constexpr (std::is_same_v<K, TriangleSkeleton>) {
                k.a += offset, k.b += offset, k.c += offset;
            } else if constexpr (std::is_same_v<K, BoxSkeleton>) {
                k.lo += offset, k.hi += offset;
            } else {
                k.a += offset, k.b += offset;
            }
        },
        s);
    return s;
}

// The kernel of a's kind whose every parameter goes linearly from a's (u = 0) to b's (u = 1).
Kernel KernelBetween(const Kernel& a, const Kernel& b, double u) {
    const auto mix = [u](double x, double y) { return x + (y - x) * u; };
    const double radius = mix(a.Radius(), b.Radius());
    if (a.Kind() == KernelKind::Blob) return Kernel::Blob(mix(a.Strength(), b.Strength()), radius);
    const double e = mix(a.Thickness(), b.Thickness()), k = mix(a.Stiffness(), b.Stiffness());
    return a.Kind() == KernelKind::GascuelLinear ? Kernel::GascuelLinear(e, k, radius)
                                                 : Kernel::GascuelQuadratic(e, k, radius);
}

// The box of the kernels between a and b: each parameter's smaller and larger value.
KernelBox BoxBetween(const Kernel& a, const Kernel& b) {
    Kernel lo = a, hi = b;
    if (a.Kind() == KernelKind::Blob) {
        lo = Kernel::Blob(std::min(a.Strength(), b.Strength()), std::min(a.Radius(), b.Radius()));
        hi = Kernel::Blob(std::max(a.Strength(), b.Strength()), std::max(a.Radius(), b.Radius()));
    } else {
        const auto make = [&](double e, double k, double r) {
            return a.Kind() == KernelKind::GascuelLinear ? Kernel::GascuelLinear(e, k, r)
                                                         : Kernel::GascuelQuadratic(e, k, r);
        };
        lo = make(std::min(a.Thickness(), b.Thickness()), std::min(a.Stiffness(), b.Stiffness()),
                  std::min(a.Radius(), b.Radius()));
        hi = make(std::max(a.Thickness(), b.Thickness()), std::max(a.Stiffness(), b.Stiffness()),
                  std::max(a.Radius(), b.Radius()));
    }
    return KernelBox(lo, hi);
}

struct MovingSet {
    std::vector<FieldTerm> reference;
    std::vector<Vec3> velocity;
    // Animated kernels: where kernelMoves[i], term i's kernel at t is
    // KernelBetween(kernelStart[i], kernelEnd[i], t) (the reference's at t = 0.5).
    std::vector<bool> kernelMoves;
    std::vector<Kernel> kernelStart, kernelEnd;
    // The terms at time t: reference skeletons moved by v(t − 0.5), weights w(1 + 0.3(t − 0.5)).
    std::vector<FieldTerm> At(double t) const {
        std::vector<FieldTerm> out = reference;
        for (size_t i = 0; i < out.size(); ++i) {
            out[i].skeleton = Translated(reference[i].skeleton, velocity[i] * (t - 0.5));
            out[i].weight = reference[i].weight * (1 + 0.3 * (t - 0.5));
            if (kernelMoves[i]) out[i].kernel = KernelBetween(kernelStart[i], kernelEnd[i], t);
        }
        return out;
    }
    Field Moving() const {
        std::vector<TermMotion> motion(reference.size());
        for (size_t i = 0; i < reference.size(); ++i) {
            const double w = reference[i].weight;
            motion[i].moving = true;
            motion[i].reach = 0.5 * Length(velocity[i]);
            motion[i].weightLo = std::min(0.85 * w, 1.15 * w);
            motion[i].weightHi = std::max(0.85 * w, 1.15 * w);
            // A point's centre sweeps the segment c ± v/2: its box (field_motion.h).
            if (const auto* point = std::get_if<PointSkeleton>(&reference[i].skeleton)) {
                motion[i].centreBoxed = true;
                motion[i].centres = Bounds3(point->center - velocity[i] * 0.5,
                                            point->center + velocity[i] * 0.5);
            }
            if (kernelMoves[i]) {
                motion[i].kernelMoves = true;
                motion[i].kernels = BoxBetween(kernelStart[i], kernelEnd[i]);
            }
        }
        auto at = [set = *this](int row, double t, FieldTerm& term) {
            const FieldTerm moved = set.At(t)[row];
            term.skeleton = moved.skeleton;
            term.weight = moved.weight;
            term.kernel = moved.kernel;
        };
        return Field(reference, std::make_shared<const FieldMotion>(motion, at));
    }
};

MovingSet RandomMovingSet(Rng& rng) {
    MovingSet set;
    const int n = 1 + static_cast<int>(rng.Uniform() * 4);
    for (int i = 0; i < n; ++i) {
        FieldTerm t;
        t.name = StringPrintf("t%d", i);
        t.skeleton = testing::RandomSkeleton(rng, static_cast<int>(rng.Uniform() * 7));
        const double e = Uniform(rng, 0.1, 0.5), r = e + Uniform(rng, 0.2, 0.8);
        t.kernel = Kernel::GascuelQuadratic(e, Uniform(rng, 0.1, 3.0 / (r - e)), r);
        t.weight = rng.Uniform() < 0.2 ? -Uniform(rng, 0.2, 1) : Uniform(rng, 0.5, 2);
        // Half the terms get a kernel of a random kind whose parameters change by up to
        // ±30 % during [0, 1], every corner of their box valid.
        const bool kernelMoves = rng.Uniform() < 0.5;
        Kernel start = t.kernel, end = t.kernel;
        while (kernelMoves) {
            const auto vary = [&](double v) { return v * Uniform(rng, 0.7, 1.3); };
            const int kind = static_cast<int>(rng.Uniform() * 3);
            const double e0 = Uniform(rng, 0.1, 0.5), r0 = e0 + Uniform(rng, 0.2, 0.8);
            const double k0 = Uniform(rng, 0.1, 3.0 / (r0 - e0));
            if (kind == 2) {
                start = Kernel::Blob(Uniform(rng, 0.5, 2), r0);
                end = Kernel::Blob(vary(start.Strength()), vary(r0));
            } else {
                const auto make = kind == 0 ? Kernel::GascuelLinear : Kernel::GascuelQuadratic;
                start = make(e0, k0, r0);
                end = make(vary(e0), vary(k0), vary(r0));
            }
            if (BoxBetween(start, end).Validate("t").ok) break;
        }
        if (kernelMoves) t.kernel = KernelBetween(start, end, 0.5);
        set.kernelMoves.push_back(kernelMoves);
        set.kernelStart.push_back(start);
        set.kernelEnd.push_back(end);
        set.reference.push_back(t);
        set.velocity.push_back(testing::RandomPoint(rng, -1.5, 1.5));
    }
    return set;
}

TEST(FieldMotion, SweptBoundsHoldAtEverySampledPointAndTime) {
    Rng rng(1419);
    int checked = 0;
    for (int trial = 0; trial < 150; ++trial) {
        const MovingSet set = RandomMovingSet(rng);
        const Field moving = set.Moving();
        for (int b = 0; b < 6; ++b) {
            const Bounds3 box = testing::RandomBox(rng, -2, 1.5, 0.8);
            const FieldBound fb = moving.Bound(box);
            std::vector<int32_t> active;
            moving.ActiveTerms(box, moving.Rows(), active);
            for (int s = 0; s < 60; ++s) {
                const double t = s == 0 ? 0 : s == 1 ? 1 : rng.Uniform();
                const Field still(set.At(t));
                const Vec3 p = testing::RandomInBox(rng, box);
                const RayTimeScope time(t);
                const double v = moving.Value(p);
                ASSERT_EQ(v, still.Value(p));  // the ray's time, bit for bit
                if (s < 4) {
                    // The bound at the ray's time is the static field's at that time.
                    const FieldBound now = moving.BoundAtRayTime(box), st = still.Bound(box);
                    EXPECT_EQ(now.valueMin, st.valueMin);
                    EXPECT_EQ(now.valueMax, st.valueMax);
                    EXPECT_EQ(now.L, st.L);
                    EXPECT_EQ(now.G, st.G);
                    // Likewise each term's range (the predominance exclusion of the search).
                    for (int i = 0; i < moving.Size(); ++i) {
                        double lo, hi, stLo, stHi;
                        moving.TermRangeAtRayTime(i, box, lo, hi);
                        still.TermRange(i, box, stLo, stHi);
                        EXPECT_EQ(lo, stLo);
                        EXPECT_EQ(hi, stHi);
                    }
                }
                const double slack = 1e-9 * (1 + std::abs(v));
                EXPECT_GE(v, fb.valueMin - slack);
                EXPECT_LE(v, fb.valueMax + slack);
                EXPECT_LE(Length(moving.Gradient(p)), fb.L + 1e-9);
                double atLo, atHi;
                moving.ValueRangeAt(p, moving.Rows(), atLo, atHi);
                EXPECT_GE(v, atLo - slack);
                EXPECT_LE(v, atHi + slack);
                for (int i = 0; i < moving.Size(); ++i) {
                    const double tv = moving.TermValue(i, p);
                    double lo, hi;
                    moving.TermRange(i, box, lo, hi);
                    EXPECT_GE(tv, lo - 1e-12);
                    EXPECT_LE(tv, hi + 1e-12);
                    if (tv != 0) {
                        EXPECT_TRUE(moving.TermSupport(i).Contains(p));
                        EXPECT_NE(std::find(active.begin(), active.end(), i), active.end());
                        // Within the reference's radius plus TermReach of its skeleton.
                        const FieldTerm& ref = moving.Terms()[i];
                        EXPECT_LT(SkeletonDistance(ref.skeleton, p),
                                  ref.kernel.Radius() + moving.TermReach(i));
                    }
                    // TermLipschitz, along a short step from p at this time.
                    const Vec3 q = p + testing::RandomUnit(rng) * 1e-3;
                    EXPECT_LE(std::abs(moving.TermValue(i, q) - tv),
                              moving.TermLipschitz(i) * 1e-3 * (1 + 1e-9) + 1e-12);
                }
                ++checked;
            }
        }
    }
    EXPECT_GT(checked, 50000);
}

// The second directional derivative along random lines, by central differences, stays
// within G wherever G is finite (boxes away from the skeletons' kinks).
TEST(FieldMotion, SweptCurvatureBoundHolds) {
    Rng rng(77);
    int finite = 0;
    for (int trial = 0; trial < 150; ++trial) {
        const MovingSet set = RandomMovingSet(rng);
        const Field moving = set.Moving();
        const Bounds3 box = testing::RandomBox(rng, -2, 1.5, 0.5);
        const FieldBound fb = moving.Bound(box);
        if (!std::isfinite(fb.G)) continue;
        ++finite;
        const double h = 1e-4;
        for (int s = 0; s < 40; ++s) {
            const RayTimeScope time(rng.Uniform());
            const Vec3 u = testing::RandomUnit(rng);
            const Vec3 p = testing::RandomInBox(rng, box.Padded(-h));
            if (!box.Contains(p + u * h) || !box.Contains(p - u * h)) continue;
            const double second =
                (moving.Value(p + u * h) - 2 * moving.Value(p) + moving.Value(p - u * h)) / (h * h);
            EXPECT_LE(std::abs(second), fb.G * (1 + 1e-3) + 1e-3);
        }
    }
    EXPECT_GT(finite, 30);
}

TEST(FieldMotion, NoRayTimeMeansTheReferenceTerms) {
    Rng rng(5);
    const MovingSet set = RandomMovingSet(rng);
    const Field moving = set.Moving();
    const Field reference(set.reference);
    for (int s = 0; s < 100; ++s) {
        const Vec3 p = testing::RandomPoint(rng, -1.5, 1.5);
        EXPECT_EQ(moving.Value(p), reference.Value(p));
        const RayTimeScope none(kNoRayTime);
        EXPECT_EQ(moving.Value(p), reference.Value(p));
    }
}

}  // namespace
}  // namespace rs
