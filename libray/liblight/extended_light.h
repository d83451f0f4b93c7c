// `light I extended r P`: a spherical source of radius r at P. Shading uses the direction
// to the centre; each shadow ray aims at a jittered point of the square of side 2r centred
// on P and perpendicular to P − x, so penumbrae emerge from pixel supersampling (§3.7).
#pragma once

#include "liblight/light.h"

namespace rs {

class ExtendedLight final : public Light {
  public:
    ExtendedLight(const Color& i, double radius, const Vec3& centre)
        : radius_(radius), centre_(centre) {
        intensity = i;
    }
    bool Sample(const Vec3& x, int sampleNumber, int samplesPerSide, Rng& rng,
                LightSample& out) const override;

  private:
    double radius_;
    Vec3 centre_;
};

}  // namespace rs
