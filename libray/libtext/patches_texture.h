// `texture patches` (our extension, docs/implicit-examples.md): a debug texture that paints
// each part of a primitive in its own colour, like figure 3b of Gascuel's Implicit Patches
// paper. The part is PrimitiveHit::part: the patch index for `implicit` surfaces (the
// predominant skeleton's patch), and whatever else a primitive stores there (the triangle of
// a heightfield, 0 or 1 for a ray entering or leaving a sphere or a box). Parts < 0 ("no part",
// e.g. `method kb89`) leave the surface unchanged. The texture takes no arguments and
// ignores its transforms.
#pragma once

#include <memory>

#include "libcommon/arg_reader.h"
#include "libtext/texture.h"

namespace rs {

class PatchesTexture : public Texture {
  public:
    // Colour of part p >= 0: HSV with hue frac(p·(√5 − 1)/2) of the colour circle, saturation
    // kSaturation and value kValue. Successive golden-ratio hues keep any two consecutive
    // parts 0.382 of the circle apart and spread every prefix of the sequence evenly.
    static constexpr double kSaturation = 0.7;
    static constexpr double kValue = 0.9;
    static Color PartColor(int part);

    static std::shared_ptr<Texture> Create(ArgReader& args);

    // For ctx.primitiveHit.part = p >= 0: diffuse ← PartColor(p), ambient ← PartColor(p)
    // scaled by the largest channel of the surface's ambient (so the scene's ambient level is
    // kept). Every other field is left alone.
    void Apply(TextureContext& ctx, Surface& surface) const override;
};

}  // namespace rs
