#include "liblight/point_light.h"

#include "liblight/lights.h"

namespace rs {

bool PointLight::Sample(const Vec3& x, int, int, Rng&, LightSample& out) const {
    Vec3 d = position_ - x;
    double dist = Length(d);
    if (!(dist > 0)) return false;
    out.shadeDir = out.shadowDir = d / dist;
    out.shadowDist = dist;
    out.color = intensity;
    return true;
}

LightList CreatePointLight(ArgReader& args, const Color& intensity) {
    Vec3 p = args.ReadVector();
    return {std::make_shared<PointLight>(intensity, p)};
}

}  // namespace rs
