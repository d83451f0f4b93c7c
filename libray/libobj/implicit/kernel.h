// Layer 3 of the implicit module: field kernels, functions f(r) of the distance r >= 0 to a
// skeleton, with compact support [0, R).
//
// Gascuel kernels (Gascuel 1995 §1.2, with the outer cubic corrected as in the research
// note §2.1), parameters thickness e, stiffness k, influence radius R, 0 < e < R, k > 0:
//   linear inner    (r <= e): 1 − k(r − e)                      f' = −k,      f'' = 0
//   quadratic inner (r <= e): 1 − ½(r − e)(kr/e + k)
//                           = 1 + ke/2 − k r²/(2e)              f' = −kr/e,   f'' = −k/e
//   outer (e < r < R), Hermite form with ℓ = R − e, s = (r − e)/ℓ, m = kℓ:
//       g = (2s³ − 3s² + 1) − m(s³ − 2s² + s)
//       g' = [6s² − 6s − m(3s² − 4s + 1)]/ℓ,   g'' = [12s − 6 − m(6s − 4)]/ℓ²
//     so g(e) = 1, g'(e) = −k, g(R) = g'(R) = 0 (C¹ everywhere, f'' jumps at e and R).
//     Equivalent to (r − R)²(ar + b) with a = −(k(e − R) + 2)/(e − R)³,
//     b = (ke² − keR + 3e − R)/(e − R)³ (the printed paper coefficients are wrong).
//   f = 0 for r >= R.
// Validity: g >= 0 and g decreasing on [e, R] exactly when m = k(R − e) <= 3 (the paper's
// condition (3 + ek)/(Rk) >= 1). Validate() rejects other parameters.
//
// Blob kernel (Rayshade 4.0 blob, Wyvill-like): f = s(1 − r²/R²)² for r < R, 0 beyond;
//   f' = −4 s r (1 − r²/R²)/R²,  f'' = −(4s/R²)(1 − 3r²/R²),  f'/r = −(4s/R²)(1 − r²/R²).
//
// All valid kernels are non-increasing in r, which the interval bounds below use.
#pragma once

#include <string>

namespace rs {

enum class KernelKind { GascuelLinear, GascuelQuadratic, Blob };

// Bounds of a kernel over a distance interval [rmin, rmax].
struct KernelBounds {
    double valueMin = 0, valueMax = 0;  // exact range of f (f is monotone)
    double maxSlope = 0;                // max |f'| (exact up to the candidate-point method)
    // max over the interval of max(|f''|, |f'|/r), one-sided values of f'' at the jumps
    // included; +infinity when the interval reaches r = 0 and |f'|/r is unbounded there.
    double maxCurvature = 0;
};

struct KernelStatus {
    bool ok = true;
    std::string message;  // names the skeleton when !ok
};

class Kernel {
  public:
    Kernel() = default;
    static Kernel GascuelLinear(double thickness, double stiffness, double radius);
    static Kernel GascuelQuadratic(double thickness, double stiffness, double radius);
    static Kernel Blob(double strength, double radius);

    KernelKind Kind() const { return kind_; }
    double Radius() const { return radius_; }
    double Thickness() const { return thickness_; }
    double Stiffness() const { return stiffness_; }
    double Strength() const { return strength_; }
    // The same kernel: kind and every parameter equal.
    bool operator==(const Kernel&) const = default;

    // Checks the parameter conditions (0 < e < R, k > 0, k(R − e) <= 3; blob s > 0, R > 0).
    KernelStatus Validate(const std::string& skeletonName) const;

    // Inline: the field sums call them once per term and evaluation.
    double Value(double r) const { return PieceValue(PieceOf(r), r); }
    double Derivative(double r) const { return PieceDerivative(PieceOf(r), r); }
    // f'' with the value of the piece that contains r (pieces: [0, e], (e, R), [R, ∞)).
    double SecondDerivative(double r) const;

    // Bounds over [rmin, rmax] (0 <= rmin <= rmax). Requires a valid kernel.
    KernelBounds Bounds(double rmin, double rmax) const;

  private:
    // Pieces of a kernel: the inner part, the outer part (Gascuel only) and the zero tail.
    static constexpr int kInner = 0, kOuter = 1, kZero = 2;
    // One piece of the kernel on [lo, hi].
    double PieceValue(int piece, double r) const;
    double PieceDerivative(int piece, double r) const;
    double PieceSecond(int piece, double r) const;
    int PieceOf(double r) const;

    KernelKind kind_ = KernelKind::Blob;
    double thickness_ = 0, stiffness_ = 0, radius_ = 1, strength_ = 1;
};

inline int Kernel::PieceOf(double r) const {
    if (r >= radius_) return kZero;
    if (kind_ == KernelKind::Blob || r <= thickness_) return kInner;
    return kOuter;
}

inline double Kernel::PieceValue(int piece, double r) const {
    double e = thickness_, k = stiffness_;
    switch (piece) {
        case kInner:
            if (kind_ == KernelKind::Blob) {
                double q = 1 - r * r / (radius_ * radius_);
                return strength_ * q * q;
            }
            if (kind_ == KernelKind::GascuelLinear) return 1 - k * (r - e);
            return 1 + 0.5 * k * e - 0.5 * k * r * r / e;
        case kOuter: {
            double l = radius_ - e, s = (r - e) / l, m = k * l;
            return (2 * s * s * s - 3 * s * s + 1) - m * (s * s * s - 2 * s * s + s);
        }
        default:
            return 0;
    }
}

inline double Kernel::PieceDerivative(int piece, double r) const {
    double e = thickness_, k = stiffness_;
    switch (piece) {
        case kInner:
            if (kind_ == KernelKind::Blob) {
                double r2 = radius_ * radius_;
                return -4 * strength_ * r * (1 - r * r / r2) / r2;
            }
            if (kind_ == KernelKind::GascuelLinear) return -k;
            return -k * r / e;
        case kOuter: {
            double l = radius_ - e, s = (r - e) / l, m = k * l;
            return (6 * s * s - 6 * s - m * (3 * s * s - 4 * s + 1)) / l;
        }
        default:
            return 0;
    }
}

// Every kernel of one kind whose parameters lie in a box: thickness, stiffness and radius
// (Gascuel) or strength and radius (blob) each between its value in Lo() and in Hi() (the
// kernels of a term whose `field` parameters are animated, over an open shutter:
// field_motion.h). The bounds rest on these facts about valid kernels (proofs beside
// KernelBox::Bounds in kernel.cpp; tests/unit/implicit/kernel_test.cpp samples them):
//   Gascuel: f rises with e and with R, and is affine in k (for fixed r and the others);
//   blob: f rises with s and with R.
// Each validity condition (e > 0, R − e > 0, k > 0, k(R − e) <= 3; s > 0, R > 0) is monotone
// in each parameter, so when every corner of the box is valid every kernel in it is.
class KernelBox {
  public:
    KernelBox() = default;
    // `lo` and `hi` of one kind, each parameter of lo at most hi's.
    KernelBox(const Kernel& lo, const Kernel& hi) : lo_(lo), hi_(hi) {}

    const Kernel& Lo() const { return lo_; }
    const Kernel& Hi() const { return hi_; }
    // The largest radius: every kernel of the box is 0 for r >= Radius().
    double Radius() const { return hi_.Radius(); }

    // Validate() of every corner; the first invalid one's message, with the box's ranges.
    KernelStatus Validate(const std::string& skeletonName) const;

    // Bounds holding for every kernel of the box over [rmin, rmax] (0 <= rmin <= rmax), with
    // Kernel::Bounds' contract (valueMin, valueMax: the exact range over the box, up to the
    // rounding of the corner kernels' values; maxSlope, maxCurvature: upper bounds, exact
    // up to rounding when the box is one kernel, looser the wider it is, since the pieces'
    // variables are bounded separately). Requires a valid box.
    KernelBounds Bounds(double rmin, double rmax) const;
    // valueMin and valueMax of Bounds alone: [min, max] of f over the box and [rmin, rmax].
    void ValueRange(double rmin, double rmax, double& lo, double& hi) const;

  private:
    Kernel lo_, hi_;
};

}  // namespace rs
