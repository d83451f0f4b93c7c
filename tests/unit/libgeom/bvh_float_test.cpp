// The 4-wide single-precision walk of BoundingVolumeHierarchy against the exact double box
// tests: grazing rays, large coordinates, rays beyond single precision.
#include "libgeom/bvh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "libcommon/random.h"

namespace rs {
namespace {

double Uniform(Rng& rng, double lo, double hi) { return lo + (hi - lo) * rng.Uniform(); }

Vec3 RandomPoint(Rng& rng, const Vec3& centre, double spread) {
    return centre + Vec3{Uniform(rng, -spread, spread), Uniform(rng, -spread, spread),
                         Uniform(rng, -spread, spread)};
}

// Random boxes around `centre`: many small ones, a few large, some flat in an axis (as
// polygons' are) and some degenerate to a point; all with coordinates of size ~|centre|.
std::vector<Bounds3> RandomBoxes(Rng& rng, const Vec3& centre, double spread, int count) {
    std::vector<Bounds3> boxes;
    for (int i = 0; i < count; ++i) {
        const Vec3 c = RandomPoint(rng, centre, spread);
        const double size = rng.Uniform() < 0.05 ? spread * 0.5 : spread * 0.02;
        Vec3 h{Uniform(rng, 0, size), Uniform(rng, 0, size), Uniform(rng, 0, size)};
        if (i % 5 == 1) h[i % 3] = 0;
        if (i % 17 == 3) h = {0, 0, 0};
        boxes.push_back({c - h, c + h});
    }
    return boxes;
}

// A ray from near the boxes (sometimes from inside one, on one's face, or along an axis)
// through their region.
Ray RandomRay(Rng& rng, const std::vector<Bounds3>& boxes, const Vec3& centre, double spread) {
    Ray ray;
    const double pick = rng.Uniform();
    const Bounds3& box = boxes[static_cast<size_t>(rng.Uniform() * boxes.size()) % boxes.size()];
    if (pick < 0.2) {
        ray.origin = box.Center();
    } else if (pick < 0.3) {
        ray.origin = box.Center();
        ray.origin.x = box.lo.x;  // on a face plane
    } else {
        ray.origin = RandomPoint(rng, centre, 2 * spread);
    }
    // Aimed near the box's centre, or exactly at a point of one of its edges (grazing
    // rays, where rounding decides).
    const double aim = rng.Uniform();
    Vec3 target = RandomPoint(rng, box.Center(), spread * 0.05);
    if (aim < 0.4) {
        target = box.Corner(static_cast<int>(rng.Uniform() * 8) & 7);
        const int a = static_cast<int>(rng.Uniform() * 3) % 3;
        target[a] = Uniform(rng, box.lo[a], box.hi[a]);
    }
    ray.dir = target - ray.origin;
    for (int a = 0; a < 3; ++a) {
        if (rng.Uniform() < 0.1) ray.dir[a] = 0;
    }
    if (LengthSquared(ray.dir) == 0) ray.dir = {0, 0, 1};
    // Non-unit lengths, as in object spaces.
    ray.dir = ray.dir * Uniform(rng, 0.01, 100) / std::sqrt(LengthSquared(ray.dir));
    return ray;
}

// Every box whose exact (double) slab test meets the segment must be visited, and no item
// more than once; for scenes near the origin, far from it (coordinates ~3e4, where
// single precision keeps ~0.002 units) and tiny ones.
TEST(BoundingVolumeHierarchy, VisitsEveryBoxTheSegmentMeetsOnce) {
    const Vec3 centres[] = {{0, 0, 0}, {1e4, -3e4, 3e3}, {0.001, 0.002, -0.001}};
    const double spreads[] = {10, 1, 1e-3};
    long met = 0;
    for (int scene = 0; scene < 3; ++scene) {
        for (uint64_t seed = 1; seed <= 6; ++seed) {
            Rng rng(seed * 31 + scene);
            const auto boxes = RandomBoxes(rng, centres[scene], spreads[scene],
                                           5 + static_cast<int>(rng.Uniform() * 400));
            for (const auto split : {BoundingVolumeHierarchy::Split::Median,
                                     BoundingVolumeHierarchy::Split::SurfaceArea}) {
                BoundingVolumeHierarchy bvh;
                bvh.Build(boxes, split);
                for (int r = 0; r < 300; ++r) {
                    const Ray ray = RandomRay(rng, boxes, centres[scene], spreads[scene]);
                    const double tMin = rng.Uniform() < 0.5 ? 0 : 1e-3;
                    double tMax = rng.Uniform() < 0.5 ? 1e30 : Uniform(rng, 0.1, 2);
                    const double tMaxBefore = tMax;
                    std::vector<int> visits(boxes.size(), 0);
                    bvh.Traverse(ray, tMin, tMax, [&](int i) {
                        ++visits[i];
                        return false;
                    });
                    EXPECT_EQ(tMax, tMaxBefore);
                    const Vec3 inv{1 / ray.dir.x, 1 / ray.dir.y, 1 / ray.dir.z};
                    for (size_t i = 0; i < boxes.size(); ++i) {
                        ASSERT_LE(visits[i], 1) << "item " << i << " visited twice";
                        if (boxes[i].MeetsSegment(ray, inv, tMin, tMax)) {
                            ++met;
                            ASSERT_EQ(visits[i], 1) << "scene " << scene << " seed " << seed
                                                    << " ray " << r << " lost box " << i;
                        }
                    }
                }
            }
        }
    }
    // (Items sharing a leaf with a met one are visited too, so extra visits are not a fault.)
    EXPECT_GT(met, 5000);
}

// Spheres as items: the nearest hit through Traverse (shrinking tMax) and the occlusion
// answer (kStopAtFirstHit) equal a brute-force loop's.
TEST(BoundingVolumeHierarchy, NearestHitAndOcclusionAgreeWithBruteForce) {
    long hits = 0;
    for (uint64_t seed = 1; seed <= 20; ++seed) {
        Rng rng(seed);
        const Vec3 centre = seed % 2 ? Vec3{0, 0, 0} : Vec3{-3e4, 5e4, 1e4};
        std::vector<Vec3> centres;
        std::vector<double> radii;
        std::vector<Bounds3> boxes;
        const int count = 5 + static_cast<int>(rng.Uniform() * 300);
        for (int i = 0; i < count; ++i) {
            centres.push_back(RandomPoint(rng, centre, 10));
            radii.push_back(rng.Uniform() < 0.05 ? Uniform(rng, 1, 3) : Uniform(rng, 0.05, 0.4));
            const Vec3 r{radii.back(), radii.back(), radii.back()};
            boxes.push_back({centres.back() - r, centres.back() + r});
        }
        // Nearest root of |o + t d - c| = r above tMin, or none.
        const auto sphereHit = [&](const Ray& ray, int i, double tMin, double tMax, double& t) {
            const Vec3 oc = ray.origin - centres[i];
            const double a = LengthSquared(ray.dir), b = Dot(oc, ray.dir);
            const double disc = b * b - a * (LengthSquared(oc) - radii[i] * radii[i]);
            if (disc < 0) return false;
            const double s = std::sqrt(disc);
            for (const double root : {(-b - s) / a, (-b + s) / a}) {
                if (root > tMin && root < tMax) {
                    t = root;
                    return true;
                }
            }
            return false;
        };
        BoundingVolumeHierarchy bvh;
        bvh.Build(boxes, BoundingVolumeHierarchy::Split::SurfaceArea);
        for (int r = 0; r < 400; ++r) {
            const Ray ray = RandomRay(rng, boxes, centre, 10);
            const double tMin = 1e-6, tLimit = rng.Uniform() < 0.7 ? 1e30 : Uniform(rng, 0.1, 1);
            double bruteT = tLimit;
            int bruteItem = -1;
            for (int i = 0; i < count; ++i) {
                double t;
                if (sphereHit(ray, i, tMin, bruteT, t)) {
                    bruteT = t;
                    bruteItem = i;
                }
            }
            double tMax = tLimit;
            int item = -1;
            const bool found = bvh.Traverse(ray, tMin, tMax, [&](int i) {
                double t;
                if (!sphereHit(ray, i, tMin, tMax, t)) return false;
                tMax = t;
                item = i;
                return true;
            });
            ASSERT_EQ(found, bruteItem >= 0) << "seed " << seed << " ray " << r;
            double occlusionMax = tLimit;
            const bool occluded = bvh.Traverse<true>(ray, tMin, occlusionMax, [&](int i) {
                double t;
                return sphereHit(ray, i, tMin, tLimit, t);
            });
            EXPECT_EQ(occluded, found);
            if (!found) continue;
            ++hits;
            EXPECT_EQ(tMax, bruteT);
            EXPECT_EQ(item, bruteItem);
        }
    }
    EXPECT_GT(hits, 1000);
}

// Rays beyond single precision's range still find every box (the walk then visits all).
TEST(BoundingVolumeHierarchy, RaysBeyondSinglePrecisionVisitEveryBoxTheyMeet) {
    std::vector<Bounds3> boxes;
    for (int i = 0; i < 40; ++i) boxes.push_back({Vec3{i * 2.0, 0, 0}, Vec3{i * 2.0 + 1, 1, 1}});
    BoundingVolumeHierarchy bvh;
    bvh.Build(boxes, BoundingVolumeHierarchy::Split::SurfaceArea);
    // From 1e300 away along -x, and with a direction too long for a float reciprocal.
    for (const Ray& ray : {Ray{{1e300, 0.5, 0.5}, {-1, 0, 0}}, Ray{{-1, 0.5, 0.5}, {1e300, 0, 0}}}) {
        double tMax = 1e305;
        int visited = 0;
        bvh.Traverse(ray, 0, tMax, [&](int) {
            ++visited;
            return false;
        });
        EXPECT_EQ(visited, 40);
    }
}

}  // namespace
}  // namespace rs
