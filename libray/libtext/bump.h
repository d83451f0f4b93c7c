// `bump s` (spec §3.12.2): n ← normalize(n + s·DNoise(p)), with the raw (unnormalised)
// DNoise of the original, in texture space.
#pragma once

#include <memory>

#include "libcommon/arg_reader.h"
#include "libtext/texture.h"

namespace rs {

class BumpTexture : public Texture {
  public:
    explicit BumpTexture(double scale) : scale_(scale) {}
    static std::shared_ptr<Texture> Create(ArgReader& args);
    void Apply(TextureContext& ctx, Surface& surface) const override;

  private:
    double scale_;
};

}  // namespace rs
