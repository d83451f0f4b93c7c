// `mount cmap turbulence slope` (undocumented, spec §3.12.2): colours by altitude, with
// steep faces (normal far from +z in texture space) pushed down the map:
// idx = clamp(⌊256·(p_z + turbulence·Chaos(p, 7) − slope·(1 − n_z))⌋, 0, 255); ambient,
// diffuse and specular ⊙= cmap[idx].
#pragma once

#include <memory>
#include <utility>

#include "libcommon/arg_reader.h"
#include "libtext/colormap.h"
#include "libtext/texture.h"

namespace rs {

class MountTexture : public Texture {
  public:
    MountTexture(std::shared_ptr<const ColorMap> colorMap, double turbulence, double slope)
        : colorMap_(std::move(colorMap)), turbulence_(turbulence), slope_(slope) {}
    static std::shared_ptr<Texture> Create(ArgReader& args);
    void Apply(TextureContext& ctx, Surface& surface) const override;

  private:
    std::shared_ptr<const ColorMap> colorMap_;
    double turbulence_, slope_;
};

}  // namespace rs
