#include "libtext/patches_texture.h"

#include <algorithm>
#include <cmath>

namespace rs {

Color PatchesTexture::PartColor(int part) {
    // (√5 − 1)/2, the fractional part of the golden ratio.
    const double kGoldenFraction = (std::sqrt(5.0) - 1) / 2;
    double hue = std::fmod(part * kGoldenFraction, 1.0);
    // HSV → RGB: the hue circle in six sectors of 1/6; in sector i at fraction f the three
    // channels are v, v(1 − s) and a ramp between them.
    double h6 = 6 * hue;
    int sector = std::min(static_cast<int>(h6), 5);
    double f = h6 - sector;
    double v = kValue, lo = kValue * (1 - kSaturation);
    double down = kValue * (1 - kSaturation * f), up = kValue * (1 - kSaturation * (1 - f));
    switch (sector) {
        case 0:
            return {v, up, lo};
        case 1:
            return {down, v, lo};
        case 2:
            return {lo, v, up};
        case 3:
            return {lo, down, v};
        case 4:
            return {up, lo, v};
        default:
            return {v, lo, down};
    }
}

std::shared_ptr<Texture> PatchesTexture::Create(ArgReader& /*args*/) {
    return std::make_shared<PatchesTexture>();
}

void PatchesTexture::Apply(TextureContext& ctx, Surface& surface) const {
    int part = ctx.primitiveHit.part;
    if (part < 0) return;
    Color c = PartColor(part);
    double ambientLevel = std::max({surface.ambient.r, surface.ambient.g, surface.ambient.b});
    surface.diffuse = c;
    surface.ambient = ambientLevel * c;
}

}  // namespace rs
