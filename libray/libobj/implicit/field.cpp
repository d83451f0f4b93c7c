#include "libobj/implicit/field.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "libcommon/stats.h"

namespace rs {

FieldCounters::FieldCounters()
    : values(RegisterCounter("Implicit field evaluations")),
      gradients(RegisterCounter("Implicit gradient evaluations")),
      bounds(RegisterCounter("Implicit bound evaluations")) {}

const FieldCounters& FieldCounterIds() {
    static const FieldCounters counters;
    return counters;
}

Bounds3 TermSupportBounds(const FieldTerm& term) {
    return SkeletonBounds(term.skeleton).Padded(term.kernel.Radius());
}

Field::Field(std::vector<FieldTerm> terms, std::shared_ptr<const FieldMotion> motion) {
    auto table = std::make_shared<TermTable>();
    table->support.reserve(terms.size());
    for (size_t i = 0; i < terms.size(); ++i) {
        Bounds3 support = TermSupportBounds(terms[i]);
        if (motion && motion->Of(static_cast<int>(i)).moving) {
            support = support.Padded(motion->Of(static_cast<int>(i)).reach);
        }
        table->support.push_back(support);
    }
    table->terms = std::move(terms);
    table->motion = std::move(motion);
    rows_.resize(table->terms.size());
    std::iota(rows_.begin(), rows_.end(), 0);
    table_ = std::move(table);
}

Field Field::Subset(std::vector<int> rows) const {
    Field out;
    out.table_ = table_;
    out.rows_ = std::move(rows);
    return out;
}

DistanceRange Field::SweptDistanceRange(int i, const Bounds3& box) const {
    DistanceRange r = SkeletonDistanceRange(table_->terms[i].skeleton, box);
    if (const FieldMotion* motion = table_->motion.get(); motion && motion->Of(i).moving) {
        const double reach = motion->Of(i).reach;
        r.min = std::max(0.0, r.min - reach);
        r.max += reach;
    }
    return r;
}

void Field::WeightRange(int i, double& lo, double& hi) const {
    lo = hi = table_->terms[i].weight;
    if (const FieldMotion* motion = table_->motion.get(); motion && motion->Of(i).moving) {
        lo = motion->Of(i).weightLo;
        hi = motion->Of(i).weightHi;
    }
}

double Field::TermLipschitz(int i) const {
    const Kernel& k = table_->terms[i].kernel;
    double lo, hi;
    WeightRange(i, lo, hi);
    return std::max(std::abs(lo), std::abs(hi)) * k.Bounds(0, k.Radius()).maxSlope;
}

double Field::TermValue(int i, const Vec3& p) const {
    const FieldTerm& t = TermAt(i);
    return t.weight * t.kernel.Value(SkeletonDistance(t.skeleton, p));
}

template <bool kValue, bool kGradient, class Indices>
void Field::Sum(const Vec3& p, const Indices& indices, double* value, Vec3* gradient) const {
    if constexpr (kValue) Count(FieldCounterIds().values);
    if constexpr (kGradient) Count(FieldCounterIds().gradients);
    const TermTable& table = *table_;
    double sum = 0;
    Vec3 g;
    const auto add = [&](const FieldTerm& t) {
        // Points, the commonest skeleton, without the variant dispatch (same arithmetic).
        const auto* point = std::get_if<PointSkeleton>(&t.skeleton);
        Vec3 closest;
        const double d = point ? Length(p - (closest = point->center))
                               : SkeletonDistance(t.skeleton, p, closest);
        if constexpr (kValue) sum += t.weight * t.kernel.Value(d);
        if constexpr (kGradient) {
            if (d > 0 && d < t.kernel.Radius()) {
                g += (p - closest) * (t.weight * t.kernel.Derivative(d) / d);
            }
        }
    };
    // Two loops, so a static field's (or a moving one's without a ray time) pays no test of
    // the motion per term; a moving one looks its terms at the ray time up once. A term
    // beyond its support box is skipped: it and its gradient are exactly 0 there.
    if (TermsAtTime* now = table.motion ? table.motion->Now() : nullptr) {
        for (const int i : indices) {
            if (MayReach(table.support[i], p)) add(now->Of(i, table.terms[i]));
        }
    } else {
        for (const int i : indices) {
            if (MayReach(table.support[i], p)) add(table.terms[i]);
        }
    }
    if constexpr (kValue) *value = deformation_ ? sum + deformation_->Value(p) : sum;
    if constexpr (kGradient) *gradient = deformation_ ? g + deformation_->Gradient(p) : g;
}

double Field::Value(const Vec3& p) const {
    double value;
    Sum<true, false>(p, rows_, &value, nullptr);
    return value;
}

double Field::Value(const Vec3& p, std::span<const int32_t> terms) const {
    double value;
    Sum<true, false>(p, terms, &value, nullptr);
    return value;
}

Vec3 Field::Gradient(const Vec3& p) const {
    Vec3 gradient;
    Sum<false, true>(p, rows_, nullptr, &gradient);
    return gradient;
}

Vec3 Field::Gradient(const Vec3& p, std::span<const int32_t> terms) const {
    Vec3 gradient;
    Sum<false, true>(p, terms, nullptr, &gradient);
    return gradient;
}

double Field::ValueAndGradient(const Vec3& p, std::span<const int32_t> terms,
                               Vec3& gradient) const {
    double value;
    Sum<true, true>(p, terms, &value, &gradient);
    return value;
}

void Field::TermsMeeting(const Bounds3& box, std::span<const int32_t> terms,
                         std::vector<int32_t>& out) const {
    const TermTable& table = *table_;
    for (const int i : terms) {
        if (MayReach(table.support[i], box)) out.push_back(i);
    }
}

void Field::ActiveTerms(const Bounds3& box, std::span<const int32_t> terms,
                        std::vector<int32_t>& out) const {
    const TermTable& table = *table_;
    for (const int i : terms) {
        if (!MayReach(table.support[i], box)) continue;
        if (SweptDistanceRange(i, box).min < table.terms[i].kernel.Radius()) out.push_back(i);
    }
}

FieldBound Field::Bound(const Bounds3& box) const { return Bound(box, rows_, nullptr); }

FieldBound Field::Bound(const Bounds3& box, std::span<const int32_t> terms,
                        std::vector<TermValueRange>* termRanges) const {
    Count(FieldCounterIds().bounds);
    if (termRanges) termRanges->assign(terms.size(), TermValueRange{});
    const TermTable& table = *table_;
    FieldBound fb;
    fb.minDistance = std::numeric_limits<double>::infinity();
    const FieldMotion* motion = table.motion.get();
    for (size_t k = 0; k < terms.size(); ++k) {
        const int i = terms[k];
        if (!MayReach(table.support[i], box)) continue;
        const FieldTerm& t = table.terms[i];
        // A moving term (field_motion.h): distances widened by its reach, its weight range.
        const TermMotion* moves = motion && motion->Of(i).moving ? &motion->Of(i) : nullptr;
        DistanceRange r = SkeletonDistanceRange(t.skeleton, box);
        if (moves) {
            r.min = std::max(0.0, r.min - moves->reach);
            r.max += moves->reach;
        }
        if (r.min >= t.kernel.Radius()) continue;  // f = f' = f'' = 0 on the whole box
        KernelBounds kb = t.kernel.Bounds(r.min, r.max);
        // w·f over w in [wLo, wHi] and f in [fmin, fmax] (f >= 0): the extremes are
        // products of ends (for a static term, of its one weight).
        const double wLo = moves ? moves->weightLo : t.weight;
        const double wHi = moves ? moves->weightHi : t.weight;
        const double w = std::max(std::abs(wLo), std::abs(wHi));
        double lo = wLo * (wLo >= 0 ? kb.valueMin : kb.valueMax);
        double hi = wLo * (wLo >= 0 ? kb.valueMax : kb.valueMin);
        if (moves) {
            lo = std::min(lo, wHi * (wHi >= 0 ? kb.valueMin : kb.valueMax));
            hi = std::max(hi, wHi * (wHi >= 0 ? kb.valueMax : kb.valueMin));
        }
        // TermRange's numbers: w·f at the two ends of the distance range, ordered.
        if (termRanges) (*termRanges)[k] = {std::min(lo, hi), std::max(lo, hi)};
        fb.valueMin += lo;
        fb.valueMax += hi;
        fb.L += w * kb.maxSlope;
        // max(|f''|, |f'|/r) covers the convex eigenvalues; non-convex kinds add |f'|·X. A
        // moving non-convex skeleton has no curvature bound here: X infinite.
        double curvature = kb.maxCurvature;
        const double extra = moves && !SkeletonIsConvex(t.skeleton)
                                 ? std::numeric_limits<double>::infinity()
                                 : ExtraDistanceCurvature(t.skeleton, box);
        if (extra > 0 && kb.maxSlope > 0) curvature = std::max(curvature, kb.maxSlope * extra);
        fb.G += w * curvature;
        fb.minDistance = std::min(fb.minDistance, r.min);
        ++fb.activeTerms;
    }
    if (deformation_) {
        FieldBound db = deformation_->Bound(box);
        fb.valueMin += db.valueMin;
        fb.valueMax += db.valueMax;
        fb.L += db.L;
        fb.G += db.G;
    }
    return fb;
}

void Field::ValueRangeAt(const Vec3& p, std::span<const int32_t> terms, double& lo,
                         double& hi) const {
    const TermTable& table = *table_;
    lo = hi = 0;
    for (const int i : terms) {
        if (!MayReach(table.support[i], p)) continue;
        const FieldTerm& t = table.terms[i];
        const double d = SkeletonDistance(t.skeleton, p), reach = TermReach(i);
        const double near = t.kernel.Value(std::max(0.0, d - reach)), far = t.kernel.Value(d + reach);
        double wLo, wHi;
        WeightRange(i, wLo, wHi);
        lo += std::min({wLo * near, wLo * far, wHi * near, wHi * far});
        hi += std::max({wLo * near, wLo * far, wHi * near, wHi * far});
    }
    if (deformation_) {
        const double v = deformation_->Value(p);
        lo += v;
        hi += v;
    }
}

void Field::TermRange(int i, const Bounds3& box, double& lo, double& hi) const {
    const FieldTerm& t = table_->terms[i];
    if (!MayReach(table_->support[i], box)) {
        lo = hi = 0;
        return;
    }
    const DistanceRange r = SweptDistanceRange(i, box);
    double wLo, wHi;
    WeightRange(i, wLo, wHi);
    const double near = t.kernel.Value(r.min), far = t.kernel.Value(r.max);
    lo = std::min({wLo * near, wLo * far, wHi * near, wHi * far});
    hi = std::max({wLo * near, wLo * far, wHi * near, wHi * far});
}

Bounds3 Field::SupportBounds() const {
    Bounds3 b;
    for (const int i : rows_) b.Extend(table_->support[i]);
    return b;
}

}  // namespace rs
