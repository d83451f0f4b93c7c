// `stripe S width bump [mapping]` (spec §3.12.2): a raised grid in (u, v) space (default
// `map uv`). With u, v reduced to [0, 1): the band u < w or v < w takes surface S; the
// bevel between w and 2w (and above 1 − w) tilts the normal by ±bump along ∂P/∂u or
// ∂P/∂v; the rest is unchanged. The texture transform acts on (u, v).
#pragma once

#include <memory>
#include <utility>

#include "libcommon/arg_reader.h"
#include "libtext/mapping.h"
#include "libtext/texture.h"

namespace rs {

class StripeTexture : public Texture {
  public:
    StripeTexture(const Surface& surface, double width, double bump,
                  std::shared_ptr<const Mapping> mapping)
        : surface_(surface), width_(width), bump_(bump), mapping_(std::move(mapping)) {}
    static std::shared_ptr<Texture> Create(ArgReader& args);
    void Apply(TextureContext& ctx, Surface& surface) const override;

  private:
    Surface surface_;
    double width_, bump_;
    std::shared_ptr<const Mapping> mapping_;
};

}  // namespace rs
