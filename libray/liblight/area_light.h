// `light I area P1 P2 nu P3 nv`: a parallelogram source with corner P1 and edges P2 − P1
// and P3 − P1, made of nu·nv independent sub-lights of intensity I/(nu·nv). Each use of a
// sub-light picks a fresh uniform point inside its cell, for shading and shadow alike.
#pragma once

#include "liblight/light.h"

namespace rs {

class AreaLightCell final : public Light {
  public:
    AreaLightCell(const Color& i, const Vec3& corner, const Vec3& edgeU, const Vec3& edgeV)
        : corner_(corner), edgeU_(edgeU), edgeV_(edgeV) {
        intensity = i;
    }
    bool Sample(const Vec3& x, int sampleNumber, int samplesPerSide, Rng& rng,
                LightSample& out) const override;

  private:
    Vec3 corner_, edgeU_, edgeV_;
};

}  // namespace rs
