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

#include <memory>
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
    explicit Field(std::vector<FieldTerm> terms) : terms_(std::move(terms)) {}

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
    FieldBound Bound(const Bounds3& box) const;
    // [lo, hi] containing w_i f_i(d_i(p)) for every p in the box (f is monotone in d).
    void TermRange(int i, const Bounds3& box, double& lo, double& hi) const;

    // The box outside of which every term vanishes (skeleton boxes padded by R).
    Bounds3 SupportBounds() const;

  private:
    std::vector<FieldTerm> terms_;
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
