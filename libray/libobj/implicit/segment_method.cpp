#include "libobj/implicit/segment_method.h"

#include <algorithm>
#include <cmath>

namespace rs {

SegmentMethod::SegmentMethod(const Field& field, const MethodParams& params)
    : field_(field),
      threshold_(params.threshold),
      tolerance_(params.tolerance),
      box_(PositiveSupportBounds(field)) {}

std::optional<double> SegmentMethod::FirstRoot(const Ray& ray, double tMin, double tMax) const {
    double t0 = tMin, t1 = tMax;
    if (!box_.ClipRay(ray, t0, t1)) return std::nullopt;
    const RayField g{field_, ray, threshold_};
    const double length = Length(ray.dir);
    const double tolT = tolerance_ / length;
    double t = t0, gt = g(t), sigma = t1 - t0;
    for (int step = 0; step < kMaxSteps && t < t1; ++step) {
        sigma = std::min(sigma, t1 - t);
        double k = field_.Bound(Bounds3(ray.At(t), ray.At(t + sigma))).L * length;
        double dt = k > 0 ? std::min(std::abs(gt) / k, sigma) : sigma;
        dt = std::max(dt, tolT);
        double tn = NextSample(t, dt, t1);
        double gn = g(tn);
        if (std::optional<double> root = RootOfStep(g, t, gt, tn, gn, tolT, tMin, tMax))
            return root;
        sigma = kGrowth * (tn - t);
        t = tn;
        gt = gn;
    }
    return std::nullopt;
}

}  // namespace rs
