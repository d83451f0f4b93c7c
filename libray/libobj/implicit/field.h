// Layer 4 of the implicit module: a field F(p) = Σ_i w_i f_i(d_i(p)), the weighted sum of
// (skeleton, kernel) terms. Negative weights carve.
//
// Bound(box) returns, over every point of the (closed) box,
//   - [valueMin, valueMax] containing F;
//   - L >= |∇F| (so |F(p) − F(q)| <= L|p − q| inside the box, the box being convex);
//   - G >= |uᵀ∇²F u| for every unit u (the second directional derivative along any line).
// Derivation, per term with distance range [rmin, rmax] (skeleton.h): ∇(f∘d) = f'∇d with
// |∇d| = 1, so |∇| <= max|f'|; ∇²(f∘d) = f''∇d∇dᵀ + f'∇²d, where ∇²d ∇d = 0 and the other
// eigenvalues of ∇²d are bounded by H = max(1/d, X) (skeleton.h: X = 0 for convex kinds,
// ExtraDistanceCurvature otherwise). Writing u = α∇d + βw (w ⊥ ∇d, α² + β² = 1) gives
// |uᵀ∇²(f∘d)u| <= α²|f''| + β²|f'|H <= max(|f''|, |f'|/d, |f'|X): the kernel's
// max(|f''|, |f'|/r) over [rmin, rmax], and max|f'|·X when X > 0. The field is C¹ and
// piecewise C², which is all the Taylor arguments of the LG tests need. Terms whose support
// (d < R) misses the box contribute nothing; the others' bounds add, scaled by |w|.
//
// A field may carry one deformation D (contact.h: compression and propagation between
// colliding patches): F(p) = Σ_i w_i f_i(d_i(p)) + D(p). Value, Gradient and Bound then add
// D's value, gradient and bounds (value ranges, L and G of a sum add); the terms, TermValue,
// TermRange and SupportBounds keep describing the undeformed terms alone (predominance is
// decided on them).
//
// A field may move (field_motion.h: skeleton motion blur): its table then holds reference
// terms and a FieldMotion. Every box function (Bound, TermRange, ActiveTerms, TermsMeeting,
// SupportBounds, TermSupport) then holds for every time of the shutter interval: each
// term's distance range swept over it (field_motion.h: the reach, or a point's centre box),
// weights over their intervals, an animated kernel over its parameter box (KernelBox, with
// its largest radius for supports and cutoffs), and X infinite for a moving non-convex kind; every point function (values, gradients, TermValue, TermAt) uses
// the terms at the calling thread's ray time (RayTimeScope).
#pragma once

#include <cstdint>
#include <limits>
#include <memory>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "libcommon/stats.h"
#include "libobj/implicit/field_motion.h"
#include "libobj/implicit/kernel.h"
#include "libobj/implicit/skeleton.h"

namespace rs {

struct FieldTerm {
    std::string name;
    Skeleton skeleton;
    Kernel kernel;
    double weight = 1;
};

inline const FieldTerm& TermsAtTime::Of(int row, const FieldTerm& reference) {
    return stamp_[row] == epoch_ ? terms_[row] : Make(row, reference);
}

struct FieldBound {
    double valueMin = 0, valueMax = 0;
    double L = 0;  // gradient-norm bound
    double G = 0;  // second-directional-derivative bound (may be +infinity)
    // Smallest lower distance bound among the terms whose support meets the box (+infinity
    // when none does): the "min" of Gascuel's Dratio heuristic.
    double minDistance = 0;
    int activeTerms = 0;
};

struct TermValueRange {
    double lo = 0, hi = 0;
};

// An extra C¹, piecewise C² term of a field. Bound(box) fills valueMin, valueMax, L and G
// with the same contracts as Field::Bound, for the term alone.
class FieldDeformation {
  public:
    virtual ~FieldDeformation() = default;
    virtual double Value(const Vec3& p) const = 0;
    virtual Vec3 Gradient(const Vec3& p) const = 0;
    virtual FieldBound Bound(const Bounds3& box) const = 0;
};

// A field sums some rows of a term table. The table (the terms and their support boxes) is
// shared, not copied, by every copy of the field and every field made from it by Subset, so
// a patch's field costs its row list, not copies of its neighbours' terms. Term indices in
// this interface (TermValue, TermRange, the term lists of the sums, ActiveTerms) are rows of
// the table, i.e. indices into Terms(); a field made from a vector of terms sums all of
// them, in order, so there rows and positions coincide.
class Field {
  public:
    Field() : Field(std::vector<FieldTerm>{}) {}
    // With `motion`, `terms` are the reference terms of a moving field (one TermMotion
    // per term).
    explicit Field(std::vector<FieldTerm> terms,
                   std::shared_ptr<const FieldMotion> motion = nullptr);
    // The field of rows `rows` of this field's table (summed in that order, no repeats),
    // sharing the table; without a deformation.
    Field Subset(std::vector<int> rows) const;

    // Every term of the table, indexed by row (a Subset's table holds non-members too); a
    // moving field's reference terms.
    const std::vector<FieldTerm>& Terms() const { return table_->terms; }
    // The motion of a moving field, else null.
    const FieldMotion* Motion() const { return table_->motion.get(); }
    // Row i's term at the calling thread's ray time (Terms()[i] for a static field).
    const FieldTerm& TermAt(int i) const {
        return table_->motion ? table_->motion->Resolve(i, table_->terms[i]) : table_->terms[i];
    }
    // Whether TermAt gives the terms at a ray time: a moving field with the calling
    // thread's ray time set (false for a static field, whose terms never move).
    bool AtRayTime() const { return table_->motion && table_->motion->Now(); }
    // The box outside of which row i vanishes (at every time of the shutter interval).
    const Bounds3& TermSupport(int i) const { return table_->support[i]; }
    // |w|·max|f'| of row i at every time: its Lipschitz constant in space.
    double TermLipschitz(int i) const;
    // How far row i's support may reach beyond the reference term's (0 for a static
    // field): its skeleton's reach, plus the growth of its kernel radius over the shutter
    // when its kernel moves, so every point where the term is non-zero at some time lies
    // within R_ref + TermReach of the reference skeleton.
    double TermReach(int i) const {
        if (!table_->motion) return 0;
        const TermMotion& m = table_->motion->Of(i);
        return m.kernelMoves ? m.reach + (m.kernels.Radius() - table_->terms[i].kernel.Radius())
                             : m.reach;
    }
    // The rows this field sums, in summation order.
    const std::vector<int>& Rows() const { return rows_; }
    // Adds (or, with nullptr, removes) the deformation term.
    void SetDeformation(std::shared_ptr<const FieldDeformation> deformation) {
        deformation_ = std::move(deformation);
    }
    const FieldDeformation* Deformation() const { return deformation_.get(); }
    // The number of terms the field sums.
    int Size() const { return static_cast<int>(rows_.size()); }

    // w_i f_i(d_i(p)) for row i.
    double TermValue(int i, const Vec3& p) const;
    double Value(const Vec3& p) const;
    // Analytic gradient Σ w_i f_i'(d_i) (p − c_i)/d_i, with c_i the closest skeleton point;
    // terms at d_i = 0 contribute 0 (their gradient is 0 for the quadratic and blob kernels
    // and undefined for the linear one).
    Vec3 Gradient(const Vec3& p) const;
    // Value and Gradient summing only the listed rows, for a list that keeps Rows()' order
    // and holds every row whose support may reach p (e.g. from ActiveTerms or TermsMeeting
    // of a box containing p): the other terms are exactly 0 there, so the sums add the same
    // numbers in the same order and the results are bit-identical to Value(p) and
    // Gradient(p), at the cost of the listed terms only.
    double Value(const Vec3& p, std::span<const int32_t> terms) const;
    Vec3 Gradient(const Vec3& p, std::span<const int32_t> terms) const;
    // Both at once (counted as one value and one gradient evaluation), sharing each term's
    // distance; bit-identical to the two separate calls.
    double ValueAndGradient(const Vec3& p, std::span<const int32_t> terms, Vec3& gradient) const;
    // Appends to `out`, in the order of `terms`, every listed row whose support box meets
    // the (closed) box. Monotone: for a box inside `box`, the rows of this list are a
    // superset of every row meeting it, so a list made for a cell serves all its sub-cells
    // and points (as `terms` of the sums, Bound and ActiveTerms).
    void TermsMeeting(const Bounds3& box, std::span<const int32_t> terms,
                      std::vector<int32_t>& out) const;
    // Appends to `out`, in the order of `terms`, every listed row whose support may meet
    // the box (its support box meets it and its distance range starts below R): every
    // other term and its gradient are exactly 0 at every point of the box. `terms` must
    // hold every row of the field that meets the box (Rows() or a TermsMeeting list).
    void ActiveTerms(const Bounds3& box, std::span<const int32_t> terms,
                     std::vector<int32_t>& out) const;
    FieldBound Bound(const Bounds3& box) const;
    // Bound, from the listed rows only, which must hold every row of the field meeting the
    // box (Rows() or a TermsMeeting list: the others add nothing, so the result is
    // bit-identical to Bound(box)). With termRanges, also stores in (*termRanges)[k] the
    // range [lo, hi] TermRange gives for row terms[k] (the same numbers, computed once for
    // both; termRanges is resized to terms.size()).
    FieldBound Bound(const Bounds3& box, std::span<const int32_t> terms,
                     std::vector<TermValueRange>* termRanges) const;
    // Bound(box) of the field at the calling thread's ray time only (RayTimeScope): for a
    // moving field with a ray time set, every moving term's bounds at that time (tighter
    // than the swept ones, and valid only for searches at that time); else Bound(box).
    FieldBound BoundAtRayTime(const Bounds3& box) const;
    // [lo, hi] containing F(p) at every time of a moving field's shutter interval, from
    // the listed rows (as for Value(p, terms)) and the deformation's value: each term's
    // weight range times the kernel at the ends of its distance range at p over the
    // interval (f is monotone). A cheap point
    // version of Bound's value range, for the octree build.
    void ValueRangeAt(const Vec3& p, std::span<const int32_t> terms, double& lo, double& hi) const;
    // [lo, hi] containing w_i f_i(d_i(p)) for every p in the box (f is monotone in d), row i.
    void TermRange(int i, const Bounds3& box, double& lo, double& hi) const;
    // TermRange of row i at the calling thread's ray time only (as BoundAtRayTime: the
    // static field's TermRange at that time for a moving row with a ray time set, tighter
    // than the swept one and valid only at that time); else TermRange.
    void TermRangeAtRayTime(int i, const Bounds3& box, double& lo, double& hi) const;

    // The box outside of which every term of the field vanishes (skeleton boxes padded by R).
    Bounds3 SupportBounds() const;

  private:
    struct TermTable {
        std::vector<FieldTerm> terms;
        std::vector<Bounds3> support;  // TermSupportBounds of each term, padded by its reach
        std::shared_ptr<const FieldMotion> motion;
    };
    // Subset's field: rows of a shared table (no table of its own is made).
    Field(std::shared_ptr<const TermTable> table, std::vector<int> rows)
        : table_(std::move(table)), rows_(std::move(rows)) {}
    // Row i's distance range over the box at every time, and its weight interval. With a
    // finite `cutoff`, a range whose minimum is at least the cutoff may have its maximum
    // left at the minimum (MovingDistanceRange in the .cpp): only the minimum then holds.
    DistanceRange SweptDistanceRange(
        int i, const Bounds3& box,
        double cutoff = std::numeric_limits<double>::infinity()) const;
    void WeightRange(int i, double& lo, double& hi) const;
    // Row i's motion when it moves, else null.
    const TermMotion* MotionOf(int i) const {
        const FieldMotion* motion = table_->motion.get();
        return motion && motion->Of(i).moving ? &motion->Of(i) : nullptr;
    }
    // Adds the deformation's bounds over the box (if any) to fb.
    void AddDeformationBound(const Bounds3& box, FieldBound& fb) const;

    // The sums of F (into *value) and ∇F (into *gradient) over the rows `indices` yields,
    // as selected; one loop, so ValueAndGradient shares each term's distance.
    template <bool kValue, bool kGradient, class Indices>
    void Sum(const Vec3& p, const Indices& indices, double* value, Vec3* gradient) const;

    // Whether p may lie in the support of row i: false only where d_i(p) >= R_i, so the
    // term and its derivatives are exactly 0 there and the sums may skip it (a box test
    // instead of a distance).
    static bool MayReach(const Bounds3& b, const Vec3& p) {
        return p.x >= b.lo.x && p.x <= b.hi.x && p.y >= b.lo.y && p.y <= b.hi.y &&
               p.z >= b.lo.z && p.z <= b.hi.z;
    }
    // Likewise for a box: false only where the box misses the term's support box, so every
    // point of it is at distance >= R_i (and the distance range's lower end too).
    static bool MayReach(const Bounds3& b, const Bounds3& box) {
        return box.lo.x <= b.hi.x && box.hi.x >= b.lo.x && box.lo.y <= b.hi.y &&
               box.hi.y >= b.lo.y && box.lo.z <= b.hi.z && box.hi.z >= b.lo.z;
    }

    std::shared_ptr<const TermTable> table_;
    std::vector<int> rows_;
    std::shared_ptr<const FieldDeformation> deformation_;
};

// The statistics counters of every Field (libcommon/stats.h), so callers can attribute
// evaluations to an object or a ray by differences of ThreadCount.
struct FieldCounters {
    FieldCounters();
    CounterId values, gradients, bounds;  // Value, Gradient and Bound calls
};
const FieldCounters& FieldCounterIds();

// The box of the support {d < R} of one term.
Bounds3 TermSupportBounds(const FieldTerm& term);

}  // namespace rs
