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

namespace {

// The corner of the box [lo, hi] whose parameter j (Gascuel: 0 thickness, 1 stiffness,
// 2 radius; blob: 0 strength, 2 radius) is hi's when bit j of `upper` is set, else lo's.
Kernel Corner(const Kernel& lo, const Kernel& hi, unsigned upper) {
    const auto pick = [&](unsigned bit, double l, double h) { return (upper >> bit) & 1 ? h : l; };
    const double radius = pick(2, lo.Radius(), hi.Radius());
    if (lo.Kind() == KernelKind::Blob) return Kernel::Blob(pick(0, lo.Strength(), hi.Strength()), radius);
    const double e = pick(0, lo.Thickness(), hi.Thickness());
    const double k = pick(1, lo.Stiffness(), hi.Stiffness());
    return lo.Kind() == KernelKind::GascuelLinear ? Kernel::GascuelLinear(e, k, radius)
                                                  : Kernel::GascuelQuadratic(e, k, radius);
}

constexpr unsigned kFirst = 1, kStiffness = 2, kRadius = 4;

}  // namespace

KernelStatus KernelBox::Validate(const std::string& skeletonName) const {
    for (unsigned upper = 0; upper < 8; ++upper) {
        KernelStatus status = Corner(lo_, hi_, upper).Validate(skeletonName);
        if (status.ok) continue;
        if (lo_.Kind() == KernelKind::Blob) {
            status.message += StringPrintf(
                "; over the shutter its blob field spans strength [%g, %g] and radius [%g, %g], "
                "and every corner of that box must be a valid field",
                lo_.Strength(), hi_.Strength(), lo_.Radius(), hi_.Radius());
        } else {
            status.message += StringPrintf(
                "; over the shutter its field spans thickness [%g, %g], stiffness [%g, %g] and "
                "radius [%g, %g], and every corner of that box must be a valid field",
                lo_.Thickness(), hi_.Thickness(), lo_.Stiffness(), hi_.Stiffness(),
                lo_.Radius(), hi_.Radius());
        }
        return status;
    }
    return {};
}

// The value range rests on the monotonicity of f in its parameters, at fixed r, for valid
// kernels (on a valid box every kernel between two of its points is valid, so the segment
// joining them may be followed):
//   - blob s(1 − r²/R²)² (0 for r >= R): rises with s, and with R since 1 − r²/R² >= 0 does;
//   - Gascuel, affine in k on every piece (the pieces' ends e and R do not depend on k; the
//     outer part is H0(s) − kℓ·H1(s) with s = (r − e)/ℓ free of k);
//   - Gascuel, rising with R: the inner parts do not depend on R, the tail is 0, and on the
//     outer part (H0 = 2s³ − 3s² + 1, H1 = s(1 − s)², g = H0 − m·H1, m = kℓ, ℓ = R − e),
//     with ds/dℓ = −s/ℓ and dm/dℓ = m/ℓ,
//       dg/dℓ = −(s·g_s + m·H1)/ℓ = −2s²(1 − s)(m − 3)/ℓ >= 0 (m <= 3), as
//       g_s = −6s(1 − s) − m(1 − s)(1 − 3s);
//   - Gascuel, rising with e: the linear inner part 1 − k(r − e) and the quadratic one
//     1 + ke/2 − kr²/(2e) (derivative k/2 + kr²/(2e²)) rise with e; on the outer part, with
//     ds/de = (s − 1)/ℓ and dm/de = −m/ℓ,
//       dg/de = ((s − 1)·g_s + m·H1)/ℓ = (1 − s)²(m + 2s(3 − m))/ℓ >= 0;
//     f is continuous in (r, e) (f(e) = 1 from both sides), so it rises across r = e too.
// Every f is non-increasing in r, so the minimum is at (rmax, e_lo, R_lo, s_lo) and the
// maximum at (rmin, e_hi, R_hi, s_hi), over k at one of its ends (affine).
void KernelBox::ValueRange(double rmin, double rmax, double& lo, double& hi) const {
    if (lo_.Kind() == KernelKind::Blob) {
        lo = lo_.Value(rmax);
        hi = hi_.Value(rmin);
        return;
    }
    lo = std::min(lo_.Value(rmax), Corner(lo_, hi_, kStiffness).Value(rmax));
    hi = std::max(hi_.Value(rmin), Corner(lo_, hi_, kFirst | kRadius).Value(rmin));
}

// Slopes and curvatures: each piece's |f'|, |f''| and |f'|/r written in variables bounded
// separately over the box and the distance interval, each bound attained by one corner of
// those variables' box (so exact for a one-kernel box, looser for wider ones).
//   Blob, u = r/R in [rmin/R_hi, min(1, rmax/R_lo)]: f' = −4s·u(1 − u²)/R, u(1 − u²) rising
//     up to u = 1/√3 then falling; f'' = −(4s/R²)(1 − 3u²), |1 − 3u²| largest at an end;
//     f'/r = −(4s/R²)(1 − u²), largest at the lower end.
//   Gascuel inner piece (r <= e <= e_hi, so only when rmin <= e_hi): linear |f'| = k,
//     |f'|/r = k/r, f'' = 0; quadratic |f'| = kr/e <= k·min(1, min(rmax, e_hi)/e_lo),
//     |f''| = |f'|/r = k/e <= k_hi/e_lo.
//   Gascuel outer piece (e < r < R): ℓ >= ℓ_min = R_lo − e_hi > 0, m = kℓ in
//     [k_lo·ℓ_min, k_hi(R_hi − e_lo)] and s in [s_lo, s_hi], where s rises with r and falls
//     with R and with e (∂s/∂e = (r − R)/ℓ² <= 0) on the piece, so s >= (rmin − e_hi)/(R_hi −
//     e_hi) when rmin > e_hi (else s >= 0) and s <= (rmax − e_lo)/(R_lo − e_lo) when rmax <
//     R_lo (else s <= 1). |f'| = |P(s, m)|/ℓ with P = 6s² − 6s − m(3s² − 4s + 1), affine in
//     m (largest at an end of m's range) and quadratic in s (largest at an end of s's range
//     or at its vertex (3 − 2m)/(6 − 3m)); |f''| = |Q(s, m)|/ℓ² with Q = 12s − 6 − m(6s − 4),
//     bilinear (largest at a corner); |f'|/r <= max|f'|/max(rmin, e_lo) (r > e >= e_lo).
KernelBounds KernelBox::Bounds(double rmin, double rmax) const {
    KernelBounds kb;
    rmin = std::max(rmin, 0.0);
    rmax = std::max(rmax, rmin);
    ValueRange(rmin, rmax, kb.valueMin, kb.valueMax);
    const double rLo = lo_.Radius(), rHi = hi_.Radius();
    if (rmin >= rHi) return kb;  // every kernel and its derivatives are 0 there
    if (lo_.Kind() == KernelKind::Blob) {
        const double uLo = rmin / rHi, uHi = std::min(1.0, rmax / rLo);
        const auto rise = [](double u) { return u * (1 - u * u); };
        const double peak = 1 / std::sqrt(3.0);
        const double most = uLo < peak && peak < uHi ? rise(peak) : std::max(rise(uLo), rise(uHi));
        const double scale = 4 * hi_.Strength() / rLo;
        kb.maxSlope = scale * most;
        kb.maxCurvature = scale / rLo *
                          std::max({std::abs(1 - 3 * uLo * uLo), std::abs(1 - 3 * uHi * uHi),
                                    1 - uLo * uLo});
        return kb;
    }
    const double eLo = lo_.Thickness(), eHi = hi_.Thickness();
    const double kLo = lo_.Stiffness(), kHi = hi_.Stiffness();
    if (rmin <= eHi) {
        if (lo_.Kind() == KernelKind::GascuelLinear) {
            kb.maxSlope = kHi;
            kb.maxCurvature = rmin > 0 ? kHi / rmin : kInf;
        } else {
            kb.maxSlope = kHi * std::min(1.0, std::min(rmax, eHi) / eLo);
            kb.maxCurvature = kHi / eLo;
        }
    }
    if (rmax > eLo) {
        const double sLo = rmin > eHi ? std::min(1.0, (rmin - eHi) / (rHi - eHi)) : 0;
        const double sHi = rmax < rLo ? std::max(0.0, (rmax - eLo) / (rLo - eLo)) : 1;
        const double lMin = rLo - eHi;
        double slope = 0, second = 0;
        for (const double m : {kLo * lMin, kHi * (rHi - eLo)}) {
            const auto p = [m](double s) { return 6 * s * s - 6 * s - m * (3 * s * s - 4 * s + 1); };
            const auto q = [m](double s) { return 12 * s - 6 - m * (6 * s - 4); };
            slope = std::max({slope, std::abs(p(sLo)), std::abs(p(sHi))});
            if (m != 2) {
                const double vertex = (3 - 2 * m) / (6 - 3 * m);
                if (vertex > sLo && vertex < sHi) slope = std::max(slope, std::abs(p(vertex)));
            }
            second = std::max({second, std::abs(q(sLo)), std::abs(q(sHi))});
        }
        slope /= lMin;
        kb.maxSlope = std::max(kb.maxSlope, slope);
        kb.maxCurvature = std::max({kb.maxCurvature, second / (lMin * lMin),
                                    slope / std::max(rmin, eLo)});
    }
    return kb;
}

}  // namespace rs
