#include "libtext/blotch.h"

#include "libcommon/constants.h"
#include "libtext/noise.h"
#include "libtext/texture_space.h"

namespace rs {

std::shared_ptr<Texture> BlotchTexture::Create(ArgReader& args) {
    double mix = args.ReadNumber();
    return std::make_shared<BlotchTexture>(mix, args.ReadSurface());
}

void BlotchTexture::Apply(TextureContext& ctx, Surface& surface) const {
    double v = Noise(TextureSpace(transform, ctx.time).Point(ctx.point));
    if (v <= mix_) return;
    // m ≥ 1 would divide by zero or flip the sign: any noise above it selects S fully.
    double beta = mix_ < 1 ? (v - mix_) / (1 - mix_) : 1;
    if (beta < kEpsilon) return;
    surface = BlendSurfaces(surface, 1 - beta, surface_, beta);
}

}  // namespace rs
