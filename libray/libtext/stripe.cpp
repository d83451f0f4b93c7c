#include "libtext/stripe.h"

#include <cmath>

#include "libtext/texture_space.h"

namespace rs {

std::shared_ptr<Texture> StripeTexture::Create(ArgReader& args) {
    Surface surface = args.ReadSurface();
    double width = args.ReadNumber();
    double bump = args.ReadNumber();
    std::shared_ptr<const Mapping> mapping;
    if (args.Accept("map")) {
        mapping = ReadMapping(args);
    } else {
        mapping = std::make_shared<UVMapping>();
    }
    return std::make_shared<StripeTexture>(surface, width, bump, std::move(mapping));
}

void StripeTexture::Apply(TextureContext& ctx, Surface& surface) const {
    SurfaceUV s = mapping_->Map(ctx);
    const TextureSpace space(transform, ctx.time);
    Vec2 uv = space.UV(s.uv);
    double u = uv.u - std::floor(uv.u), v = uv.v - std::floor(uv.v);
    double w = width_;
    if (u > 2 * w && v > 2 * w && u <= 1 - w && v <= 1 - w) return;  // flat top
    if (u < w || v < w) {  // the stripe itself
        surface = surface_;
        return;
    }
    // Bevel: split the remapped square along its diagonals into four facing triangles.
    u = (u - w) / (1 - w);
    v = (v - w) / (1 - w);
    double fu, fv;
    if (v < u) {
        if (v < 1 - u) {
            fu = 0, fv = -bump_;
        } else {
            fu = bump_, fv = 0;
        }
    } else if (v < 1 - u) {
        fu = -bump_, fv = 0;
    } else {
        fu = 0, fv = bump_;
    }
    space.Derivatives(s.dpdu, s.dpdv, ctx.normal);
    ctx.normal = BumpNormal(ctx.normal, s.dpdu, s.dpdv, fu, fv);
}

}  // namespace rs
