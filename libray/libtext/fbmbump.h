// `fbmbump offset scale H lambda octaves` (spec §3.12.2): g = VfBm(p) with
// ω = λ^−(1+2H)/2; n ← normalize(n + (offset + scale·g_x, offset + scale·g_y,
// offset + scale·g_z)). The original does not renormalise; the spec's fix does.
#pragma once

#include <memory>

#include "libcommon/arg_reader.h"
#include "libtext/noise.h"
#include "libtext/texture.h"

namespace rs {

class FBmBumpTexture : public Texture {
  public:
    FBmBumpTexture(double offset, double scale, double h, double lambda, int octaves)
        : offset_(offset), scale_(scale), omega_(FBmOmega(h, lambda)), lambda_(lambda),
          octaves_(octaves) {}
    static std::shared_ptr<Texture> Create(ArgReader& args);
    void Apply(TextureContext& ctx, Surface& surface) const override;

  private:
    double offset_, scale_, omega_, lambda_;
    int octaves_;
};

}  // namespace rs
