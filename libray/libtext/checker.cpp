#include "libtext/checker.h"

#include "libtext/texture_space.h"

namespace rs {
namespace {

// The cell index of one coordinate: ⌊c⌋ for c > 0, else ⌊1 − c⌋ (so the cell (−1, 0] has
// index 1 and parity alternates across 0 as everywhere else).
inline long CellIndex(double c) {
    return c > 0 ? static_cast<long>(c) : static_cast<long>(1 - c);
}

}  // namespace

std::shared_ptr<Texture> CheckerTexture::Create(ArgReader& args) {
    return std::make_shared<CheckerTexture>(args.ReadSurface());
}

void CheckerTexture::Apply(TextureContext& ctx, Surface& surface) const {
    Vec3 p = TextureSpace(transform, ctx.time).Point(ctx.point);
    if ((CellIndex(p.x) + CellIndex(p.y) + CellIndex(p.z)) & 1) surface = surface_;
}

}  // namespace rs
