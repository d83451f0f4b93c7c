// Test double for the light factories of liblight/lights.h, linked into libshade_test only
// while liblight has no implementation (see CMakeLists.txt). Each factory reads exactly the
// arguments of its grammar rule (spec §2 `lighttype`) and returns lights that never shine.
#include "liblight/lights.h"

namespace rs {

namespace {

class FakeLight final : public Light {
  public:
    bool Sample(const Vec3&, int, int, Rng&, LightSample&) const override { return false; }
};

LightList One(const Color& intensity) {
    auto light = std::make_shared<FakeLight>();
    light->intensity = intensity;
    return {light};
}

}  // namespace

LightList CreatePointLight(ArgReader& args, const Color& intensity) {
    args.ReadVector();
    return One(intensity);
}

LightList CreateDirectionalLight(ArgReader& args, const Color& intensity) {
    args.ReadVector();
    return One(intensity);
}

LightList CreateExtendedLight(ArgReader& args, const Color& intensity) {
    args.ReadNumber();
    args.ReadVector();
    return One(intensity);
}

LightList CreateSpotLight(ArgReader& args, const Color& intensity) {
    args.ReadVector();
    args.ReadVector();
    args.ReadNumber();
    if (args.PeekNumber()) {
        args.ReadNumber();
        args.ReadNumber();
    }
    return One(intensity);
}

LightList CreateAreaLight(ArgReader& args, const Color& intensity) {
    args.ReadVector();
    args.ReadVector();
    args.ReadInt();
    args.ReadVector();
    args.ReadInt();
    return One(intensity);
}

}  // namespace rs
