#include "libobj/metaball_sum.h"

#include <algorithm>
#include <cmath>

#include "libobj/polynomial.h"

namespace rs {

namespace {

// Up to this many balls a plain loop finds the ones a ray meets faster than the hierarchy.
constexpr size_t kLinearSearchMax = 8;

// Relative margin of the field-bound rejections in FirstRoot. An interval's quartic is
// formed from terms of size at most 81·|s| per active ball (|q_i| ≤ 1 and each of q_i's
// three terms at most 4 in size on the ball's chord), so its computed values differ from
// the true field minus T by a few hundred ulp of T + Σ|s| at most; a field bound below T by
// 10⁻⁷ of that is far outside this error and outside the solver's zero tolerance, so every
// value the solver would compute there is negative and it would report no root. The rounding
// of the interval's start point (about u·|o + t·d|, moving the field by up to 4|s|/r times
// that) stays below the margin for rays starting within some 10⁷ ball radii of the balls.
constexpr double kFieldBoundMargin = 1e-7;

// A ball the ray meets: where it passes closest to the centre (parameter and squared
// distance) and the part of (tMin, tMax) inside the sphere of influence.
struct Span {
    int ball;
    double tClosest, dist2;
    double enter, exit;
};

struct Event {
    double t;
    int span;
    bool entering;
};

// Per-thread scratch of FirstRoot, so rays allocate nothing once it has grown.
struct Scratch {
    std::vector<Span> spans;
    std::vector<Event> events;
    std::vector<int> active;  // indices into spans, in increasing ball index
};

// The largest value of s·q² over [ta, tb] for a span, q = 1 − ρ²/r² ∈ [0, 1] being largest at
// the interval's point nearest to the closest approach; at most 0 for a negative strength.
double TermPeak(double strength, double radius2, const Span& span, double dd, double ta,
                double tb) {
    if (strength < 0) return 0;
    const double gap = span.tClosest - std::clamp(span.tClosest, ta, tb);
    const double q = 1 - (span.dist2 + dd * gap * gap) / radius2;
    return strength * q * q;
}

}  // namespace

MetaballSum::MetaballSum(double threshold, std::vector<Metaball> balls) : threshold_(threshold) {
    balls_.reserve(balls.size());
    std::vector<Bounds3> boxes;
    boxes.reserve(balls.size());
    for (const Metaball& b : balls) {
        const double r2 = b.radius * b.radius;
        balls_.push_back({b.centre, r2, 1 / r2, b.strength});
        const Vec3 r{b.radius, b.radius, b.radius};
        boxes.emplace_back(b.centre - r, b.centre + r);
        bounds_.Extend(boxes.back());
    }
    if (balls_.size() > kLinearSearchMax) hierarchy_.Build(boxes);
}

void MetaballSum::BallsAt(const Vec3& p, std::vector<int>& out) const {
    out.clear();
    if (hierarchy_.IsEmpty()) {
        for (size_t i = 0; i < balls_.size(); ++i) out.push_back(static_cast<int>(i));
        return;
    }
    hierarchy_.VisitContaining(p, [&](int i) { out.push_back(i); });
    std::sort(out.begin(), out.end());
}

std::optional<double> MetaballSum::FirstRoot(const Ray& ray, double tMin, double tMax,
                                             int* quarticsSolved) const {
    if (quarticsSolved) *quarticsSolved = 0;
    const double dd = LengthSquared(ray.dir);
    if (!(dd > 0)) return std::nullopt;
    thread_local Scratch scratch;
    std::vector<Span>& spans = scratch.spans;
    std::vector<Event>& events = scratch.events;
    std::vector<int>& active = scratch.active;
    spans.clear();
    events.clear();
    active.clear();
    double peakSum = 0, strengthSum = 0;  // over the balls met

    // Adds ball i's span and events if its sphere of influence meets (tMin, tMax).
    const auto addBall = [&](int i) {
        const Ball& b = balls_[i];
        // |o + t d − c|² = r²: solved around the closest approach for stability.
        const Vec3 oc = ray.origin - b.centre;
        const double tClosest = -Dot(oc, ray.dir) / dd;
        const double dist2 = LengthSquared(oc + ray.dir * tClosest);
        const double h2 = (b.radius2 - dist2) / dd;
        if (h2 <= 0) return;
        const double h = std::sqrt(h2);
        const double t0 = std::max(tClosest - h, tMin), t1 = std::min(tClosest + h, tMax);
        if (t0 >= t1) return;
        const int k = static_cast<int>(spans.size());
        spans.push_back({i, tClosest, dist2, t0, t1});
        events.push_back({t0, k, true});
        events.push_back({t1, k, false});
        if (b.strength > 0) {
            const double q = 1 - dist2 / b.radius2;
            peakSum += b.strength * q * q;
        }
        strengthSum += std::abs(b.strength);
    };
    if (hierarchy_.IsEmpty()) {
        for (size_t i = 0; i < balls_.size(); ++i) addBall(static_cast<int>(i));
    } else {
        double segmentEnd = tMax;
        hierarchy_.Traverse(ray, tMin, segmentEnd, [&](int i) {
            addBall(i);
            return false;  // collects every ball: the segment is not shortened
        });
    }
    if (spans.empty()) return std::nullopt;
    // Even every ball at its peak stays below the threshold: no root anywhere.
    if (peakSum + kFieldBoundMargin * (threshold_ + strengthSum) < threshold_) {
        return std::nullopt;
    }

    // The first root in (tMin, tMax) of F − T on [ta, tb], where the active balls are fixed.
    const auto solve = [&](double ta, double tb) -> std::optional<double> {
        double bound = 0, activeStrength = 0;
        for (int k : active) {
            const Ball& b = balls_[spans[k].ball];
            bound += TermPeak(b.strength, b.radius2, spans[k], dd, ta, tb);
            activeStrength += std::abs(b.strength);
        }
        if (bound + kFieldBoundMargin * (threshold_ + activeStrength) < threshold_) {
            return std::nullopt;
        }
        // Quartic in u = t − ta: Σ s_i·q_i(u)² − T, with q_i = 1 − ρ_i²(u)/r_i² and
        // ρ_i² = |d|²u² + 2(o'−c)·d u + |o'−c|², o' = the point at ta.
        const Vec3 start = ray.At(ta);
        double c[5] = {-threshold_, 0, 0, 0, 0};  // ascending powers
        for (int k : active) {
            const Ball& b = balls_[spans[k].ball];
            const Vec3 oc = start - b.centre;
            const double a2 = -dd * b.inverseRadius2,
                         a1 = -2 * Dot(oc, ray.dir) * b.inverseRadius2,
                         a0 = 1 - LengthSquared(oc) * b.inverseRadius2;
            c[4] += b.strength * a2 * a2;
            c[3] += b.strength * 2 * a2 * a1;
            c[2] += b.strength * (a1 * a1 + 2 * a2 * a0);
            c[1] += b.strength * 2 * a1 * a0;
            c[0] += b.strength * a0 * a0;
        }
        if (quarticsSolved) ++*quarticsSolved;
        // Roots come nearest first and only as many as needed are computed.
        AscendingRoots roots(c, 4, 0, tb - ta);
        double u;
        while (roots.Next(u)) {
            const double t = ta + u;
            if (t > tMin && t < tMax) return t;
        }
        return std::nullopt;
    };

    std::sort(events.begin(), events.end(),
              [](const Event& a, const Event& b) { return a.t < b.t; });
    const auto byBall = [&spans](int k, int ball) { return spans[k].ball < ball; };
    for (size_t e = 0; e + 1 < events.size(); ++e) {
        const Event& event = events[e];
        // Active balls in increasing index, the order of the quartic's sums.
        const auto at =
            std::lower_bound(active.begin(), active.end(), spans[event.span].ball, byBall);
        if (event.entering) {
            active.insert(at, event.span);
        } else {
            active.erase(at);
        }
        const double ta = event.t, tb = events[e + 1].t;
        if (active.empty() || tb <= ta) continue;
        if (std::optional<double> root = solve(ta, tb)) return root;
    }
    return std::nullopt;
}

double MetaballSum::Value(const Vec3& p) const {
    thread_local std::vector<int> near;
    BallsAt(p, near);
    double f = 0;
    for (int i : near) {
        const Ball& b = balls_[i];
        const double q = 1 - LengthSquared(p - b.centre) / b.radius2;
        if (q > 0) f += b.strength * q * q;
    }
    return f;
}

Vec3 MetaballSum::Gradient(const Vec3& p) const {
    // ∇[s(1 − ρ²/r²)²] = −(4s/r²)(1 − ρ²/r²)(X − c) = (4·c4·ρ² + 2·c2)(X − c) with c4 = s/r⁴,
    // c2 = −2s/r², inside the ball.
    thread_local std::vector<int> near;
    BallsAt(p, near);
    Vec3 g;
    for (int i : near) {
        const Ball& b = balls_[i];
        const Vec3 d = p - b.centre;
        const double rho2 = LengthSquared(d);
        if (rho2 >= b.radius2) continue;
        const double c4 = b.strength / (b.radius2 * b.radius2), c2 = -2 * b.strength / b.radius2;
        g += d * (4 * c4 * rho2 + 2 * c2);
    }
    return g;
}

int MetaballSum::Predominant(const Vec3& p) const {
    thread_local std::vector<int> near;
    BallsAt(p, near);
    int best = -1;
    double bestValue = 0;
    for (int i : near) {  // increasing index: a later ball must be strictly larger
        const Ball& b = balls_[i];
        const double q = 1 - LengthSquared(p - b.centre) / b.radius2;
        if (q <= 0) continue;
        const double value = b.strength * q * q;
        if (best < 0 || value > bestValue) {
            best = i;
            bestValue = value;
        }
    }
    return best;
}

}  // namespace rs
