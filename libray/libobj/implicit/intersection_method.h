// Layer 6 of the implicit module: the interface of the baseline intersection methods
// (march, sphere, segment, exact here; polynomial at layer 8), which search the PLAIN SUM
// F = Σ w_i f_i(d_i) of an object's terms for the first root of g = F − T along a ray.
// Patches are not used by them (they would need a predominance test per root and one search
// per patch: see README.md, "Methods"), and blend lists are ignored (everything blends).
// The octree methods (kb89_method.h, patches_method.h) implement the same interface.
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

// A hit of a method: the ray parameter and the term owning the hit's patch (the skeleton
// whose patch it lies on, or the predominant one where the method reports it), or −1.
struct MethodHit {
    double t = 0;
    int term = -1;
};

// How an implicit object's rays are intersected: the baselines below the primitive
// (FirstRoot on the plain sum) and the octree methods (Kb89Method, PatchesMethod), which
// override Intersect, Normal and Bounds. Every method is made by its row of the registry
// (method_registry.h) and is immutable once made (thread-safe, lazy trees included).
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

    // The first hit in (tMin, tMax): FirstRoot, with PredominantTerm at the root.
    virtual std::optional<MethodHit> Intersect(const Ray& ray, double tMin, double tMax) const;
    // The unit outward normal at a hit p owned by `term` (−1: none), `whole` being the
    // object's plain sum: normalised −∇F (Gradient), and where ∇F = 0 the direction away
    // from the skeleton predominating at p (+z on the skeleton).
    virtual Vec3 Normal(const Field& whole, const Vec3& p, int term) const;
    // A box containing every hit (default: PositiveSupportBounds of `whole`).
    virtual Bounds3 Bounds(const Field& whole) const;
};

// The unit vector from the closest point of skeleton `own` of `field` to p, +z when p lies
// on it: the normal where ∇F vanishes (pinch points).
Vec3 AwayFromSkeleton(const Field& field, int own, const Vec3& p);

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
