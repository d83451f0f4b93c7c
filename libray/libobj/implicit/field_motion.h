// Layer 4 of the implicit module, beside field.h: the motion of a field's terms during an
// open shutter (skeleton motion blur).
//
// A moving field holds, for each term, a reference term (its skeleton and weight at one
// time of the shutter interval, conventionally the middle) and a TermMotion that bounds the
// term over the whole interval [t0, t1]:
//   - reach ρ: for every t in [t0, t1], every point of the skeleton at t lies within ρ of
//     the reference skeleton and every reference point within ρ of the skeleton at t (a
//     Hausdorff bound), so |d_t(p) − d_ref(p)| <= ρ for every p: distance ranges over a box
//     widen to [max(0, dmin − ρ), dmax + ρ] and support boxes grow by ρ;
//   - [weightLo, weightHi] holds the weight at every t (of one sign: the builder checks);
//   - a term whose `field` parameters are animated holds a KernelBox (kernel.h) holding
//     its kernel at every t, and the box functions bound it over that box: supports,
//     cutoffs and Lipschitz constants use its largest radius R_hi (the support of the term
//     at t lies within R_hi + ρ of the reference skeleton), value ranges, slopes and
//     curvatures KernelBox::Bounds; the others keep their one kernel;
//   - for a point skeleton, a box holding its centre at every t (the interval ranges of its
//     coordinates). It lies within the reach of the reference centre, and it bounds tighter:
//     d_t(p) lies between p's nearest and farthest distances to the box, so a box's distance
//     range is the two boxes' nearest and farthest distances, and the support box is the
//     centre box padded by R (a point moving along a line sweeps a thin box, not a ball).
// Field::Bound and the other box functions use these swept bounds, so every octree,
// patch box and neighbour list built from them holds at every time of the shutter. Point
// evaluations (values, gradients, predominance) use the term at the current ray time:
// RayTimeScope sets it for the calling thread, and FieldMotion::Resolve makes the term at
// that time on first use by a ray, caching it per thread (only the terms a ray's search
// touches are ever evaluated). With no ray time set, Resolve gives the reference term. A sum
// over many terms looks the cache up once (FieldMotion::Now) and asks it per term.
#pragma once

#include <cstdint>
#include <functional>
#include <limits>
#include <vector>

#include "libcommon/bounds.h"
#include "libobj/implicit/kernel.h"

namespace rs {

struct FieldTerm;

struct TermMotion {
    bool moving = false;  // false: the term is the same at every time
    double reach = 0;
    double weightLo = 0, weightHi = 0;
    bool centreBoxed = false;  // true: a moving point skeleton whose centre stays in `centres`
    Bounds3 centres;
    bool kernelMoves = false;  // true: the kernel changes, and `kernels` holds it at every t
    KernelBox kernels;
};

class FieldMotion;

// One thread's terms of one moving field at its current ray time (FieldMotion::Now): row r
// is current when its stamp equals the epoch; a new time bumps the epoch (O(1)), so stale
// rows are remade on their next use.
class TermsAtTime {
  public:
    // The term of `row` at this time (`reference`, the table's term of that row, when the
    // row does not move). Valid until the same thread resolves terms of a different time.
    // Inline, in field.h (where FieldTerm is complete).
    inline const FieldTerm& Of(int row, const FieldTerm& reference);

  private:
    friend class FieldMotion;
    const FieldTerm& Make(int row, const FieldTerm& reference);

    const FieldMotion* motion_ = nullptr;
    uint64_t id_ = 0;
    double time_ = std::numeric_limits<double>::quiet_NaN();
    uint64_t epoch_ = 1;
    uint64_t lastUse_ = 0;
    std::vector<uint64_t> stamp_;  // 0: the row's slot holds no term yet
    std::vector<FieldTerm> terms_;
};

class FieldMotion {
  public:
    // Sets term.skeleton, term.weight and term.kernel to their values at `time` for row
    // `row` (the rest of `term` already holds the reference term's other members).
    using TermAt = std::function<void(int row, double time, FieldTerm& term)>;

    FieldMotion(std::vector<TermMotion> terms, TermAt termAt);

    const TermMotion& Of(int row) const { return terms_[row]; }
    // The term of `row` at the calling thread's ray time (RayTimeScope), or `reference`
    // (the table's term of that row) when the row does not move or no time is set. The
    // reference stays valid until the same thread resolves terms of a different time.
    const FieldTerm& Resolve(int row, const FieldTerm& reference) const;
    // The calling thread's terms at its ray time, or null when no ray time is set (every
    // row then is its reference term). One lookup serves a whole sum; asked again by the
    // same motion with no change of time in between, it answers inline.
    inline TermsAtTime* Now() const;

  private:
    friend class TermsAtTime;
    // Now() when the thread's last answer does not hold: finds or makes this motion's cache.
    TermsAtTime* FindNow() const;
    std::vector<TermMotion> terms_;
    TermAt termAt_;
    uint64_t id_;  // unique per FieldMotion: the key of the per-thread caches
};

namespace field_motion_detail {

// The calling thread's ray time, and what FieldMotion::Now() answered last (a cache, or
// null with no time set): still the answer while the same motion asks again with no change
// of time in between (`changes` counts the RayTimeScope changes).
struct ThreadRayTime {
    double time = std::numeric_limits<double>::quiet_NaN();
    uint64_t changes = 0;
    uint64_t lastId = 0;  // 0: none (motion ids start at 1)
    uint64_t lastChanges = 0;
    TermsAtTime* last = nullptr;
};
inline thread_local ThreadRayTime tRayTime;

}  // namespace field_motion_detail

inline TermsAtTime* FieldMotion::Now() const {
    const field_motion_detail::ThreadRayTime& now = field_motion_detail::tRayTime;
    if (now.lastId == id_ && now.lastChanges == now.changes) return now.last;
    return FindNow();
}

// The ray time meaning none: reference terms.
inline constexpr double kNoRayTime = std::numeric_limits<double>::quiet_NaN();

// Sets the ray time the calling thread's field evaluations use, for the scope's lifetime
// (restoring the previous one after); kNoRayTime (any NaN) means none.
class RayTimeScope {
  public:
    explicit RayTimeScope(double time);
    ~RayTimeScope();
    RayTimeScope(const RayTimeScope&) = delete;
    RayTimeScope& operator=(const RayTimeScope&) = delete;

  private:
    double previous_;
};

}  // namespace rs
