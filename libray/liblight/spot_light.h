// `light I spot P Q c [θi θo]`: a spot at P aimed at Q with falloff cosφ^c and a smooth
// cone between the inner angle θi and the outer angle θo (degrees). Omitted angles mean no
// cone (180°), as the documentation says; the original used 0° and emitted nothing (spec
// §6: fix recommended).
#pragma once

#include "liblight/light.h"

namespace rs {

class SpotLight final : public Light {
  public:
    SpotLight(const Color& i, const Vec3& from, const Vec3& at, double coef, double innerDeg,
              double outerDeg);
    bool Sample(const Vec3& x, int sampleNumber, int samplesPerSide, Rng& rng,
                LightSample& out) const override;

  private:
    Vec3 position_;
    Vec3 axis_;  // unit, from P toward Q
    double coef_;
    double cosInner_, cosOuter_;
};

}  // namespace rs
