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

namespace {

// The distance range over `box` of a moving term's skeleton at every time of the interval
// (field_motion.h): between the box's and the centre box's nearest and farthest points for
// a point, else the reference's range widened by the reach. A centre-boxed point whose
// nearest distance is at least `cutoff` (a kernel radius: the term vanishes on the box)
// gets no farthest distance computed: the range is then {nearest, nearest}, to be used for
// that test only.
DistanceRange MovingDistanceRange(const TermMotion& m, const Skeleton& reference,
                                  const Bounds3& box,
                                  double cutoff = std::numeric_limits<double>::infinity()) {
    if (m.centreBoxed) {
        // Per axis: the gap between the two intervals, then their farthest ends' distance.
        const Bounds3& c = m.centres;
        const auto gap = [](double boxLo, double boxHi, double lo, double hi) {
            const double g = std::max(0.0, std::max(lo - boxHi, boxLo - hi));
            return g * g;
        };
        const double near = std::sqrt(gap(box.lo.x, box.hi.x, c.lo.x, c.hi.x) +
                                      gap(box.lo.y, box.hi.y, c.lo.y, c.hi.y) +
                                      gap(box.lo.z, box.hi.z, c.lo.z, c.hi.z));
        if (near >= cutoff) return {near, near};
        const auto far = [](double boxLo, double boxHi, double lo, double hi) {
            const double f = std::max(boxHi - lo, hi - boxLo);
            return f * f;
        };
        const double farthest = std::sqrt(far(box.lo.x, box.hi.x, c.lo.x, c.hi.x) +
                                          far(box.lo.y, box.hi.y, c.lo.y, c.hi.y) +
                                          far(box.lo.z, box.hi.z, c.lo.z, c.hi.z));
        return {near, std::max(farthest, near)};
    }
    DistanceRange r = SkeletonDistanceRange(reference, box);
    r.min = std::max(0.0, r.min - m.reach);
    r.max += m.reach;
    return r;
}

// The same at one point.
DistanceRange MovingDistanceRange(const TermMotion& m, const Skeleton& reference,
                                  const Vec3& p) {
    return MovingDistanceRange(m, reference, Bounds3(p, p));
}

// [lo, hi] holding w·f(d) for w in [wLo, wHi], d in r and f the kernel, or every kernel of
// the box of `moves` when its kernel moves (f is monotone in d).
void WeightedKernelRange(const Kernel& kernel, const TermMotion* moves, const DistanceRange& r,
                         double wLo, double wHi, double& lo, double& hi) {
    double near, far;
    if (moves && moves->kernelMoves) {
        moves->kernels.ValueRange(r.min, r.max, far, near);
    } else {
        near = kernel.Value(r.min);
        far = kernel.Value(r.max);
    }
    lo = std::min({wLo * near, wLo * far, wHi * near, wHi * far});
    hi = std::max({wLo * near, wLo * far, wHi * near, wHi * far});
}

}  // namespace

Field::Field(std::vector<FieldTerm> terms, std::shared_ptr<const FieldMotion> motion) {
    auto table = std::make_shared<TermTable>();
    table->support.reserve(terms.size());
    for (size_t i = 0; i < terms.size(); ++i) {
        Bounds3 support = TermSupportBounds(terms[i]);
        if (motion && motion->Of(static_cast<int>(i)).moving) {
            // Padded by the largest radius of the interval (an animated kernel's R_hi).
            const TermMotion& m = motion->Of(static_cast<int>(i));
            const double radius = m.kernelMoves ? m.kernels.Radius() : terms[i].kernel.Radius();
            if (m.kernelMoves) support = SkeletonBounds(terms[i].skeleton).Padded(radius);
            support = m.centreBoxed ? m.centres.Padded(radius) : support.Padded(m.reach);
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
    return Field(table_, std::move(rows));
}

DistanceRange Field::SweptDistanceRange(int i, const Bounds3& box, double cutoff) const {
    if (const TermMotion* moves = MotionOf(i)) {
        return MovingDistanceRange(*moves, table_->terms[i].skeleton, box, cutoff);
    }
    return SkeletonDistanceRange(table_->terms[i].skeleton, box);
}

void Field::WeightRange(int i, double& lo, double& hi) const {
    lo = hi = table_->terms[i].weight;
    if (const TermMotion* moves = MotionOf(i)) {
        lo = moves->weightLo;
        hi = moves->weightHi;
    }
}

double Field::TermLipschitz(int i) const {
    const Kernel& k = table_->terms[i].kernel;
    double lo, hi;
    WeightRange(i, lo, hi);
    const TermMotion* moves = MotionOf(i);
    const double slope = moves && moves->kernelMoves
                             ? moves->kernels.Bounds(0, moves->kernels.Radius()).maxSlope
                             : k.Bounds(0, k.Radius()).maxSlope;
    return std::max(std::abs(lo), std::abs(hi)) * slope;
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
        const TermMotion* moves = MotionOf(i);
        const double radius = moves && moves->kernelMoves ? moves->kernels.Radius()
                                                          : table.terms[i].kernel.Radius();
        if (SweptDistanceRange(i, box, radius).min < radius) out.push_back(i);
    }
}

namespace {

// Adds term t's bounds over the box to fb (Field::Bound), `moves` its motion when it moves
// (null: t itself at every point of the box); false when t vanishes on the whole box. With
// `range`, also stores TermRange's numbers in it.
bool AddTermBound(const FieldTerm& t, const TermMotion* moves, const Bounds3& box,
                  FieldBound& fb, TermValueRange* range) {
    // A moving term (field_motion.h): its distance range over the interval, its weight
    // range, and its kernel box when its kernel moves.
    const KernelBox* kernels = moves && moves->kernelMoves ? &moves->kernels : nullptr;
    const double radius = kernels ? kernels->Radius() : t.kernel.Radius();
    const DistanceRange r = moves ? MovingDistanceRange(*moves, t.skeleton, box, radius)
                                  : SkeletonDistanceRange(t.skeleton, box);
    if (r.min >= radius) return false;  // f = f' = f'' = 0 on the whole box
    KernelBounds kb = kernels ? kernels->Bounds(r.min, r.max) : t.kernel.Bounds(r.min, r.max);
    // w·f over w in [wLo, wHi] and f in [fmin, fmax] (f >= 0): the extremes are products
    // of ends (for a static term, of its one weight).
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
    if (range) *range = {std::min(lo, hi), std::max(lo, hi)};
    fb.valueMin += lo;
    fb.valueMax += hi;
    fb.L += w * kb.maxSlope;
    // max(|f''|, |f'|/r) covers the convex eigenvalues; non-convex kinds add |f'|·X. A
    // moving non-convex skeleton has no curvature bound here: X infinite. Points, the
    // commonest kind, are convex (X = 0) without the dispatch.
    double curvature = kb.maxCurvature;
    const double extra = std::holds_alternative<PointSkeleton>(t.skeleton) ? 0
                         : moves && !SkeletonIsConvex(t.skeleton)
                             ? std::numeric_limits<double>::infinity()
                             : ExtraDistanceCurvature(t.skeleton, box);
    if (extra > 0 && kb.maxSlope > 0) curvature = std::max(curvature, kb.maxSlope * extra);
    fb.G += w * curvature;
    fb.minDistance = std::min(fb.minDistance, r.min);
    ++fb.activeTerms;
    return true;
}

FieldBound EmptyBound() {
    FieldBound fb;
    fb.minDistance = std::numeric_limits<double>::infinity();
    return fb;
}

}  // namespace

FieldBound Field::Bound(const Bounds3& box) const { return Bound(box, rows_, nullptr); }

FieldBound Field::Bound(const Bounds3& box, std::span<const int32_t> terms,
                        std::vector<TermValueRange>* termRanges) const {
    Count(FieldCounterIds().bounds);
    if (termRanges) termRanges->assign(terms.size(), TermValueRange{});
    const TermTable& table = *table_;
    FieldBound fb = EmptyBound();
    const FieldMotion* motion = table.motion.get();
    for (size_t k = 0; k < terms.size(); ++k) {
        const int i = terms[k];
        if (!MayReach(table.support[i], box)) continue;
        const TermMotion* moves = motion && motion->Of(i).moving ? &motion->Of(i) : nullptr;
        AddTermBound(table.terms[i], moves, box, fb, termRanges ? &(*termRanges)[k] : nullptr);
    }
    AddDeformationBound(box, fb);
    return fb;
}

FieldBound Field::BoundAtRayTime(const Bounds3& box) const {
    TermsAtTime* now = table_->motion ? table_->motion->Now() : nullptr;
    if (!now) return Bound(box);
    Count(FieldCounterIds().bounds);
    const TermTable& table = *table_;
    FieldBound fb = EmptyBound();
    for (const int i : rows_) {
        if (MayReach(table.support[i], box)) {
            AddTermBound(now->Of(i, table.terms[i]), nullptr, box, fb, nullptr);
        }
    }
    AddDeformationBound(box, fb);
    return fb;
}

void Field::AddDeformationBound(const Bounds3& box, FieldBound& fb) const {
    if (!deformation_) return;
    const FieldBound db = deformation_->Bound(box);
    fb.valueMin += db.valueMin;
    fb.valueMax += db.valueMax;
    fb.L += db.L;
    fb.G += db.G;
}

void Field::ValueRangeAt(const Vec3& p, std::span<const int32_t> terms, double& lo,
                         double& hi) const {
    const TermTable& table = *table_;
    lo = hi = 0;
    for (const int i : terms) {
        if (!MayReach(table.support[i], p)) continue;
        const FieldTerm& t = table.terms[i];
        const TermMotion* moves = MotionOf(i);
        DistanceRange r;
        if (moves) {
            r = MovingDistanceRange(*moves, t.skeleton, p);
        } else {
            r.min = r.max = SkeletonDistance(t.skeleton, p);
        }
        double wLo, wHi, termLo, termHi;
        WeightRange(i, wLo, wHi);
        WeightedKernelRange(t.kernel, moves, r, wLo, wHi, termLo, termHi);
        lo += termLo;
        hi += termHi;
    }
    if (deformation_) {
        const double v = deformation_->Value(p);
        lo += v;
        hi += v;
    }
}

void Field::TermRange(int i, const Bounds3& box, double& lo, double& hi) const {
    if (!MayReach(table_->support[i], box)) {
        lo = hi = 0;
        return;
    }
    double wLo, wHi;
    WeightRange(i, wLo, wHi);
    WeightedKernelRange(table_->terms[i].kernel, MotionOf(i), SweptDistanceRange(i, box), wLo,
                        wHi, lo, hi);
}

void Field::TermRangeAtRayTime(int i, const Bounds3& box, double& lo, double& hi) const {
    TermsAtTime* now = table_->motion && table_->motion->Of(i).moving ? table_->motion->Now()
                                                                      : nullptr;
    if (!now || !MayReach(table_->support[i], box)) return TermRange(i, box, lo, hi);
    const FieldTerm& t = now->Of(i, table_->terms[i]);
    WeightedKernelRange(t.kernel, nullptr, SkeletonDistanceRange(t.skeleton, box), t.weight,
                        t.weight, lo, hi);
}

Bounds3 Field::SupportBounds() const {
    Bounds3 b;
    for (const int i : rows_) b.Extend(table_->support[i]);
    return b;
}

}  // namespace rs
