#include "libobj/implicit/march_method.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rs {

double DefaultMarchStep(const Field& field) {
    double smallest = std::numeric_limits<double>::infinity();
    const FieldMotion* motion = field.Motion();
    for (size_t i = 0; i < field.Terms().size(); ++i) {
        const FieldTerm& t = field.Terms()[i];
        if (t.weight <= 0) continue;
        // An animated kernel: its smallest thickness and radius over the shutter.
        const TermMotion* moves = motion ? &motion->Of(static_cast<int>(i)) : nullptr;
        const Kernel& k = moves && moves->kernelMoves ? moves->kernels.Lo() : t.kernel;
        smallest = std::min(smallest, k.Kind() == KernelKind::Blob ? 0.5 * k.Radius()
                                                                   : k.Thickness());
    }
    return smallest < std::numeric_limits<double>::infinity() ? 0.25 * smallest : 1.0;
}

MarchMethod::MarchMethod(const Field& field, const MethodParams& params)
    : field_(field),
      threshold_(params.threshold),
      tolerance_(params.tolerance),
      step_(params.step > 0 ? params.step : DefaultMarchStep(field)),
      box_(PositiveSupportBounds(field)) {}

std::optional<double> MarchMethod::FirstRoot(const Ray& ray, double tMin, double tMax) const {
    double t0 = tMin, t1 = tMax;
    if (!box_.ClipRay(ray, t0, t1)) return std::nullopt;
    const RayField g{field_, ray, threshold_};
    const double length = Length(ray.dir);
    const double h = step_ / length, tolT = tolerance_ / length;
    double ta = t0, ga = g(ta);
    while (ta < t1) {
        // The next sample; the clipped end is always sampled, and a step too small to move
        // a double moves to the next representable t instead.
        double tb = NextSample(ta, h, t1);
        double gb = g(tb);
        if (std::optional<double> root = RootOfStep(g, ta, ga, tb, gb, tolT, tMin, tMax))
            return root;
        ta = tb;
        ga = gb;
    }
    return std::nullopt;
}

}  // namespace rs
