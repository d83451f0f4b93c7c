// `sky scale H lambda octaves cthresh lthresh` (spec §3.12.2): cloud cover from
// It = fBm(p) normalised by M = 1/(1 − ω) to (M + It)/2M, then ramped from 0 at lthresh to
// 1 at cthresh (clamped), raised to `scale` when scale ≠ 0. Transparency ← 1 − It; ambient
// and diffuse *= It.
#pragma once

#include <memory>

#include "libcommon/arg_reader.h"
#include "libtext/texture.h"

namespace rs {

class SkyTexture : public Texture {
  public:
    SkyTexture(double scale, double h, double lambda, int octaves, double cthresh,
               double lthresh);
    static std::shared_ptr<Texture> Create(ArgReader& args);
    void Apply(TextureContext& ctx, Surface& surface) const override;

  private:
    double scale_, omega_, lambda_, cthresh_, lthresh_, maxValue_;
    int octaves_;
};

}  // namespace rs
