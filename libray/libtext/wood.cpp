#include "libtext/wood.h"

#include <algorithm>
#include <cmath>

#include "libtext/noise.h"
#include "libtext/texture_space.h"

namespace rs {

std::shared_ptr<Texture> WoodTexture::Create(ArgReader& /*args*/) {
    return std::make_shared<WoodTexture>();
}

Color WoodTexture::Factor(const Vec3& p) {
    double chaos = Chaos(p, 7);
    double t = std::fabs(std::sin(std::sin(8 * chaos + 7 * p.x + 3 * p.y)));
    double grain = std::fabs(std::sin(40 * chaos + 50 * p.z));
    double g0 = 0.5 * std::pow(t, 0.3);
    double ring = std::pow((t + 1) / 2, 0.6);
    double b = ring * (0.6 * grain + 0.3);
    double gr = ring * (0.2 * grain + 0.8);
    double red = (0.5 * b + 0.35 * gr) * 2 * g0;
    double blue = (0.25 * b + 0.35 * gr) * 2 * g0;
    double green = g0 * std::max(b, gr) * (0.15 * grain + 0.85);
    return {red, green, blue};
}

void WoodTexture::Apply(TextureContext& ctx, Surface& surface) const {
    Color c = Factor(TextureSpace(transform, ctx.time).Point(ctx.point));
    surface.ambient *= c;
    surface.diffuse *= c;
}

}  // namespace rs
