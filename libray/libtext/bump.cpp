#include "libtext/bump.h"

#include "libtext/noise.h"
#include "libtext/texture_space.h"

namespace rs {

std::shared_ptr<Texture> BumpTexture::Create(ArgReader& args) {
    return std::make_shared<BumpTexture>(args.ReadNumber());
}

void BumpTexture::Apply(TextureContext& ctx, Surface& /*surface*/) const {
    TextureSpace space(transform, ctx.time);
    Vec3 n = space.NormalToTexture(ctx.normal);
    AssignNormal(ctx.normal, space.NormalToNode(n + scale_ * DNoise(space.Point(ctx.point))));
}

}  // namespace rs
