// `marble [cmap]` (spec §3.12.2): v = (½(sin(8·Chaos(p, 6) + 7p_z) + 1))^0.77 ∈ [0, 1];
// ambient and diffuse are multiplied by cmap[⌊255v⌋] component-wise, or by v without a
// colour map.
#pragma once

#include <memory>
#include <utility>

#include "libcommon/arg_reader.h"
#include "libtext/colormap.h"
#include "libtext/texture.h"

namespace rs {

class MarbleTexture : public Texture {
  public:
    explicit MarbleTexture(std::shared_ptr<const ColorMap> colorMap = nullptr)
        : colorMap_(std::move(colorMap)) {}
    static std::shared_ptr<Texture> Create(ArgReader& args);
    void Apply(TextureContext& ctx, Surface& surface) const override;

  private:
    std::shared_ptr<const ColorMap> colorMap_;  // may be null
};

}  // namespace rs
