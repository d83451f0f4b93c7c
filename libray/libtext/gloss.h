// `gloss g` (spec §3.12.2): blurs reflections by tilting the normal per eye-ray sample:
// n ← normalize(n + (1 − g)(px·Û + py·V̂)) with (Û, V̂) from n (spec §3.11.1) and (px, py)
// the unit-square sample of the ray's sample number. g = 1 is a mirror.
#pragma once

#include <memory>

#include "libcommon/arg_reader.h"
#include "libcommon/random.h"
#include "libtext/texture.h"

namespace rs {

// The lens / gloss sample of spec §3.3 ("unit circle point", actually a square) in
// [−1, 1]²: sample number m of an n×n grid picks cell (m mod n, ⌊m/n⌋) and a uniform point
// inside it; m < 0 gives a uniform point in the whole square. ξ comes from `rng` (0.5,
// the cell centre, when rng is null).
Vec2 UnitSquareSample(int sampleNumber, int samplesPerSide, Rng* rng);

class GlossTexture : public Texture {
  public:
    explicit GlossTexture(double glossiness) : blur_(1 - glossiness) {}
    static std::shared_ptr<Texture> Create(ArgReader& args);
    void Apply(TextureContext& ctx, Surface& surface) const override;

  private:
    double blur_;  // 1 − g
};

}  // namespace rs
