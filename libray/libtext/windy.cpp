#include "libtext/windy.h"

#include "libtext/noise.h"
#include "libtext/texture_space.h"

namespace rs {

std::shared_ptr<Texture> WindyTexture::Create(ArgReader& args) {
    double scale = args.ReadNumber();
    double windScale = args.ReadNumber();
    double chaosScale = args.ReadNumber();
    double bumpScale = args.ReadNumber();
    int octaves = args.ReadInt();
    double tScale = args.ReadNumber();
    double hScale = args.ReadNumber();
    double offset = args.ReadNumber();
    return std::make_shared<WindyTexture>(scale, windScale, chaosScale, bumpScale, octaves,
                                          tScale, hScale, offset);
}

void WindyTexture::Apply(TextureContext& ctx, Surface& /*surface*/) const {
    TextureSpace space(transform, ctx.time);
    Vec3 p = space.Point(ctx.point);
    double wind = chaosScale_ != 0 ? chaosScale_ * Chaos(windScale_ * p, 7) : 1;
    Vec3 g = bumpScale_ * DNoise(p);
    double frequency = 1, amplitude = wind;
    for (int j = 0; j < octaves_; ++j) {
        frequency *= tScale_;
        g += amplitude * DNoise(frequency * p);
        amplitude *= hScale_;
    }
    g *= wind + offset_;
    Vec3 n = space.NormalToTexture(ctx.normal);
    AssignNormal(ctx.normal, space.NormalToNode(n + scale_ * g));
}

}  // namespace rs
