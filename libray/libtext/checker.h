// `checker S` (spec §3.12.2): unit cubes in texture space alternate between the current
// surface and S. With k = ⌊c⌋ for c > 0 and ⌊1 − c⌋ otherwise, on each axis, the cell takes S
// when k_x + k_y + k_z is odd (the Docs say "even"; the original wins).
#pragma once

#include <memory>

#include "libcommon/arg_reader.h"
#include "libtext/texture.h"

namespace rs {

class CheckerTexture : public Texture {
  public:
    explicit CheckerTexture(const Surface& surface) : surface_(surface) {}
    static std::shared_ptr<Texture> Create(ArgReader& args);
    void Apply(TextureContext& ctx, Surface& surface) const override;

  private:
    Surface surface_;
};

}  // namespace rs
