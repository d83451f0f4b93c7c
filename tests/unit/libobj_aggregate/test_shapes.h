// Small analytic primitives for the aggregate tests (test code only): a sphere, an axis box,
// the plane z = 0 and a probe that records the order it is tested in.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "libobj/primitive.h"

namespace rs::testing {

class TestSphere final : public Primitive {
  public:
    TestSphere(const Vec3& center, double radius, const std::string& counterName = "TestSphere")
        : center_(center), radius_(radius), counters_(counterName) {}

    const IntersectionCounters& Counters() const override { return counters_; }
    Bounds3 Bounds() const override {
        const Vec3 r{radius_, radius_, radius_};
        return {center_ - r, center_ + r};
    }
    bool IsClosed() const override { return true; }

    // |o + t·d − c|² = r²: a·t² + 2·h·t + k = 0 with a = d·d, h = d·(o − c), k = |o − c|² − r².
    bool Intersect(const Ray& ray, double tMin, double tMax, PrimitiveHit& hit) const override {
        const Vec3 oc = ray.origin - center_;
        const double a = Dot(ray.dir, ray.dir);
        const double h = Dot(ray.dir, oc);
        const double k = Dot(oc, oc) - radius_ * radius_;
        const double disc = h * h - a * k;
        if (disc < 0) return false;
        const double root = std::sqrt(disc);
        const double roots[2] = {(-h - root) / a, (-h + root) / a};
        for (int i = 0; i < 2; ++i) {
            if (roots[i] > tMin && roots[i] < tMax) {
                hit.t = roots[i];
                hit.part = i;
                return true;
            }
        }
        return false;
    }

    SurfaceNormals Normal(const Vec3& p, const PrimitiveHit&) const override {
        const Vec3 n = Normalize(p - center_);
        return {n, n, false};
    }

    // The spec's geometric test for spheres: the ray enters iff it starts outside.
    bool Enters(const Ray& ray, const PrimitiveHit&, const SurfaceNormals&) const override {
        return LengthSquared(ray.origin - center_) > radius_ * radius_;
    }

  private:
    Vec3 center_;
    double radius_;
    IntersectionCounters counters_;
};

class TestBox final : public Primitive {
  public:
    TestBox(const Vec3& lo, const Vec3& hi) : box_(lo, hi) {}

    const IntersectionCounters& Counters() const override {
        static const IntersectionCounters counters("TestBox");
        return counters;
    }
    Bounds3 Bounds() const override { return box_; }
    bool IsClosed() const override { return true; }

    // Slab test: the ray is inside the box for t in [tNear, tFar].
    bool Intersect(const Ray& ray, double tMin, double tMax, PrimitiveHit& hit) const override {
        double tNear = -INFINITY, tFar = INFINITY;
        for (int a = 0; a < 3; ++a) {
            if (ray.dir[a] == 0) {
                if (ray.origin[a] < box_.lo[a] || ray.origin[a] > box_.hi[a]) return false;
                continue;
            }
            double t0 = (box_.lo[a] - ray.origin[a]) / ray.dir[a];
            double t1 = (box_.hi[a] - ray.origin[a]) / ray.dir[a];
            if (t0 > t1) std::swap(t0, t1);
            tNear = std::max(tNear, t0);
            tFar = std::min(tFar, t1);
        }
        if (tNear > tFar) return false;
        if (tNear > tMin && tNear < tMax) {
            hit.t = tNear;
        } else if (tFar > tMin && tFar < tMax) {
            hit.t = tFar;
        } else {
            return false;
        }
        return true;
    }

    // The face nearest to p.
    SurfaceNormals Normal(const Vec3& p, const PrimitiveHit&) const override {
        int best = 0;
        double bestDist = INFINITY, sign = 1;
        for (int a = 0; a < 3; ++a) {
            for (int side = 0; side < 2; ++side) {
                const double d = std::abs(p[a] - (side ? box_.hi[a] : box_.lo[a]));
                if (d < bestDist) {
                    bestDist = d;
                    best = a;
                    sign = side ? 1 : -1;
                }
            }
        }
        Vec3 n;
        n[best] = sign;
        return {n, n, false};
    }

    bool Enters(const Ray& ray, const PrimitiveHit&, const SurfaceNormals&) const override {
        return !box_.Contains(ray.origin);
    }

  private:
    Bounds3 box_;
};

// The plane z = 0 (unbounded, normal +z).
class TestPlane final : public Primitive {
  public:
    const IntersectionCounters& Counters() const override {
        static const IntersectionCounters counters("TestPlane");
        return counters;
    }
    Bounds3 Bounds() const override { return {}; }
    bool IsBounded() const override { return false; }
    bool Intersect(const Ray& ray, double tMin, double tMax, PrimitiveHit& hit) const override {
        if (ray.dir.z == 0) return false;
        const double t = -ray.origin.z / ray.dir.z;
        if (!(t > tMin && t < tMax)) return false;
        hit.t = t;
        return true;
    }
    SurfaceNormals Normal(const Vec3&, const PrimitiveHit&) const override {
        return {{0, 0, 1}, {0, 0, 1}, false};
    }
};

// Never hits; appends its id to `log` each time it is tested.
class Probe final : public Primitive {
  public:
    Probe(int id, std::vector<int>* log, bool bounded, const Bounds3& box = {{-1, -1, -1}, {1, 1, 1}})
        : id_(id), log_(log), bounded_(bounded), box_(box) {}
    const IntersectionCounters& Counters() const override {
        static const IntersectionCounters counters("Probe");
        return counters;
    }
    Bounds3 Bounds() const override { return box_; }
    bool IsBounded() const override { return bounded_; }
    bool Intersect(const Ray&, double, double, PrimitiveHit&) const override {
        log_->push_back(id_);
        return false;
    }
    SurfaceNormals Normal(const Vec3&, const PrimitiveHit&) const override { return {}; }

  private:
    int id_;
    std::vector<int>* log_;
    bool bounded_;
    Bounds3 box_;
};

}  // namespace rs::testing
