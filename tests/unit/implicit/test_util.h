// Shared helpers of the implicit unit tests: seeded random points, boxes, skeletons.
#pragma once

#include <cstdint>

#include "libcommon/random.h"
#include "libobj/implicit/skeleton.h"

namespace rs::testing {

inline double Uniform(Rng& rng, double lo, double hi) { return lo + (hi - lo) * rng.Uniform(); }

inline Vec3 RandomPoint(Rng& rng, double lo, double hi) {
    return {Uniform(rng, lo, hi), Uniform(rng, lo, hi), Uniform(rng, lo, hi)};
}

inline Vec3 RandomInBox(Rng& rng, const Bounds3& box) {
    return {Uniform(rng, box.lo.x, box.hi.x), Uniform(rng, box.lo.y, box.hi.y),
            Uniform(rng, box.lo.z, box.hi.z)};
}

inline Vec3 RandomUnit(Rng& rng) {
    for (;;) {
        Vec3 v = RandomPoint(rng, -1, 1);
        double l2 = LengthSquared(v);
        if (l2 > 1e-4 && l2 <= 1) return v / std::sqrt(l2);
    }
}

// A box with corners in [lo, hi]³ and edges of at most `maxEdge`.
inline Bounds3 RandomBox(Rng& rng, double lo, double hi, double maxEdge) {
    Vec3 a = RandomPoint(rng, lo, hi);
    Vec3 e{Uniform(rng, 0.01, maxEdge), Uniform(rng, 0.01, maxEdge), Uniform(rng, 0.01, maxEdge)};
    return Bounds3(a, a + e);
}

// One skeleton of kind `kind` (the variant index) with random parameters around the origin.
inline Skeleton RandomSkeleton(Rng& rng, int kind) {
    switch (kind) {
        case 0:
            return PointSkeleton{RandomPoint(rng, -1, 1)};
        case 1:
            return SegmentSkeleton{RandomPoint(rng, -1, 1), RandomPoint(rng, -1, 1)};
        case 2: {
            PolylineSkeleton p;
            int n = 2 + static_cast<int>(rng.Uniform() * 4);
            for (int i = 0; i < n; ++i) p.points.push_back(RandomPoint(rng, -1, 1));
            return p;
        }
        case 3:
            return CircleSkeleton{RandomPoint(rng, -0.5, 0.5), RandomUnit(rng),
                                  Uniform(rng, 0.2, 1)};
        case 4:
            return TriangleSkeleton{RandomPoint(rng, -1, 1), RandomPoint(rng, -1, 1),
                                    RandomPoint(rng, -1, 1)};
        case 5: {
            Vec3 a = RandomPoint(rng, -1, 0.5);
            return BoxSkeleton{a, a + RandomPoint(rng, 0.05, 0.8)};
        }
        default:
            return CylinderSkeleton{RandomPoint(rng, -1, 1), RandomPoint(rng, -1, 1),
                                    Uniform(rng, 0.05, 0.5)};
    }
}

inline constexpr int kSkeletonKinds = 7;

}  // namespace rs::testing
