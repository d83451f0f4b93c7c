#include "libtext/mount.h"

#include "libtext/noise.h"
#include "libtext/texture_space.h"

namespace rs {

std::shared_ptr<Texture> MountTexture::Create(ArgReader& args) {
    std::shared_ptr<const ColorMap> colorMap = ReadColorMapArgument(args);
    double turbulence = args.ReadNumber();
    double slope = args.ReadNumber();
    return std::make_shared<MountTexture>(std::move(colorMap), turbulence, slope);
}

void MountTexture::Apply(TextureContext& ctx, Surface& surface) const {
    TextureSpace space(transform, ctx.time);
    Vec3 p = space.Point(ctx.point);
    double nz = space.NormalToTexture(ctx.normal).z;
    double height = p.z + turbulence_ * Chaos(p, 7) - slope_ * (1 - nz);
    const Color& c = ColorMapLookup(*colorMap_, 256 * height);
    surface.ambient *= c;
    surface.diffuse *= c;
    surface.specular *= c;
}

}  // namespace rs
