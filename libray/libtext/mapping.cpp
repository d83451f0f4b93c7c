#include "libtext/mapping.h"

#include <algorithm>
#include <cmath>

#include "libcommon/constants.h"

namespace rs {

Vec2 SphereUV(double nx, double ny, double nz) {
    double v = std::acos(std::clamp(-nz, -1.0, 1.0)) / kPi;
    if (v < kEpsilon || v > 1 - kEpsilon) return {0, v};
    double u = std::acos(std::clamp(nx / std::sin(kPi * v), -1.0, 1.0)) / (2 * kPi);
    if (!(ny > 0)) u = 1 - u;
    return {u, v};
}

SurfaceUV UVMapping::Map(const TextureContext& ctx) const {
    if (ctx.primitive == nullptr) return {};
    SurfaceUV s =
        ctx.primitive->UV(ctx.pointPrimitive, ctx.facingNormalPrimitive, ctx.primitiveHit);
    s.dpdu = ctx.nodeFromPrimitive.ApplyVector(s.dpdu);
    s.dpdv = ctx.nodeFromPrimitive.ApplyVector(s.dpdv);
    return s;
}

std::optional<MappingFrame> MappingFrame::Make(const Vec3& origin, const Vec3& up,
                                               const Vec3& uAxis) {
    Vec3 side = Cross(up, uAxis);
    if (Length(up) < kEpsilon || Length(side) <= kEpsilon * Length(up) * Length(uAxis)) {
        return std::nullopt;
    }
    MappingFrame f;
    f.origin = origin;
    f.n = Normalize(up);
    f.v = Normalize(side);
    f.u = Cross(f.v, f.n);
    return f;
}

SurfaceUV SphericalMapping::Map(const TextureContext& ctx) const {
    SurfaceUV s;
    Vec3 d = ctx.point - frame_.origin;
    double len = Length(d);
    if (len == 0) return s;  // X at the origin: (0, 0)
    Vec3 w = d / len;
    s.uv = SphereUV(Dot(w, frame_.u), Dot(w, frame_.v), Dot(w, frame_.n));
    // u grows eastward (N̂ × w); v grows toward the +N̂ pole (w × ∂u).
    Vec3 east = Cross(frame_.n, w);
    s.dpdu = LengthSquared(east) > 0 ? Normalize(east) : frame_.u;
    s.dpdv = Normalize(Cross(w, s.dpdu));
    return s;
}

SurfaceUV CylindricalMapping::Map(const TextureContext& ctx) const {
    SurfaceUV s;
    Vec3 d = ctx.point - frame_.origin;
    double nx = Dot(d, frame_.u), ny = Dot(d, frame_.v);
    double rho = std::sqrt(nx * nx + ny * ny);
    double u = 0;
    if (rho >= kEpsilon) {
        u = std::acos(std::clamp(nx / rho, -1.0, 1.0)) / (2 * kPi);
        if (ny < 0) u = 1 - u;
    }
    s.uv = {u, Dot(d, frame_.n)};
    // The original uses N̂ × X (from the space's origin); the mapping's origin is meant.
    Vec3 east = Cross(frame_.n, d);
    s.dpdu = LengthSquared(east) > 0 ? Normalize(east) : frame_.u;
    s.dpdv = frame_.n;
    return s;
}

std::shared_ptr<PlanarMapping> PlanarMapping::Make(const Vec3& origin, const Vec3& vAxis,
                                                   const Vec3& uAxis) {
    // Dual basis of (a, b, c) = (uAxis, vAxis, uAxis × vAxis): a* = (b × c)/det,
    // b* = (c × a)/det with det = a·(b × c) = |a × b|² > 0 unless a ∥ b.
    Vec3 c = Cross(uAxis, vAxis);
    double det = LengthSquared(c);
    if (det <= kEpsilon * kEpsilon * LengthSquared(uAxis) * LengthSquared(vAxis)) return nullptr;
    std::shared_ptr<PlanarMapping> m(new PlanarMapping());
    m->origin_ = origin;
    m->uDual_ = Cross(vAxis, c) / det;
    m->vDual_ = Cross(c, uAxis) / det;
    m->dpdu_ = Normalize(uAxis);
    m->dpdv_ = Normalize(vAxis);
    return m;
}

SurfaceUV PlanarMapping::Map(const TextureContext& ctx) const {
    Vec3 d = ctx.point - origin_;
    SurfaceUV s;
    s.uv = {Dot(d, uDual_), Dot(d, vDual_)};
    s.dpdu = dpdu_;
    s.dpdv = dpdv_;
    return s;
}

Vec3 BumpNormal(const Vec3& n, const Vec3& dpdu, const Vec3& dpdv, double fu, double fv) {
    Vec3 bumped = Normalize(n + fu * Cross(n, dpdv) - fv * Cross(n, dpdu));
    return LengthSquared(bumped) > 0 && IsFinite(bumped) ? bumped : n;
}

std::shared_ptr<Mapping> ReadMapping(ArgReader& args) {
    if (args.Accept("uv")) return std::make_shared<UVMapping>();

    bool spherical = args.Accept("spherical");
    bool cylindrical = !spherical && args.Accept("cylindrical");
    bool planar = !spherical && !cylindrical && args.Accept("planar");
    if (!spherical && !cylindrical && !planar) {
        args.Fail("expected uv, spherical, cylindrical or planar after map");
    }
    // Defaults: origin 0; up (or v axis) ẑ for the curved mappings, ŷ for planar; u axis x̂.
    Vec3 origin, second = planar ? Vec3{0, 1, 0} : Vec3{0, 0, 1}, uAxis{1, 0, 0};
    if (args.PeekNumber()) {
        origin = args.ReadVector();
        second = args.ReadVector();
        uAxis = args.ReadVector();
    }
    if (planar) {
        std::shared_ptr<PlanarMapping> m = PlanarMapping::Make(origin, second, uAxis);
        if (!m) args.Fail("planar mapping axes are zero or parallel");
        return m;
    }
    std::optional<MappingFrame> frame = MappingFrame::Make(origin, second, uAxis);
    if (!frame) args.Fail("mapping up and u axes are zero or parallel");
    if (spherical) return std::make_shared<SphericalMapping>(*frame);
    return std::make_shared<CylindricalMapping>(*frame);
}

}  // namespace rs
