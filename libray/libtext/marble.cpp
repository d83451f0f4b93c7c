#include "libtext/marble.h"

#include <cmath>

#include "libtext/noise.h"
#include "libtext/texture_space.h"

namespace rs {

std::shared_ptr<Texture> MarbleTexture::Create(ArgReader& args) {
    if (args.PeekFilename()) return std::make_shared<MarbleTexture>(ReadColorMapArgument(args));
    return std::make_shared<MarbleTexture>();
}

void MarbleTexture::Apply(TextureContext& ctx, Surface& surface) const {
    Vec3 p = TextureSpace(transform, ctx.time).Point(ctx.point);
    double v = std::pow(0.5 * (std::sin(8 * Chaos(p, 6) + 7 * p.z) + 1), 0.77);
    ModulateAmbientDiffuse(surface, colorMap_.get(), v);
}

}  // namespace rs
