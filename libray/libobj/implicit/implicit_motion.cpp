#include "libobj/implicit/implicit_motion.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <tuple>
#include <utility>
#include <variant>

#include "libcommon/error.h"
#include "libobj/implicit/implicit_block.h"

namespace rs {

namespace {

// The interval bounds of one skeleton's numbers over [t0, t1], around their reference
// values; `ok` false when some number has no finite bound. Ranges are the union of those
// over kPieces equal sub-intervals, tighter than one interval evaluation (interval
// arithmetic overestimates less on shorter intervals) and as rigorous.
class NumberMotion {
  public:
    static constexpr int kPieces = 16;

    NumberMotion(const ImplicitDescription& d, const SkeletonSpec& e, double t0, double t1)
        : d_(d), e_(e), t0_(t0), t1_(t1), tm_(0.5 * (t0 + t1)) {}

    bool ok = true;

    // The range of the block's number `index` over sub-interval `piece` of [t0, t1].
    std::pair<double, double> PieceRangeOf(size_t index, int piece) {
        const double a = t0_ + (t1_ - t0_) * piece / kPieces;
        const double b = piece + 1 == kPieces ? t1_ : t0_ + (t1_ - t0_) * (piece + 1) / kPieces;
        const auto r = d_.numbers.Range(index, a, b);
        if (!std::isfinite(r.first) || !std::isfinite(r.second)) ok = false;
        return r;
    }
    std::pair<double, double> RangeOf(size_t index) {
        auto r = PieceRangeOf(index, 0);
        for (int k = 1; k < kPieces; ++k) {
            const auto p = PieceRangeOf(index, k);
            r = {std::min(r.first, p.first), std::max(r.second, p.second)};
        }
        return r;
    }
    // The same for the skeleton's own number i.
    std::pair<double, double> PieceRange(size_t i, int piece) {
        return PieceRangeOf(e_.firstNumber + i, piece);
    }
    std::pair<double, double> Range(size_t i) { return RangeOf(e_.firstNumber + i); }
    double Value(size_t i) const { return d_.numbers.At(e_.firstNumber + i, tm_); }
    // How far number i may be from its reference value.
    double Delta(size_t i) {
        const auto [lo, hi] = Range(i);
        const double v = Value(i);
        return std::max({hi - v, v - lo, 0.0});
    }
    Vec3 Deltas(size_t i) { return {Delta(i), Delta(i + 1), Delta(i + 2)}; }
    double PointDelta(size_t i) { return Length(Deltas(i)); }
    // The bound on the turn of the unit vector of the reference vector `v` (numbers i..i+2
    // or a difference with change bound `change`): min(2, 2|ΔN|/|N|).
    static double TurnBound(const Vec3& v, double change) {
        const double length = Length(v);
        return length > 0 ? std::min(2.0, 2 * change / length) : 2.0;
    }

  private:
    const ImplicitDescription& d_;
    const SkeletonSpec& e_;
    double t0_, t1_, tm_;
};

// Whether the vector of numbers i..i+2 may vanish: its box over some sub-interval holds 0.
bool MayVanish(NumberMotion& m, size_t i) {
    for (int k = 0; k < NumberMotion::kPieces; ++k) {
        bool holdsZero = true;
        for (size_t c = 0; c < 3; ++c) {
            const auto [lo, hi] = m.PieceRange(i + c, k);
            holdsZero &= lo <= 0 && hi >= 0;
        }
        if (holdsZero) return true;
    }
    return false;
}

// The reach of skeleton `e` (implicit_motion.h), or an error message.
std::string SkeletonReach(NumberMotion& m, const SkeletonSpec& e, const char* who,
                          double& reach) {
    reach = 0;
    switch (e.kind) {
        case SkeletonKind::Point:
        case SkeletonKind::Segment:
        case SkeletonKind::Polyline:
        case SkeletonKind::Triangle:
            for (size_t i = 0; i + 2 < e.numberCount; i += 3) reach = std::max(reach, m.PointDelta(i));
            break;
        case SkeletonKind::Box: {
            const Vec3 a = m.Deltas(0), b = m.Deltas(3);
            reach = Length(Max(a, b));
            break;
        }
        case SkeletonKind::Circle: {
            if (m.Range(0).first <= 0 || MayVanish(m, 4)) {
                return StringPrintf("skeleton '%s': the circle's radius or normal may reach 0 "
                                    "during the shutter", who);
            }
            const Vec3 normal{m.Value(4), m.Value(5), m.Value(6)};
            reach = m.PointDelta(1) + m.Delta(0) +
                    m.Value(0) * NumberMotion::TurnBound(normal, m.PointDelta(4));
            break;
        }
        case SkeletonKind::Cylinder: {
            if (m.Range(0).first < 0) {
                return StringPrintf("skeleton '%s': the cylinder's radius may be negative "
                                    "during the shutter", who);
            }
            const Vec3 axis = Vec3{m.Value(4), m.Value(5), m.Value(6)} -
                              Vec3{m.Value(1), m.Value(2), m.Value(3)};
            const double da = m.PointDelta(1), db = m.PointDelta(4);
            reach = std::max(da, db) + m.Delta(0) +
                    m.Value(0) * NumberMotion::TurnBound(axis, da + db);
            break;
        }
    }
    reach *= 1 + 1e-12;
    return {};
}

// The box of skeleton `index`'s kernels over the interval (kernel.h): each parameter's
// range; an error message when some corner is not a valid kernel, with `place` set to the
// `field` statement.
std::string KernelMotion(const ImplicitDescription& d, size_t index, NumberMotion& m,
                         TermMotion& motion, StatementPlace& place) {
    const KernelSpec& k = d.kernels[d.skeletons[index].kernel];
    double lo[3] = {}, hi[3] = {};
    for (int i = 0; i < k.paramCount; ++i) std::tie(lo[i], hi[i]) = m.RangeOf(k.params[i]);
    if (!m.ok) return {};  // reported with the other unbounded numbers
    motion.kernelMoves = true;
    motion.kernels = KernelBox(KernelWithParameters(k.kind, lo), KernelWithParameters(k.kind, hi));
    KernelStatus status = motion.kernels.Validate(d.names.Name(index));
    if (status.ok) return {};
    place = k.place;
    return status.message;
}

// The motion of skeleton `index`, or an error message (about the statement at `place`,
// set to the skeleton's, or its `field` statement's for an invalid kernel box).
std::string TermMotionOf(const ImplicitDescription& d, size_t index, double referenceWeight,
                         double t0, double t1, TermMotion& motion, StatementPlace& place) {
    const SkeletonSpec& e = d.skeletons[index];
    const char* who = d.names.Name(index).c_str();
    place = e.place;
    NumberMotion m(d, e, t0, t1);
    if (std::string error = SkeletonReach(m, e, who, motion.reach); !error.empty()) return error;
    if (HasAnimatedKernel(d, index)) {
        if (std::string error = KernelMotion(d, index, m, motion, place); !error.empty()) {
            return error;
        }
    }
    const auto [wLo, wHi] = m.RangeOf(e.weight);
    if (!m.ok || !std::isfinite(wLo) || !std::isfinite(wHi)) {
        return StringPrintf("skeleton '%s': its motion during the shutter cannot be bounded "
                            "(an expression with no interval bound: a division or power "
                            "by a range holding 0, %%, tan across a pole, asin or acos out "
                            "of [-1, 1])",
                            who);
    }
    if (referenceWeight > 0 ? !(wLo > 0) : !(wHi <= 0)) {
        return StringPrintf("skeleton '%s': its weight changes sign during the shutter", who);
    }
    if (e.kind == SkeletonKind::Point) {
        motion.centreBoxed = true;
        for (size_t c = 0; c < 3; ++c) {
            const auto [lo, hi] = m.Range(c);
            motion.centres.lo[static_cast<int>(c)] = lo;
            motion.centres.hi[static_cast<int>(c)] = hi;
        }
    }
    motion.moving = true;
    motion.weightLo = wLo;
    motion.weightHi = wHi;
    return {};
}

}  // namespace

MovingTerms BuildMovingTerms(const std::shared_ptr<const ImplicitDescription>& block,
                             std::vector<FieldTerm> reference, double t0, double t1) {
    const ImplicitDescription& d = *block;
    MovingTerms out;
    std::vector<TermMotion> motions(d.skeletons.size());
    for (size_t i = 0; i < d.skeletons.size(); ++i) {
        if (!IsAnimatedSkeleton(d, i)) continue;
        out.error = TermMotionOf(d, i, reference[i].weight, t0, t1, motions[i], out.place);
        if (!out.error.empty()) return out;
    }
    // A moving term at a ray time: its skeleton, weight and kernel. The interval checks
    // above keep MakeSkeletonAt from failing inside [t0, t1], and the kernel there lies in
    // its valid box. `term` starts as the reference term, whose static numbers are those of
    // every time: a point (the commonest moving skeleton), the weight and the kernel get
    // only their animated numbers anew.
    // Bits 0–2: a point's coordinates, 3 the weight, 4 the kernel.
    std::vector<uint8_t> animated(d.skeletons.size(), 0);
    for (size_t i = 0; i < d.skeletons.size(); ++i) {
        const SkeletonSpec& e = d.skeletons[i];
        if (e.kind == SkeletonKind::Point) {
            for (size_t c = 0; c < 3; ++c) {
                if (d.numbers.IsAnimated(e.firstNumber + c)) animated[i] |= 1u << c;
            }
        }
        if (d.numbers.IsAnimated(e.weight)) animated[i] |= 8;
        if (HasAnimatedKernel(d, i)) animated[i] |= 16;
    }
    auto termAt = [block, animated = std::move(animated)](int row, double time, FieldTerm& term) {
        const ImplicitDescription& b = *block;
        const SkeletonSpec& e = b.skeletons[row];
        const unsigned changes = animated[row];
        if (e.kind == SkeletonKind::Point) {
            Vec3& centre = std::get<PointSkeleton>(term.skeleton).center;
            for (int c = 0; c < 3; ++c) {
                if ((changes >> c) & 1) centre[c] = b.numbers.At(e.firstNumber + c, time);
            }
        } else {
            MakeSkeletonAt(b, static_cast<size_t>(row), time, term.skeleton);
        }
        if (changes & 8) term.weight = b.numbers.At(e.weight, time);
        if (changes & 16) term.kernel = MakeKernelAt(b, static_cast<size_t>(row), time);
    };
    out.motion = std::make_shared<const FieldMotion>(std::move(motions), std::move(termAt));
    out.reference = std::move(reference);
    return out;
}

}  // namespace rs
