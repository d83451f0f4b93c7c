#include "libobj/implicit/exact_method.h"

#include <algorithm>
#include <atomic>
#include <cfloat>
#include <cmath>
#include <utility>
#include <vector>

#include "libcommon/error.h"
#include "libcommon/stats.h"

namespace rs {

namespace {

using Real = long double;

template <class... Fs>
struct Overloaded : Fs... {
    using Fs::operator()...;
};
template <class... Fs>
Overloaded(Fs...) -> Overloaded<Fs...>;

struct LVec {
    Real x = 0, y = 0, z = 0;
};
LVec operator+(const LVec& a, const LVec& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
LVec operator-(const LVec& a, const LVec& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
LVec operator*(const LVec& a, Real s) { return {a.x * s, a.y * s, a.z * s}; }
Real Dot(const LVec& a, const LVec& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
Real Length(const LVec& a) { return std::sqrt(Dot(a, a)); }
LVec Long(const Vec3& v) { return {v.x, v.y, v.z}; }

Real SegmentDistance(const LVec& a, const LVec& b, const LVec& p) {
    LVec ab = b - a;
    Real len2 = Dot(ab, ab);
    Real s = len2 > 0 ? std::clamp(Dot(p - a, ab) / len2, Real(0), Real(1)) : Real(0);
    return Length(p - (a + ab * s));
}

// Ericson, Real-Time Collision Detection §5.1.5 (Voronoi regions of the triangle).
Real TriangleDistance(const LVec& a, const LVec& b, const LVec& c, const LVec& p) {
    LVec ab = b - a, ac = c - a;
    LVec n{ab.y * ac.z - ab.z * ac.y, ab.z * ac.x - ab.x * ac.z, ab.x * ac.y - ab.y * ac.x};
    if (Dot(n, n) == 0) {
        return std::min({SegmentDistance(a, b, p), SegmentDistance(b, c, p),
                         SegmentDistance(c, a, p)});
    }
    LVec ap = p - a;
    Real d1 = Dot(ab, ap), d2 = Dot(ac, ap);
    if (d1 <= 0 && d2 <= 0) return Length(ap);
    LVec bp = p - b;
    Real d3 = Dot(ab, bp), d4 = Dot(ac, bp);
    if (d3 >= 0 && d4 <= d3) return Length(bp);
    Real vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) return Length(p - (a + ab * (d1 / (d1 - d3))));
    LVec cp = p - c;
    Real d5 = Dot(ab, cp), d6 = Dot(ac, cp);
    if (d6 >= 0 && d5 <= d6) return Length(cp);
    Real vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) return Length(p - (a + ac * (d2 / (d2 - d6))));
    Real va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
        return Length(p - (b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)))));
    }
    Real denom = 1 / (va + vb + vc);
    return Length(p - (a + ab * (vb * denom) + ac * (vc * denom)));
}

Real CylinderDistance(const CylinderSkeleton& s, const LVec& p) {
    LVec a = Long(s.a), axis = Long(s.b) - a;
    Real len = Length(axis);
    if (len == 0) return Length(p - a);  // as skeleton.cpp: a degenerate cylinder is a point
    LVec u = axis * (1 / len), v = p - a;
    Real h = Dot(v, u);
    Real radial = std::max(Length(v - u * h) - Real(s.radius), Real(0));
    Real axial = std::max({-h, h - len, Real(0)});
    return std::sqrt(radial * radial + axial * axial);
}

// The number of parts of a term's distance (see the header).
int PartCount(const Skeleton& s) {
    if (const auto* poly = std::get_if<PolylineSkeleton>(&s)) {
        return static_cast<int>(poly->points.size()) - 1;
    }
    return std::holds_alternative<CircleSkeleton>(s) ? 2 : 1;
}

// Part j of the term's distance at p: each is convex along any line.
Real PartValue(const Skeleton& skeleton, int j, const LVec& p) {
    return std::visit(
        Overloaded{
            [&](const PointSkeleton& s) { return Length(p - Long(s.center)); },
            [&](const SegmentSkeleton& s) { return SegmentDistance(Long(s.a), Long(s.b), p); },
            [&](const PolylineSkeleton& s) {
                return SegmentDistance(Long(s.points[j]), Long(s.points[j + 1]), p);
            },
            [&](const CircleSkeleton& s) {
                LVec v = p - Long(s.center), n = Long(s.normal);
                Real z = Dot(v, n);
                return j == 0 ? Length(v - n * z) : std::abs(z);
            },
            [&](const TriangleSkeleton& s) {
                return TriangleDistance(Long(s.a), Long(s.b), Long(s.c), p);
            },
            [&](const BoxSkeleton& s) {
                Real sum = 0;
                LVec lo = Long(s.lo), hi = Long(s.hi);
                for (Real gap : {std::max({lo.x - p.x, p.x - hi.x, Real(0)}),
                                 std::max({lo.y - p.y, p.y - hi.y, Real(0)}),
                                 std::max({lo.z - p.z, p.z - hi.z, Real(0)})}) {
                    sum += gap * gap;
                }
                return std::sqrt(sum);
            },
            [&](const CylinderSkeleton& s) { return CylinderDistance(s, p); },
        },
        skeleton);
}

// The distance from part values, and its range from the parts' ranges [lo_j, hi_j].
Real DistanceFromParts(const Skeleton& s, const Real* parts) {
    if (const auto* circle = std::get_if<CircleSkeleton>(&s)) {
        Real radial = parts[0] - circle->radius;
        return std::sqrt(radial * radial + parts[1] * parts[1]);
    }
    return *std::min_element(parts, parts + PartCount(s));
}

std::pair<Real, Real> DistanceRange(const Skeleton& s, const Real* a, const Real* b) {
    if (const auto* circle = std::get_if<CircleSkeleton>(&s)) {
        // Within a piece ρ − radius keeps its sign and ρ, |z| are monotone.
        Real ra = std::abs(a[0] - circle->radius), rb = std::abs(b[0] - circle->radius);
        Real rLo = std::min(ra, rb), rHi = std::max(ra, rb);
        Real zLo = std::min(a[1], b[1]), zHi = std::max(a[1], b[1]);
        return {std::sqrt(rLo * rLo + zLo * zLo), std::sqrt(rHi * rHi + zHi * zHi)};
    }
    // min over parts of monotone functions: [min_j lo_j, min_j hi_j].
    Real lo = INFINITY, hi = INFINITY;
    for (int j = 0; j < PartCount(s); ++j) {
        lo = std::min(lo, std::min(a[j], b[j]));
        hi = std::min(hi, std::max(a[j], b[j]));
    }
    return {lo, hi};
}

// The kernel in long double (formulas of kernel.h; pieces [0, e], (e, R), [R, ∞)).
Real KernelValue(const Kernel& k, Real r) {
    const Real radius = k.Radius();
    if (r >= radius) return 0;
    if (k.Kind() == KernelKind::Blob) {
        Real q = 1 - r * r / (radius * radius);
        return k.Strength() * q * q;
    }
    const Real e = k.Thickness(), stiffness = k.Stiffness();
    if (r <= e) {
        if (k.Kind() == KernelKind::GascuelLinear) return 1 - stiffness * (r - e);
        return 1 + stiffness * e / 2 - stiffness * r * r / (2 * e);
    }
    Real l = radius - e, s = (r - e) / l, m = stiffness * l;
    return (2 * s * s * s - 3 * s * s + 1) - m * (s * s * s - 2 * s * s + s);
}

// Golden-section search for a minimum of f on [lo, hi] (exact for unimodal f up to the
// resolution of its values).
template <class F>
Real GoldenMinimum(F&& f, Real lo, Real hi) {
    const Real r = (std::sqrt(Real(5)) - 1) / 2;
    Real x1 = hi - r * (hi - lo), x2 = lo + r * (hi - lo);
    Real f1 = f(x1), f2 = f(x2);
    for (int i = 0; i < 200 && hi - lo > 4 * LDBL_EPSILON * (std::abs(lo) + std::abs(hi)); ++i) {
        if (f1 <= f2) {
            hi = x2;
            x2 = x1;
            f2 = f1;
            x1 = hi - r * (hi - lo);
            f1 = f(x1);
        } else {
            lo = x1;
            x1 = x2;
            f1 = f2;
            x2 = lo + r * (hi - lo);
            f2 = f(x2);
        }
    }
    return (lo + hi) / 2;
}

// The point where a monotone f crosses `level` in [lo, hi] (f(lo) − level and
// f(hi) − level of opposite signs), to adjacent long doubles.
template <class F>
Real LevelCrossing(F&& f, Real lo, Real hi, Real level) {
    const bool loAbove = f(lo) > level;
    for (int i = 0; i < 20000; ++i) {
        Real mid = (lo + hi) / 2;
        if (mid <= lo || mid >= hi) break;
        if ((f(mid) > level) == loAbove) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    return (lo + hi) / 2;
}

struct Sample {
    Real t = 0, g = 0, absSum = 0;
    std::vector<Real> parts;  // all terms' parts, at partOffset[i]
};

// One ray's search (see the header).
class RaySolver {
  public:
    RaySolver(const Field& field, double threshold, const Ray& ray, double tMin, double tMax)
        : field_(field),
          terms_(field.Motion() ? TermsAtRayTime(field, resolved_) : field.Terms()),
          threshold_(threshold),
          ray_(ray),
          origin_(Long(ray.origin)),
          dir_(Long(ray.dir)),
          length_(Length(ray.dir)),
          tMin_(tMin),
          tMax_(tMax) {
        int offset = 0;
        for (const FieldTerm& t : terms_) {
            partOffset_.push_back(offset);
            offset += PartCount(t.skeleton);
        }
        partTotal_ = offset;
    }

    std::optional<double> Solve(double t0, double t1) {
        const Real extent =
            std::max({Real(t1) - Real(t0), std::abs(Real(t0)), std::abs(Real(t1))});
        floor_ = ExactMethod::kFloor * extent;
        window_ = ExactMethod::kTangencyWindow * extent;
        tEnd_ = t1;
        // Support spans and breakpoints.
        std::vector<Real> breaks{t0, t1};
        spans_.assign(terms_.size(), {1, 0});
        std::vector<int> met;  // the terms whose support box the ray meets in [t0, t1]
        for (size_t i = 0; i < terms_.size(); ++i) {
            double s0 = t0, s1 = t1;
            if (!TermSupportBounds(terms_[i]).ClipRay(ray_, s0, s1)) continue;
            met.push_back(static_cast<int>(i));
            spans_[i] = {s0, s1};
            breaks.push_back(s0);
            breaks.push_back(s1);
            AddPartBreaks(static_cast<int>(i), s0, s1, breaks);
        }
        std::sort(breaks.begin(), breaks.end());
        breaks.erase(std::unique(breaks.begin(), breaks.end()), breaks.end());
        for (size_t k = 0; k + 1 < breaks.size(); ++k) {
            Real a = std::max(breaks[k], Real(t0)), b = std::min(breaks[k + 1], Real(t1));
            if (!(b > a)) continue;
            pieceEnd_ = b;
            active_.clear();
            for (int i : met) {
                if (spans_[i].first <= b && spans_[i].second >= a) active_.push_back(i);
            }
            std::optional<Real> root = Search(Evaluate(a), Evaluate(b));
            if (root) return static_cast<double>(*root);
            if (exhausted_) break;
        }
        return std::nullopt;
    }

  private:
    LVec At(Real t) const { return origin_ + dir_ * t; }

    // Breakpoints of term i on [s0, s1]: each part's minimum and level crossings.
    void AddPartBreaks(int i, Real s0, Real s1, std::vector<Real>& breaks) const {
        const FieldTerm& term = terms_[i];
        const bool circle = std::holds_alternative<CircleSkeleton>(term.skeleton);
        for (int j = 0; j < PartCount(term.skeleton); ++j) {
            auto part = [&](Real t) { return PartValue(term.skeleton, j, At(t)); };
            Real m = GoldenMinimum(part, s0, s1);
            breaks.push_back(m);
            std::vector<Real> levels;
            if (circle) {
                if (j == 0) levels.push_back(std::get<CircleSkeleton>(term.skeleton).radius);
            } else {
                if (term.kernel.Kind() != KernelKind::Blob) {
                    levels.push_back(term.kernel.Thickness());
                }
                levels.push_back(term.kernel.Radius());
            }
            const Real p0 = part(s0), pm = part(m), p1 = part(s1);
            for (Real level : levels) {
                if (p0 > level && pm < level) breaks.push_back(LevelCrossing(part, s0, m, level));
                if (pm < level && p1 > level) breaks.push_back(LevelCrossing(part, m, s1, level));
            }
        }
    }

    Sample Evaluate(Real t) const {
        Count(FieldCounterIds().values);
        Sample s;
        s.t = t;
        s.parts.resize(partTotal_);
        const LVec p = At(t);
        Real sum = 0, absSum = 0;
        for (int i : active_) {
            const FieldTerm& term = terms_[i];
            Real* parts = s.parts.data() + partOffset_[i];
            for (int j = 0; j < PartCount(term.skeleton); ++j) {
                parts[j] = PartValue(term.skeleton, j, p);
            }
            Real d = DistanceFromParts(term.skeleton, parts);
            Real v = term.weight * KernelValue(term.kernel, d);
            sum += v;
            absSum += std::abs(v);
        }
        s.g = sum - threshold_;
        s.absSum = absSum;
        return s;
    }

    Real Value(Real t) const {
        Count(FieldCounterIds().values);
        const LVec p = At(t);
        Real sum = 0, parts[2];
        for (int i : active_) {
            const FieldTerm& term = terms_[i];
            Real d;
            if (std::holds_alternative<CircleSkeleton>(term.skeleton)) {
                parts[0] = PartValue(term.skeleton, 0, p);
                parts[1] = PartValue(term.skeleton, 1, p);
                d = DistanceFromParts(term.skeleton, parts);
            } else {
                d = INFINITY;
                for (int j = 0; j < PartCount(term.skeleton); ++j) {
                    d = std::min(d, PartValue(term.skeleton, j, p));
                }
            }
            sum += term.weight * KernelValue(term.kernel, d);
        }
        return sum - threshold_;
    }

    // The tangency tolerance τ over [a, b].
    Real Tau(const Sample& a, const Sample& b) const {
        return 256 * LDBL_EPSILON * (threshold_ + std::max(a.absSum, b.absSum));
    }

    // [lo, hi] containing g on [a, b] (a, b in one piece).
    std::pair<Real, Real> Enclose(const Sample& a, const Sample& b) const {
        Real lo = -threshold_, hi = -threshold_;
        for (int i : active_) {
            const FieldTerm& term = terms_[i];
            auto [dLo, dHi] = DistanceRange(term.skeleton, a.parts.data() + partOffset_[i],
                                            b.parts.data() + partOffset_[i]);
            Real fLo = term.weight * KernelValue(term.kernel, dHi);
            Real fHi = term.weight * KernelValue(term.kernel, dLo);
            lo += std::min(fLo, fHi);
            hi += std::max(fLo, fHi);
        }
        return {lo, hi};
    }

    std::optional<Real> Accept(Real t) const {
        if (t > tMin_ && t < tMax_) return t;
        return std::nullopt;
    }

    // The sign change in [a, b] (classes of a.g and gb differ), to adjacent long doubles.
    std::optional<Real> Bisect(Real lo, Real gLo, Real hi, Real gHi) const {
        for (int i = 0; i < 20000; ++i) {
            Real mid = (lo + hi) / 2;
            if (mid <= lo || mid >= hi) break;
            Real gm = Value(mid);
            if (gm == 0) return Accept(mid);
            if (ClassChanges(gLo, gm)) {
                hi = mid;
                gHi = gm;
            } else {
                lo = mid;
                gLo = gm;
            }
        }
        return Accept(std::abs(gLo) <= std::abs(gHi) ? lo : hi);
    }

    std::optional<Real> Floor(const Sample& a, const Sample& b) const {
        if (ClassChanges(a.g, b.g)) return Bisect(a.t, a.g, b.t, b.g);
        // The extremum of g toward zero: the maximum outside, the minimum inside.
        const Real toward = a.g > 0 ? 1 : -1;
        Real te = GoldenMinimum([&](Real t) { return toward * Value(t); }, a.t, b.t);
        Real ge = Value(te);
        if (ClassChanges(a.g, ge)) return Bisect(a.t, a.g, te, ge);
        if (std::abs(ge) > Tau(a, b)) return std::nullopt;
        // |g| <= τ here, but near a simple root where g' is tiny (a grazing ray just inside)
        // that is true up to τ/|g'| before the root. Look over a wider window, within the
        // piece, for the extremum: if g crosses there, the root is bisected; if g still
        // approaches zero at the piece's end, the next piece decides (its first floor
        // interval repeats this from there; a tangency exactly at the break is found there,
        // g moving away from zero); otherwise the tangency is the window's extremum.
        const Real end = std::min(a.t + window_, pieceEnd_);
        Real tw = GoldenMinimum([&](Real t) { return toward * Value(t); }, a.t, end);
        Real gw = Value(tw);
        if (ClassChanges(a.g, gw)) return Bisect(a.t, a.g, tw, gw);
        const bool atCutEnd = end == pieceEnd_ && pieceEnd_ < tEnd_ &&
                              end - tw <= 8 * LDBL_EPSILON * std::abs(end);
        if (atCutEnd) return std::nullopt;
        return Accept(std::abs(gw) <= std::abs(ge) ? tw : te);
    }

    std::optional<Real> Search(const Sample& a, const Sample& b) {
        if (a.g == 0 && a.t > tMin_ && a.t < tMax_) return a.t;
        if (++nodes_ > ExactMethod::kMaxNodes) {
            if (!exhausted_) {
                static std::atomic<bool> warned{false};
                if (!warned.exchange(true)) {
                    Report(Severity::Warn, {},
                           "exact implicit solver: more than %ld intervals on one ray (a "
                           "near-tangency where the field's G is infinite); the rest of such "
                           "rays is reported as a miss",
                           ExactMethod::kMaxNodes);
                }
            }
            exhausted_ = true;
            return std::nullopt;
        }
        const Real tau = Tau(a, b);
        auto [lo, hi] = Enclose(a, b);
        if (lo > tau || hi < -tau) return std::nullopt;
        const Real width = b.t - a.t;
        if (width <= floor_) return Floor(a, b);
        const bool change = ClassChanges(a.g, b.g);
        // Second-order tests with Field::Bound's G over the segment's box (padded by a few
        // ulps of the coordinates, the box corners being rounded to double).
        const Vec3 pa = ray_.At(static_cast<double>(a.t)), pb = ray_.At(static_cast<double>(b.t));
        const double pad = 1e-15 * (1 + std::max({std::abs(pa.x), std::abs(pa.y), std::abs(pa.z),
                                                  std::abs(pb.x), std::abs(pb.y), std::abs(pb.z)}));
        const FieldBound bound = field_.Bound(Bounds3(pa, pb).Padded(pad));
        const Real gt = Real(bound.G) * length_ * length_, lt = Real(bound.L) * length_;
        if (std::isfinite(gt)) {
            if (!change && std::min(std::abs(a.g), std::abs(b.g)) > gt * width * width / 8 + tau) {
                return std::nullopt;
            }
            const double mid = static_cast<double>((a.t + b.t) / 2);
            const Real slope = Dot(field_.Gradient(ray_.At(mid)), ray_.dir);
            if (std::abs(slope) > gt * width / 2 + 1e-12L * lt) {
                // g' keeps its sign: one root iff the classes differ; |g| is smallest at an
                // end otherwise, and the ends were not roots.
                if (!change) return std::nullopt;
                return Bisect(a.t, a.g, b.t, b.g);
            }
        }
        Sample m = Evaluate((a.t + b.t) / 2);
        if (std::optional<Real> r = Search(a, m)) return r;
        if (exhausted_) return std::nullopt;
        return Search(m, b);
    }

    // A moving field's terms at the ray's time, every one (this reference method does not
    // need to be fast).
    static const std::vector<FieldTerm>& TermsAtRayTime(const Field& field,
                                                        std::vector<FieldTerm>& out) {
        for (int i = 0; i < static_cast<int>(field.Terms().size()); ++i) {
            out.push_back(field.TermAt(i));
        }
        return out;
    }

    const Field& field_;
    std::vector<FieldTerm> resolved_;  // before terms_, which may refer to it
    const std::vector<FieldTerm>& terms_;
    Real threshold_;
    const Ray& ray_;
    LVec origin_, dir_;
    Real length_;
    double tMin_, tMax_;
    std::vector<int> partOffset_;
    int partTotal_ = 0;
    std::vector<std::pair<Real, Real>> spans_;
    std::vector<int> active_;
    Real floor_ = 0, window_ = 0, pieceEnd_ = 0, tEnd_ = 0;
    long nodes_ = 0;
    bool exhausted_ = false;
};

}  // namespace

ExactMethod::ExactMethod(const Field& field, const MethodParams& params)
    : field_(field), threshold_(params.threshold), box_(PositiveSupportBounds(field)) {}

std::optional<double> ExactMethod::FirstRoot(const Ray& ray, double tMin, double tMax) const {
    double t0 = tMin, t1 = tMax;
    if (!box_.ClipRay(ray, t0, t1)) return std::nullopt;
    RaySolver solver(field_, threshold_, ray, tMin, tMax);
    return solver.Solve(t0, t1);
}

}  // namespace rs
