// The contract every leaf shape implements (cf. Embree's user geometry).
//
// All calls work in the primitive's own object space. Ray directions are NOT unit length in
// general (transforms do not renormalise), and t is measured in units of the given
// direction, so t means the same point in every space.
//
// Intersect is cheap: it returns the nearest t strictly inside (tMin, tMax) and a small
// payload. Normals, uv and the enter/leave classification are computed afterwards, once,
// for the winning hit only, from that payload.
#pragma once

#include "libcommon/bounds.h"
#include "libcommon/ray.h"
#include "libcommon/stats.h"

namespace rs {

// What Intersect hands to the shading calls. The meaning of a/b/c and part is private to
// each primitive (barycentrics, face index, patch index, ...).
struct PrimitiveHit {
    double t = 0;
    double a = 0, b = 0, c = 0;
    int part = -1;
};

// Object-space normals of a hit, both unit length and NOT yet flipped toward the ray.
// `smooth` marks interpolated (Phong) normals, for which the shading model consults the
// geometric normal when the two disagree (spec §3.6).
struct SurfaceNormals {
    Vec3 shading;
    Vec3 geometric;
    bool smooth = false;
};

// Surface parameterisation at a hit (spec §3.9 "UV"), with the derivative directions used
// by bump-type textures. Primitives without a parameterisation return the defaults.
struct SurfaceUV {
    Vec2 uv;
    Vec3 dpdu{1, 0, 0};
    Vec3 dpdv{0, 1, 0};
};

// For solids whose surface a line crosses at most twice (entry tNear ≤ exit tFar): accepts
// the nearer crossing inside (tMin, tMax), recording part 0 for the entry and 1 for the exit
// (what EntersFromHit reads back).
inline bool AcceptNearerCrossing(double tNear, double tFar, double tMin, double tMax,
                                 PrimitiveHit& hit) {
    if (tNear > tMin && tNear < tMax) {
        hit.t = tNear;
        hit.part = 0;
        return true;
    }
    if (tFar > tMin && tFar < tMax) {
        hit.t = tFar;
        hit.part = 1;
        return true;
    }
    return false;
}

class Primitive {
  public:
    virtual ~Primitive() = default;

    // Per-type test/hit counters, e.g. IntersectionCounters("Sphere"); the report lists
    // each type that was tested.
    virtual const IntersectionCounters& Counters() const = 0;

    // Object-space box containing every possible hit. Only meaningful when IsBounded().
    virtual Bounds3 Bounds() const = 0;
    virtual bool IsBounded() const { return true; }
    // Closed surfaces enclose a volume and may be CSG operands.
    virtual bool IsClosed() const { return false; }

    // Nearest hit with tMin < t < tMax; fills `hit` (at least hit.t) and returns true.
    virtual bool Intersect(const Ray& ray, double tMin, double tMax, PrimitiveHit& hit) const = 0;

    // Normals at the object-space hit point `p` of `hit`.
    virtual SurfaceNormals Normal(const Vec3& p, const PrimitiveHit& hit) const = 0;

    // Texture coordinates at `p`. `facingNormal` is the object-space geometric normal
    // already flipped to face the ray (the plane's mapping depends on it).
    virtual SurfaceUV UV(const Vec3& /*p*/, const Vec3& /*facingNormal*/,
                         const PrimitiveHit& /*hit*/) const {
        return {};
    }

    // Whether the ray enters the solid at this hit (CSG and refraction). The default is the
    // normal test d·Ng < 0; solids like spheres and boxes override it with a geometric test.
    virtual bool Enters(const Ray& ray, const PrimitiveHit& /*hit*/,
                        const SurfaceNormals& n) const {
        return Dot(ray.dir, n.geometric) < 0;
    }

    // The same answer as Enters when the hit payload alone decides it (solids that record
    // whether they hit the near or the far root): 1 enters, 0 leaves, −1 when Enters must
    // be asked. Lets CSG classify hits without computing normals.
    virtual int EntersFromHit(const PrimitiveHit& /*hit*/) const { return -1; }

    // Called once per frame before rendering with the frame's start time and the shutter's
    // length (0: closed), so primitives with time-varying parameters (implicit skeletons)
    // can rebuild their acceleration data, for every ray time in [frameTime, frameTime +
    // shutter] when the shutter is open.
    virtual void PrepareFrame(double /*frameTime*/, double /*shutter*/) {}
    // Whether PrepareFrame does anything (builds, may report). Primitives that do are
    // prepared one at a time on the preparing thread, so their own builds run on the
    // build's threads and their reports keep the scene's order; the others may be prepared
    // concurrently (Object::PrepareFrame), so their Bounds() and IsBounded() must then
    // only read the primitive.
    virtual bool PrepareFrameDoesWork() const { return false; }
};

}  // namespace rs
