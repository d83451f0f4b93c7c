// Axis-aligned bounding boxes.
#pragma once

#include <limits>

#include "libcommon/ray.h"

namespace rs {

struct Bounds3 {
    // The default box is empty (lo > hi) so that Union() with it is the identity.
    Vec3 lo{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
            std::numeric_limits<double>::infinity()};
    Vec3 hi{-std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
            -std::numeric_limits<double>::infinity()};

    Bounds3() = default;
    Bounds3(const Vec3& a, const Vec3& b) : lo(Min(a, b)), hi(Max(a, b)) {}

    bool IsEmpty() const { return lo.x > hi.x || lo.y > hi.y || lo.z > hi.z; }
    Vec3 Center() const { return (lo + hi) * 0.5; }
    Vec3 Extent() const { return hi - lo; }
    Vec3 Corner(int i) const {
        return {(i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z};
    }
    bool Contains(const Vec3& p) const {
        return p.x >= lo.x && p.x <= hi.x && p.y >= lo.y && p.y <= hi.y && p.z >= lo.z &&
               p.z <= hi.z;
    }
    // Whether p lies inside the box and on none of its faces.
    bool ContainsStrictly(const Vec3& p) const {
        return p.x > lo.x && p.x < hi.x && p.y > lo.y && p.y < hi.y && p.z > lo.z && p.z < hi.z;
    }
    void Extend(const Vec3& p) { lo = Min(lo, p); hi = Max(hi, p); }
    void Extend(const Bounds3& b) { lo = Min(lo, b.lo); hi = Max(hi, b.hi); }
    Bounds3 Padded(double d) const {
        Bounds3 b = *this;
        b.lo -= Vec3{d, d, d};
        b.hi += Vec3{d, d, d};
        return b;
    }

    // Clips the parametric range [tMin, tMax] of `ray` to the box (slab test). Returns false
    // when the clipped range is empty, leaving tMin and tMax untouched. Works with non-unit
    // and axis-parallel directions (IEEE infinities from 1/0 give the right answer; NaN from
    // 0·inf is rejected).
    bool ClipRay(const Ray& ray, double& tMin, double& tMax) const {
        // The reciprocals come first, so the three divisions overlap instead of each
        // waiting for the previous axis's test.
        const Vec3 invDir{1.0 / ray.dir.x, 1.0 / ray.dir.y, 1.0 / ray.dir.z};
        return ClipSegment(ray, invDir, tMin, tMax);
    }

    // ClipRay given the reciprocal direction `invDir` (computed once per ray by callers
    // testing many boxes).
    bool ClipSegment(const Ray& ray, const Vec3& invDir, double& tMin, double& tMax) const {
        double near = tMin, far = tMax;
        for (int axis = 0; axis < 3; ++axis) {
            double t0 = (lo[axis] - ray.origin[axis]) * invDir[axis];
            double t1 = (hi[axis] - ray.origin[axis]) * invDir[axis];
            if (t0 > t1) std::swap(t0, t1);
            if (t0 > near) near = t0;  // comparisons written so NaN leaves the range alone
            if (t1 < far) far = t1;
            if (near > far) return false;
        }
        tMin = near;
        tMax = far;
        return true;
    }

    // Whether the segment (tMin, tMax) of `ray` meets the box (ClipSegment without the
    // clipped range). NaN (0·∞ on a slab plane) leaves the range alone, so such a box is
    // admitted.
    bool MeetsSegment(const Ray& ray, const Vec3& invDir, double tMin, double tMax) const {
        return ClipSegment(ray, invDir, tMin, tMax);
    }
};

inline Bounds3 Union(const Bounds3& a, const Bounds3& b) {
    Bounds3 r = a;
    r.Extend(b);
    return r;
}

inline Bounds3 Intersection(const Bounds3& a, const Bounds3& b) {
    Bounds3 r;
    r.lo = Max(a.lo, b.lo);
    r.hi = Min(a.hi, b.hi);
    return r;
}

}  // namespace rs
