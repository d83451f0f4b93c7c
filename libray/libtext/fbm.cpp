#include "libtext/fbm.h"

#include "libtext/noise.h"
#include "libtext/texture_space.h"

namespace rs {

FBmTexture::FBmTexture(double offset, double scale, double h, double lambda, int octaves,
                       double threshold, std::shared_ptr<const ColorMap> colorMap)
    : offset_(offset),
      scale_(scale),
      omega_(FBmOmega(h, lambda)),
      lambda_(lambda),
      threshold_(threshold),
      octaves_(octaves),
      colorMap_(std::move(colorMap)) {}

std::shared_ptr<Texture> FBmTexture::Create(ArgReader& args) {
    double offset = args.ReadNumber();
    double scale = args.ReadNumber();
    double h = args.ReadNumber();
    double lambda = args.ReadNumber();
    int octaves = args.ReadInt();
    double threshold = args.ReadNumber();
    std::shared_ptr<const ColorMap> colorMap;
    if (args.PeekFilename()) colorMap = ReadColorMapArgument(args);
    return std::make_shared<FBmTexture>(offset, scale, h, lambda, octaves, threshold,
                                        std::move(colorMap));
}

void FBmTexture::Apply(TextureContext& ctx, Surface& surface) const {
    Vec3 p = TextureSpace(transform, ctx.time).Point(ctx.point);
    double v = FBm(p, omega_, lambda_, octaves_);
    v = v < threshold_ ? offset_ : offset_ + scale_ * (v - threshold_);
    ModulateAmbientDiffuse(surface, colorMap_.get(), v);
}

}  // namespace rs
