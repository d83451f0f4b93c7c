#include "liblight/spot_light.h"

#include <cmath>

#include "libcommon/constants.h"
#include "liblight/lights.h"

namespace rs {

SpotLight::SpotLight(const Color& i, const Vec3& from, const Vec3& at, double coef,
                     double innerDeg, double outerDeg)
    : position_(from), axis_(Normalize(at - from)), coef_(coef),
      cosInner_(std::cos(innerDeg * kPi / 180)), cosOuter_(std::cos(outerDeg * kPi / 180)) {
    intensity = i;
}

bool SpotLight::Sample(const Vec3& x, int, int, Rng&, LightSample& out) const {
    if (!SampleFromPoint(x, position_, intensity, out)) return false;

    double cosPhi = -Dot(out.shadeDir, axis_);
    if (cosPhi <= 0) return false;
    double atten = std::pow(cosPhi, coef_);
    if (cosInner_ > 0) {
        // Smoothstep between the outer and inner cone edges.
        if (cosPhi < cosOuter_) return false;
        if (cosPhi <= cosInner_) {
            if (cosInner_ == cosOuter_) return false;
            double t = (cosPhi - cosOuter_) / (cosInner_ - cosOuter_);
            atten *= t * t * (3 - 2 * t);
        }
    }
    if (!(atten > 0)) return false;
    out.color = intensity * atten;
    return true;
}

LightList CreateSpotLight(ArgReader& args, const Color& intensity) {
    Vec3 from = args.ReadVector();
    Vec3 at = args.ReadVector();
    double coef = args.ReadNumber();
    double inner = 180, outer = 180;
    if (args.PeekNumber()) {
        inner = args.ReadNumber();
        outer = args.ReadNumber();
    }
    if (!(Length(at - from) > 0)) args.Fail("spot light with a zero axis (from == at)");
    if (inner > outer) args.Fail("spot light inner angle exceeds its outer angle");
    return {std::make_shared<SpotLight>(intensity, from, at, coef, inner, outer)};
}

}  // namespace rs
