#include "libtext/sky.h"

#include <algorithm>
#include <cmath>

#include "libcommon/constants.h"
#include "libtext/noise.h"
#include "libtext/texture_space.h"

namespace rs {

SkyTexture::SkyTexture(double scale, double h, double lambda, int octaves, double cthresh,
                       double lthresh)
    : scale_(scale),
      omega_(FBmOmega(h, lambda)),
      lambda_(lambda),
      cthresh_(cthresh),
      lthresh_(lthresh),
      octaves_(octaves) {
    // M = Σ ω^j = 1/(1 − ω) bounds |fBm| for ω < 1. For ω ≥ 1 (meaningless parameters) the
    // finite sum's bound, the octave count, stands in to avoid dividing by zero.
    maxValue_ = omega_ < 1 - kEpsilon ? 1 / (1 - omega_) : std::max(octaves, 1);
}

std::shared_ptr<Texture> SkyTexture::Create(ArgReader& args) {
    double scale = args.ReadNumber();
    double h = args.ReadNumber();
    double lambda = args.ReadNumber();
    int octaves = args.ReadInt();
    double cthresh = args.ReadNumber();
    double lthresh = args.ReadNumber();
    return std::make_shared<SkyTexture>(scale, h, lambda, octaves, cthresh, lthresh);
}

void SkyTexture::Apply(TextureContext& ctx, Surface& surface) const {
    Vec3 p = TextureSpace(transform, ctx.time).Point(ctx.point);
    double it = FBm(p, omega_, lambda_, octaves_);
    it = (maxValue_ + it) / (2 * maxValue_);
    // Ramp from lthresh to cthresh; equal thresholds make it a step at that value.
    it = cthresh_ != lthresh_ ? (it - lthresh_) / (cthresh_ - lthresh_)
                              : (it >= cthresh_ ? 1.0 : 0.0);
    it = std::clamp(it, 0.0, 1.0);
    if (scale_ != 0) it = std::pow(it, scale_);
    surface.transp = 1 - it;
    surface.diffuse *= it;
    surface.ambient *= it;
}

}  // namespace rs
