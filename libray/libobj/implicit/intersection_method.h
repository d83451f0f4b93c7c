// Layer 6 of the implicit module: the interface of the baseline intersection methods
// (march, sphere, segment, exact here; polynomial at layer 7), which search the PLAIN SUM
// F = Σ w_i f_i(d_i) of an object's terms for the first root of g = F − T along a ray.
// Patches are not used by them (they would need a predominance test per root and one search
// per patch: see README.md, "Methods"), and blend lists are ignored (everything blends).
// The octree methods (patches, kb89) are built by the primitive itself (lg_octree.h).
//
// Contract of FirstRoot(ray, tMin, tMax), ray in object space (direction of any non-zero
// length, t in units of it): a t in the OPEN interval (tMin, tMax) near the first place where
// g changes sign along the ray (inside: g > 0, as everywhere in the module), or nothing. How
// near, and which roots may be skipped, is each method's own guarantee (its header). Every
// method evaluates the field through Field (or counts its own evaluations into the same
// counters, FieldCounterIds()), so evaluation counts attribute as for the octree methods.
#pragma once

#include <optional>

#include "libcommon/ray.h"
#include "libobj/implicit/field.h"

namespace rs {

// The knobs of the baseline methods, in object space.
struct MethodParams {
    double threshold = 1;     // T > 0
    double tolerance = 1e-7;  // final root accuracy (distance along the ray)
    double step = 0;          // march step (distance); <= 0: DefaultMarchStep
};

class IntersectionMethod {
  public:
    virtual ~IntersectionMethod() = default;
    virtual std::optional<double> FirstRoot(const Ray& ray, double tMin, double tMax) const = 0;
    // ∇F at p for `field`, the plain sum this method searches (for the hit's normal);
    // methods with a faster evaluation of the same sum override it.
    virtual Vec3 Gradient(const Field& field, const Vec3& p) const { return field.Gradient(p); }
    // The term whose contribution w·f(d) is largest at p (ties to the lowest index, as
    // Patch::Predominates), or −1 when the method does not evaluate it.
    virtual int PredominantTerm(const Vec3&) const { return -1; }
};

// The box of the supports of the positive-weight terms: F <= 0 < T outside it, so every
// root lies inside (empty box when no term is positive).
Bounds3 PositiveSupportBounds(const Field& field);

// g(t) = F(o + t·d) − T along one ray.
struct RayField {
    const Field& field;
    const Ray& ray;
    double threshold;
    double operator()(double t) const { return field.Value(ray.At(t)) - threshold; }
};

// The root of g in the bracket [a, b] (g(a), g(b) of different classes, "inside" meaning
// g > 0, or an exact zero end) to within tolT (parameter units), by bisection.
double BisectBracket(const RayField& g, double a, double ga, double b, double gb, double tolT);

// True when g changes class between two values (one inside, one not).
inline bool ClassChanges(double ga, double gb) { return (ga > 0) != (gb > 0); }

// The sample after t of a forward search that wants to advance by dt: t + dt, at least the
// next representable double (so steps too small to move t still progress), at most tEnd.
double NextSample(double t, double dt, double tEnd);

// The step shared by the sampling methods (march, sphere and segment tracing): having
// sampled g at ta and tb > ta, the root it reveals in the open interval (tMin, tMax) — tb
// itself when g(tb) is exactly 0, else the bisected root of a class change (BisectBracket)
// — or nothing, in which case the search goes on from tb.
std::optional<double> RootOfStep(const RayField& g, double ta, double ga, double tb, double gb,
                                 double tolT, double tMin, double tMax);

}  // namespace rs
