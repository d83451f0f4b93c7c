#include "libtext/gloss.h"

#include "libtext/texture_space.h"

namespace rs {

Vec2 UnitSquareSample(int sampleNumber, int samplesPerSide, Rng* rng) {
    double xi1 = rng ? rng->Uniform() : 0.5;
    double xi2 = rng ? rng->Uniform() : 0.5;
    if (sampleNumber < 0 || samplesPerSide < 1) return {2 * xi1 - 1, 2 * xi2 - 1};
    double cell = 2.0 / samplesPerSide;
    return {-1 + (sampleNumber % samplesPerSide + xi1) * cell,
            -1 + (sampleNumber / samplesPerSide + xi2) * cell};
}

std::shared_ptr<Texture> GlossTexture::Create(ArgReader& args) {
    return std::make_shared<GlossTexture>(args.ReadNumber());
}

void GlossTexture::Apply(TextureContext& ctx, Surface& /*surface*/) const {
    TextureSpace space(transform, ctx.time);
    Vec3 n = space.NormalToTexture(ctx.normal);
    Vec3 u, v;
    CoordinateSystem(n, u, v);
    Vec2 s = UnitSquareSample(ctx.sampleNumber, ctx.samplesPerSide, ctx.rng);
    AssignNormal(ctx.normal, space.NormalToNode(n + blur_ * (s.u * u + s.v * v)));
}

}  // namespace rs
