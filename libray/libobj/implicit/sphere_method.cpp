#include "libobj/implicit/sphere_method.h"

#include <algorithm>
#include <cmath>

namespace rs {

SphereMethod::SphereMethod(const Field& field, const MethodParams& params)
    : field_(field),
      threshold_(params.threshold),
      tolerance_(params.tolerance),
      box_(PositiveSupportBounds(field)) {
    if (!box_.IsEmpty()) lipschitz_ = field.Bound(field.SupportBounds()).L;
}

std::optional<double> SphereMethod::FirstRoot(const Ray& ray, double tMin, double tMax) const {
    double t0 = tMin, t1 = tMax;
    if (!box_.ClipRay(ray, t0, t1)) return std::nullopt;
    const RayField g{field_, ray, threshold_};
    const double length = Length(ray.dir);
    const double lt = lipschitz_ * length, tolT = tolerance_ / length;
    double t = t0, gt = g(t);
    for (int step = 0; step < kMaxSteps && t < t1; ++step) {
        // |g|/Lt is safe (no root strictly before it); below the tolerance, step by it.
        double dt = lt > 0 ? std::abs(gt) / lt : t1 - t;
        dt = std::max(dt, tolT);
        double tn = NextSample(t, dt, t1);
        double gn = g(tn);
        if (std::optional<double> root = RootOfStep(g, t, gt, tn, gn, tolT, tMin, tMax))
            return root;
        t = tn;
        gt = gn;
    }
    return std::nullopt;
}

}  // namespace rs
