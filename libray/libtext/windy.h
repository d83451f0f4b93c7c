// `windy scale windscale chaoscale bumpscale octaves tscale hscale offset` (undocumented,
// spec §3.12.2): wind-driven water ripples. W0 = chaoscale·Chaos(windscale·p, 7) (1 when
// chaoscale = 0); G = bumpscale·DNoise(p) + Σ_{j=1..octaves} W0·hscale^(j−1)·
// DNoise(tscale^j p); n ← normalize(n + scale·(W0 + offset)·G).
#pragma once

#include <memory>

#include "libcommon/arg_reader.h"
#include "libtext/texture.h"

namespace rs {

class WindyTexture : public Texture {
  public:
    WindyTexture(double scale, double windScale, double chaosScale, double bumpScale,
                 int octaves, double tScale, double hScale, double offset)
        : scale_(scale), windScale_(windScale), chaosScale_(chaosScale),
          bumpScale_(bumpScale), tScale_(tScale), hScale_(hScale), offset_(offset),
          octaves_(octaves) {}
    static std::shared_ptr<Texture> Create(ArgReader& args);
    void Apply(TextureContext& ctx, Surface& surface) const override;

  private:
    double scale_, windScale_, chaosScale_, bumpScale_, tScale_, hScale_, offset_;
    int octaves_;
};

}  // namespace rs
