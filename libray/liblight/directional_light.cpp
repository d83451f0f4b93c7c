#include "liblight/directional_light.h"

#include "libcommon/constants.h"
#include "liblight/lights.h"

namespace rs {

bool DirectionalLight::Sample(const Vec3&, int, int, Rng&, LightSample& out) const {
    out.shadeDir = out.shadowDir = dir_;
    out.shadowDist = kFar;
    out.color = intensity;
    return true;
}

LightList CreateDirectionalLight(ArgReader& args, const Color& intensity) {
    Vec3 v = args.ReadVector();
    if (!(Length(v) > 0)) args.Fail("directional light with a zero direction");
    return {std::make_shared<DirectionalLight>(intensity, v)};
}

}  // namespace rs
