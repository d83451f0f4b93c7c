#include "libtext/cloud.h"

#include <algorithm>
#include <cmath>

#include "libcommon/constants.h"
#include "libtext/noise.h"
#include "libtext/texture_space.h"

namespace rs {

CloudTexture::CloudTexture(double scale, double h, double lambda, int octaves, double cthresh,
                           double lthresh, double transcale)
    : scale_(scale),
      omega_(FBmOmega(h, lambda)),
      lambda_(lambda),
      cthresh_(cthresh),
      lthresh_(lthresh),
      transcale_(transcale),
      octaves_(octaves) {
    double beta = 1 + 2 * h;
    halfIntensity_ = std::fabs(1 - beta) < kEpsilon;
    maxValue_ = halfIntensity_ ? 0 : 1 / (1 - beta);
}

std::shared_ptr<Texture> CloudTexture::Create(ArgReader& args) {
    double scale = args.ReadNumber();
    double h = args.ReadNumber();
    double lambda = args.ReadNumber();
    int octaves = args.ReadInt();
    double cthresh = args.ReadNumber();
    double lthresh = args.ReadNumber();
    double transcale = args.ReadNumber();
    return std::make_shared<CloudTexture>(scale, h, lambda, octaves, cthresh, lthresh,
                                          transcale);
}

void CloudTexture::Apply(TextureContext& ctx, Surface& surface) const {
    // Where the viewer stands relative to the unit sphere, in the primitive's space.
    Vec3 origin = ctx.rayPrimitive.origin;
    Vec3 dir = Normalize(ctx.rayPrimitive.dir);
    double d2 = Dot(origin, origin);
    if (d2 < 1 + kEpsilon) {
        surface.transp = 1;
        surface.ambient = Color(0);
        surface.diffuse = Color(0);
        return;
    }
    double it = 0.5;
    if (!halfIntensity_) {
        Vec3 p = TextureSpace(transform, ctx.time).Point(ctx.point);
        double f = FBm(p, omega_, lambda_, octaves_);
        it = std::clamp((maxValue_ + f) * 0.5 / maxValue_, 0.0, 1.0);
    }
    // limb: cosine of the view angle off the sphere's centre, rescaled to 0 on the limb
    // (cos = b, the tangent cone) and 1 at the centre.
    double d = std::sqrt(d2);
    double b = std::sqrt(d2 - 1) / d;
    double a = -Dot(origin, dir) / d;
    double limb = (a - b) / (1 - b);
    double excess = it - cthresh_ - (lthresh_ - cthresh_) * (1 - limb);
    double transp = transcale_ != 0 ? 1 - excess / transcale_ : (excess > 0 ? 0.0 : 1.0);
    transp = std::clamp(transp, 0.0, 1.0);
    surface.transp = transp;
    surface.diffuse *= (1 - transp) * (1 - scale_ + scale_ * it);
    surface.ambient *= 1 - transp;
}

}  // namespace rs
