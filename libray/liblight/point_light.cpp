#include "liblight/point_light.h"

#include "liblight/lights.h"

namespace rs {

bool PointLight::Sample(const Vec3& x, int, int, Rng&, LightSample& out) const {
    return SampleFromPoint(x, position_, intensity, out);
}

LightList CreatePointLight(ArgReader& args, const Color& intensity) {
    Vec3 p = args.ReadVector();
    return {std::make_shared<PointLight>(intensity, p)};
}

}  // namespace rs
