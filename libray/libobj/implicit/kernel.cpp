#include "libobj/implicit/kernel.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "libcommon/error.h"

namespace rs {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
}  // namespace

Kernel Kernel::GascuelLinear(double thickness, double stiffness, double radius) {
    Kernel k;
    k.kind_ = KernelKind::GascuelLinear;
    k.thickness_ = thickness;
    k.stiffness_ = stiffness;
    k.radius_ = radius;
    return k;
}

Kernel Kernel::GascuelQuadratic(double thickness, double stiffness, double radius) {
    Kernel k = GascuelLinear(thickness, stiffness, radius);
    k.kind_ = KernelKind::GascuelQuadratic;
    return k;
}

Kernel Kernel::Blob(double strength, double radius) {
    Kernel k;
    k.kind_ = KernelKind::Blob;
    k.strength_ = strength;
    k.radius_ = radius;
    return k;
}

KernelStatus Kernel::Validate(const std::string& skeletonName) const {
    const char* who = skeletonName.c_str();
    if (kind_ == KernelKind::Blob) {
        if (!(strength_ > 0) || !(radius_ > 0)) {
            return {false, StringPrintf("skeleton '%s': blob field needs strength > 0 and "
                                        "radius > 0 (got %g, %g)",
                                        who, strength_, radius_)};
        }
        return {};
    }
    double e = thickness_, k = stiffness_, r = radius_;
    if (!(e > 0) || !(r > e) || !(k > 0)) {
        return {false, StringPrintf("skeleton '%s': field needs 0 < thickness < radius and "
                                    "stiffness > 0 (got thickness %g, stiffness %g, radius %g)",
                                    who, e, k, r)};
    }
    // Positivity and monotonicity of the outer cubic: m = k(R − e) <= 3 (kernel.h).
    double m = k * (r - e);
    if (m > 3) {
        return {false, StringPrintf("skeleton '%s': stiffness·(radius − thickness) = %g exceeds 3, "
                                    "so the field would turn negative outside the thickness; "
                                    "lower the stiffness to at most %g or the radius to at most %g",
                                    who, m, 3 / (r - e), e + 3 / k)};
    }
    return {};
}

double Kernel::PieceSecond(int piece, double r) const {
    double e = thickness_, k = stiffness_;
    switch (piece) {
        case kInner:
            if (kind_ == KernelKind::Blob) {
                double r2 = radius_ * radius_;
                return -4 * strength_ * (1 - 3 * r * r / r2) / r2;
            }
            if (kind_ == KernelKind::GascuelLinear) return 0;
            return -k / e;
        case kOuter: {
            double l = radius_ - e, s = (r - e) / l, m = k * l;
            return (12 * s - 6 - m * (6 * s - 4)) / (l * l);
        }
        default:
            return 0;
    }
}

double Kernel::SecondDerivative(double r) const { return PieceSecond(PieceOf(r), r); }

// Candidate-point method: on each piece met by [rmin, rmax], |f'| is maximal at an end of
// the clipped piece or where f'' = 0 inside it; |f''| is monotone on each piece (constant,
// linear in r, or linear in r² for the blob) so its maximum is at an end, evaluated with
// that piece's formula (this takes the larger side of every jump of f''). |f'|/r:
//   linear inner k/r (largest at the lower end, infinite at r = 0), quadratic inner k/e,
//   blob (4s/R²)(1 − r²/R²) (largest at the lower end), outer <= max|f'| / (lower end),
//   the lower end being >= e > 0 there.
KernelBounds Kernel::Bounds(double rmin, double rmax) const {
    KernelBounds kb;
    rmin = std::max(rmin, 0.0);
    rmax = std::max(rmax, rmin);
    kb.valueMin = Value(rmax);
    kb.valueMax = Value(rmin);
    double e = thickness_, big = radius_;
    double pieceLo[2], pieceHi[2];
    int pieces;
    if (kind_ == KernelKind::Blob) {
        pieces = 1;
        pieceLo[0] = 0;
        pieceHi[0] = big;
    } else {
        pieces = 2;
        pieceLo[0] = 0;
        pieceHi[0] = e;
        pieceLo[1] = e;
        pieceHi[1] = big;
    }
    for (int p = 0; p < pieces; ++p) {
        double a = std::max(rmin, pieceLo[p]), b = std::min(rmax, pieceHi[p]);
        if (a > b) continue;
        // Interior critical point of f' (f'' = 0), if any.
        double critical = -1;
        if (kind_ == KernelKind::Blob) {
            critical = big / std::sqrt(3.0);
        } else if (p == kOuter) {
            double l = big - e, m = stiffness_ * l;
            if (m != 2) critical = e + l * (3 - 2 * m) / (6 - 3 * m);
        }
        double slope = std::max(std::abs(PieceDerivative(p, a)), std::abs(PieceDerivative(p, b)));
        if (critical > a && critical < b) {
            slope = std::max(slope, std::abs(PieceDerivative(p, critical)));
        }
        double second = std::max(std::abs(PieceSecond(p, a)), std::abs(PieceSecond(p, b)));
        double overR;
        if (kind_ == KernelKind::Blob) {
            overR = 4 * strength_ * (1 - a * a / (big * big)) / (big * big);
        } else if (p == kInner) {
            overR = kind_ == KernelKind::GascuelLinear ? (a > 0 ? stiffness_ / a : kInf)
                                                       : stiffness_ / e;
        } else {
            overR = slope / a;
        }
        kb.maxSlope = std::max(kb.maxSlope, slope);
        kb.maxCurvature = std::max({kb.maxCurvature, second, overR});
    }
    return kb;
}

}  // namespace rs
