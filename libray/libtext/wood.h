// `wood` (spec §3.12.2): rings from χ = Chaos(p, 7), t = |sin(sin(8χ + 7p_x + 3p_y))| and
// grain π = |sin(40χ + 50p_z)|; ambient and diffuse are multiplied component-wise by the
// resulting (red, green, blue). Feature size about 0.01 texture units.
#pragma once

#include <memory>

#include "libcommon/arg_reader.h"
#include "libtext/texture.h"

namespace rs {

class WoodTexture : public Texture {
  public:
    WoodTexture() = default;
    static std::shared_ptr<Texture> Create(ArgReader& args);
    void Apply(TextureContext& ctx, Surface& surface) const override;

    // The colour factor at texture-space point p.
    static Color Factor(const Vec3& p);
};

}  // namespace rs
