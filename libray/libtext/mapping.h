// Mappings from a hit to texture coordinates (u, v) for image and stripe textures
// (spec §3.13).
#pragma once

#include <memory>
#include <optional>

#include "libcommon/arg_reader.h"
#include "libtext/texture.h"

namespace rs {

class Mapping {
  public:
    virtual ~Mapping() = default;

    // (u, v) at the hit, with the derivative directions ∂P/∂u and ∂P/∂v expressed in the
    // node space of ctx (the space of ctx.point), before any texture transform.
    virtual SurfaceUV Map(const TextureContext& ctx) const = 0;
};

// `map uv`: the hit primitive's own parameterisation (spec §3.9), evaluated at the true
// primitive-space hit point; derivatives carried to node space. Without a primitive,
// (0, 0) with derivatives x̂, ŷ.
class UVMapping : public Mapping {
  public:
    SurfaceUV Map(const TextureContext& ctx) const override;
};

// Orthonormal frame shared by the spherical and cylindrical mappings:
// N̂ = normalize(up), V̂ = normalize(up × uAxis), Û = V̂ × N̂.
struct MappingFrame {
    Vec3 origin;
    Vec3 u{1, 0, 0}, v{0, 1, 0}, n{0, 0, 1};

    // Returns nothing when up is zero or parallel to uAxis.
    static std::optional<MappingFrame> Make(const Vec3& origin, const Vec3& up,
                                            const Vec3& uAxis);
};

// `map spherical [origin up uaxis]`: the sphere rule of spec §3.9 applied to the direction
// from the origin, expressed in the frame. v ∈ [0, 1] from the −N̂ pole to the +N̂ pole.
class SphericalMapping : public Mapping {
  public:
    explicit SphericalMapping(const MappingFrame& frame) : frame_(frame) {}
    SurfaceUV Map(const TextureContext& ctx) const override;

  private:
    MappingFrame frame_;
};

// `map cylindrical [origin up uaxis]`: v = height along N̂ (unnormalised), u = azimuth/2π
// measured from Û toward V̂, in [0, 1).
class CylindricalMapping : public Mapping {
  public:
    explicit CylindricalMapping(const MappingFrame& frame) : frame_(frame) {}
    SurfaceUV Map(const TextureContext& ctx) const override;

  private:
    MappingFrame frame_;
};

// `map planar [origin vaxis uaxis]`: (u, v) are the first two coordinates of X − origin in
// the (possibly skewed) basis (uAxis, vAxis, uAxis × vAxis), so X = origin + u·uAxis +
// v·vAxis + w·(uAxis × vAxis). This honours the origin, which the original ignored (spec
// §6, Doc/BUGS 1). ∂P/∂u = uAxis, ∂P/∂v = vAxis (normalised).
class PlanarMapping : public Mapping {
  public:
    // Returns nothing when the axes are zero or parallel.
    static std::shared_ptr<PlanarMapping> Make(const Vec3& origin, const Vec3& vAxis,
                                               const Vec3& uAxis);
    SurfaceUV Map(const TextureContext& ctx) const override;

  private:
    PlanarMapping() = default;
    Vec3 origin_;
    Vec3 uDual_, vDual_;  // rows of the inverse basis: u = (X − o)·uDual_, v = (X − o)·vDual_
    Vec3 dpdu_, dpdv_;
};

// Reads the mapping after the `map` keyword: `uv`, or `spherical`/`cylindrical`/`planar`
// with an optional three vectors (spec §2 `mapping`). Fails on anything else or on
// degenerate axes.
std::shared_ptr<Mapping> ReadMapping(ArgReader& args);

// The sphere rule of spec §3.9 for a unit direction (nx, ny, nz): v = acos(−nz)/π;
// u = 0 within kEpsilon of a pole, else acos(nx / sin πv)/2π, replaced by 1 − u unless
// ny > 0.
Vec2 SphereUV(double nx, double ny, double nz);

// The bump rule shared by stripe and image textures: normalize(n + fu(n × ∂P/∂v) −
// fv(n × ∂P/∂u)); returns n unchanged if the result would be zero.
Vec3 BumpNormal(const Vec3& n, const Vec3& dpdu, const Vec3& dpdv, double fu, double fv);

}  // namespace rs
