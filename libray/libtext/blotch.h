// `blotch m S` (spec §3.12.2): where v = Noise(p) exceeds m, blends toward S with weight
// β = (v − m)/(1 − m): surface ← (1 − β)·surface + β·S. No change while β < kEpsilon.
#pragma once

#include <memory>

#include "libcommon/arg_reader.h"
#include "libtext/texture.h"

namespace rs {

class BlotchTexture : public Texture {
  public:
    BlotchTexture(double mix, const Surface& surface) : mix_(mix), surface_(surface) {}
    static std::shared_ptr<Texture> Create(ArgReader& args);
    void Apply(TextureContext& ctx, Surface& surface) const override;

  private:
    double mix_;
    Surface surface_;
};

}  // namespace rs
