// `cloud scale H lambda octaves cthresh lthresh transcale` (spec §3.12.2; seven arguments):
// cloud layer meant for unit spheres at the origin of the primitive's space. Rays starting
// inside (|origin|² < 1 + ε) see a fully transparent black surface; otherwise
// It = clamp(½(M + fBm(p))/M, 0, 1) with the original's M = 1/(1 − β), β = 1 + 2H
// (H = 0 gives the limit It = ½ instead of dividing by zero), and the transparency grows
// toward the limb of the sphere as seen from the ray origin.
#pragma once

#include <memory>

#include "libcommon/arg_reader.h"
#include "libtext/texture.h"

namespace rs {

class CloudTexture : public Texture {
  public:
    CloudTexture(double scale, double h, double lambda, int octaves, double cthresh,
                 double lthresh, double transcale);
    static std::shared_ptr<Texture> Create(ArgReader& args);
    void Apply(TextureContext& ctx, Surface& surface) const override;

  private:
    double scale_, omega_, lambda_, cthresh_, lthresh_, transcale_, maxValue_;
    int octaves_;
    bool halfIntensity_;  // β = 1: M is infinite and It is ½ everywhere
};

}  // namespace rs
