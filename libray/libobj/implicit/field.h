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
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "libcommon/stats.h"
#include "libobj/implicit/kernel.h"
#include "libobj/implicit/skeleton.h"

namespace rs {

struct FieldTerm {
    std::string name;
    Skeleton skeleton;
    Kernel kernel;
    double weight = 1;
};

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

class Field {
  public:
    Field() = default;
    explicit Field(std::vector<FieldTerm> terms);

    const std::vector<FieldTerm>& Terms() const { return terms_; }
    // Adds (or, with nullptr, removes) the deformation term.
    void SetDeformation(std::shared_ptr<const FieldDeformation> deformation) {
        deformation_ = std::move(deformation);
    }
    const FieldDeformation* Deformation() const { return deformation_.get(); }
    int Size() const { return static_cast<int>(terms_.size()); }

    // w_i f_i(d_i(p)).
    double TermValue(int i, const Vec3& p) const;
    double Value(const Vec3& p) const;
    // Analytic gradient Σ w_i f_i'(d_i) (p − c_i)/d_i, with c_i the closest skeleton point;
    // terms at d_i = 0 contribute 0 (their gradient is 0 for the quadratic and blob kernels
    // and undefined for the linear one).
    Vec3 Gradient(const Vec3& p) const;
    // Value and Gradient summing only the listed terms (indices in increasing order), for a
    // list from ActiveTerms(box) with p in that box: the other terms are exactly 0 there, so
    // the sums add the same numbers in the same order and the results are bit-identical to
    // Value(p) and Gradient(p), at the cost of the listed terms only.
    double Value(const Vec3& p, std::span<const int32_t> terms) const;
    Vec3 Gradient(const Vec3& p, std::span<const int32_t> terms) const;
    // Both at once (counted as one value and one gradient evaluation), sharing each term's
    // distance; bit-identical to the two separate calls.
    double ValueAndGradient(const Vec3& p, std::span<const int32_t> terms, Vec3& gradient) const;
    // Appends to `out`, in increasing order, every term whose support may meet the box (its
    // support box meets it and its distance range starts below R): every other term and its
    // gradient are exactly 0 at every point of the box.
    void ActiveTerms(const Bounds3& box, std::vector<int32_t>& out) const;
    FieldBound Bound(const Bounds3& box) const;
    // Bound, also storing in termRanges[i] the range [lo, hi] TermRange gives for term i
    // (the same numbers, computed once for both; termRanges is resized to Size()).
    FieldBound Bound(const Bounds3& box, std::vector<TermValueRange>& termRanges) const;
    // [lo, hi] containing w_i f_i(d_i(p)) for every p in the box (f is monotone in d).
    void TermRange(int i, const Bounds3& box, double& lo, double& hi) const;

    // The box outside of which every term vanishes (skeleton boxes padded by R).
    Bounds3 SupportBounds() const;

  private:
    // The sums of F (into *value) and ∇F (into *gradient) over the term indices `indices`
    // yields, as selected; one loop, so ValueAndGradient shares each term's distance.
    template <bool kValue, bool kGradient, class Indices>
    void Sum(const Vec3& p, const Indices& indices, double* value, Vec3* gradient) const;
    FieldBound BoundImpl(const Bounds3& box, std::vector<TermValueRange>* termRanges) const;

    // Whether p may lie in the support of term i: false only where d_i(p) >= R_i, so the
    // term and its derivatives are exactly 0 there and the sums may skip it (a box test
    // instead of a distance).
    bool MayReach(int i, const Vec3& p) const {
        const Bounds3& b = support_[i];
        return p.x >= b.lo.x && p.x <= b.hi.x && p.y >= b.lo.y && p.y <= b.hi.y &&
               p.z >= b.lo.z && p.z <= b.hi.z;
    }
    // Likewise for a box: false only where the box misses the term's support box, so every
    // point of it is at distance >= R_i (and the distance range's lower end too).
    bool MayReach(int i, const Bounds3& box) const {
        const Bounds3& b = support_[i];
        return box.lo.x <= b.hi.x && box.hi.x >= b.lo.x && box.lo.y <= b.hi.y &&
               box.hi.y >= b.lo.y && box.lo.z <= b.hi.z && box.hi.z >= b.lo.z;
    }

    std::vector<FieldTerm> terms_;
    std::vector<Bounds3> support_;  // TermSupportBounds of each term
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
