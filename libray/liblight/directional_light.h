// `light I directional V`: parallel light arriving from direction V (V points toward the
// light).
#pragma once

#include "liblight/light.h"

namespace rs {

class DirectionalLight final : public Light {
  public:
    // `towardLight` must be non-zero; it is normalised here.
    DirectionalLight(const Color& i, const Vec3& towardLight) : dir_(Normalize(towardLight)) {
        intensity = i;
    }
    bool Sample(const Vec3& x, int sampleNumber, int samplesPerSide, Rng& rng,
                LightSample& out) const override;

  private:
    Vec3 dir_;
};

}  // namespace rs
