// `light I point P`: a point source at P.
#pragma once

#include "liblight/light.h"

namespace rs {

class PointLight final : public Light {
  public:
    PointLight(const Color& i, const Vec3& position) : position_(position) { intensity = i; }
    bool Sample(const Vec3& x, int sampleNumber, int samplesPerSide, Rng& rng,
                LightSample& out) const override;

  private:
    Vec3 position_;
};

}  // namespace rs
