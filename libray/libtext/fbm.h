// `fbm offset scale H lambda octaves threshold [cmap]` (spec §3.12.2): v = fBm(p) with
// ω = λ^−(1+2H)/2; v ← offset below the threshold, else offset + scale·(v − threshold).
// Ambient and diffuse are multiplied by cmap[clamp(⌊255v⌋, 0, 255)], or by v.
#pragma once

#include <memory>

#include "libcommon/arg_reader.h"
#include "libtext/colormap.h"
#include "libtext/texture.h"

namespace rs {

class FBmTexture : public Texture {
  public:
    FBmTexture(double offset, double scale, double h, double lambda, int octaves,
               double threshold, std::shared_ptr<const ColorMap> colorMap = nullptr);
    static std::shared_ptr<Texture> Create(ArgReader& args);
    void Apply(TextureContext& ctx, Surface& surface) const override;

  private:
    double offset_, scale_, omega_, lambda_, threshold_;
    int octaves_;
    std::shared_ptr<const ColorMap> colorMap_;  // may be null
};

}  // namespace rs
