#include "libtext/fbmbump.h"

#include "libtext/texture_space.h"

namespace rs {

std::shared_ptr<Texture> FBmBumpTexture::Create(ArgReader& args) {
    double offset = args.ReadNumber();
    double scale = args.ReadNumber();
    double h = args.ReadNumber();
    double lambda = args.ReadNumber();
    int octaves = args.ReadInt();
    return std::make_shared<FBmBumpTexture>(offset, scale, h, lambda, octaves);
}

void FBmBumpTexture::Apply(TextureContext& ctx, Surface& /*surface*/) const {
    TextureSpace space(transform, ctx.time);
    Vec3 g = VFBm(space.Point(ctx.point), omega_, lambda_, octaves_);
    Vec3 n = space.NormalToTexture(ctx.normal) + Vec3(offset_, offset_, offset_) + scale_ * g;
    AssignNormal(ctx.normal, space.NormalToNode(n));
}

}  // namespace rs
