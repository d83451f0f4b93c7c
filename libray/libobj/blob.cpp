#include "libobj/blob.h"

#include <algorithm>
#include <cmath>

#include "libcommon/constants.h"
#include "libobj/polynomial.h"

namespace rs {

Blob::Blob(double threshold, std::vector<Ball> balls)
    : threshold_(threshold), balls_(std::move(balls)) {
    for (const Ball& b : balls_) {
        Vec3 r{b.radius, b.radius, b.radius};
        bounds_.Extend(Bounds3(b.centre - r, b.centre + r));
    }
}

std::shared_ptr<Primitive> Blob::Create(ArgReader& args) {
    double threshold = args.ReadNumber();
    std::vector<Ball> balls;
    bool degenerate = false;
    while (args.PeekNumber()) {
        Ball b;
        b.strength = args.ReadNumber();
        b.radius = args.ReadNumber();
        b.centre = args.ReadVector();
        degenerate = degenerate || b.strength < kEpsilon || b.radius < kEpsilon;
        balls.push_back(b);
    }
    if (balls.empty() || degenerate) {
        args.Warn(balls.empty() ? "blob without metaballs, discarded"
                                : "blob with a strength or radius below 1e-5, discarded");
        return nullptr;
    }
    return std::make_shared<Blob>(threshold, std::move(balls));
}

const IntersectionCounters& Blob::Counters() const {
    static const IntersectionCounters counters("Blob");
    return counters;
}

double Blob::Field(const Vec3& p) const {
    double f = 0;
    for (const Ball& b : balls_) {
        double q = 1 - LengthSquared(p - b.centre) / (b.radius * b.radius);
        if (q > 0) f += b.strength * q * q;
    }
    return f;
}

namespace {

// Relative margin of the field-bound rejection in Blob::Intersect. An interval's quartic is
// formed from terms of size at most 81·s per active ball (|q_i| ≤ 1 and each of q_i's three
// terms at most 4 in size on the ball's chord), so its computed values differ from the true
// field minus T by a few hundred ulp of T + Σs at most; a field bound below T by 10⁻⁷ of
// that is far outside this error and outside the solver's zero tolerance, so every value the
// solver would compute there is negative and it would report no root. The rounding of the
// interval's start point (about u·|o + t·d|, moving the field by up to 4s/r times that) stays
// below the margin for rays starting within some 10⁷ ball radii of the blob.
constexpr double kFieldBoundMargin = 1e-7;

}  // namespace

bool Blob::Intersect(const Ray& ray, double tMin, double tMax, PrimitiveHit& hit) const {
    // Influence-sphere boundary events along the ray, clipped to (tMin, tMax).
    struct Event {
        double t;
        int ball;
        bool entering;
    };
    // Per ball: whether its sphere of influence holds the current interval, and where the
    // ray passes closest to its centre (parameter and squared distance). On an interval its
    // term s·q², q = 1 − ρ²/r² ∈ [0, 1], is largest at the interval's point nearest to that.
    struct BallState {
        bool active;
        double tClosest, dist2;
    };
    const double dd = LengthSquared(ray.dir);
    if (!(dd > 0)) return false;
    Event stackEvents[32];
    BallState stackStates[16];
    std::vector<Event> heapEvents;
    std::vector<BallState> heapStates;
    Event* events = stackEvents;
    BallState* states = stackStates;
    if (balls_.size() > 16) {
        heapEvents.resize(2 * balls_.size());
        heapStates.resize(balls_.size());
        events = heapEvents.data();
        states = heapStates.data();
    }
    int count = 0;
    double peakSum = 0, strengthSum = 0;  // over the balls with events
    for (size_t i = 0; i < balls_.size(); ++i) {
        const Ball& b = balls_[i];
        // |o + t d − c|² = r²: solved around the closest approach for stability.
        Vec3 oc = ray.origin - b.centre;
        double tClosest = -Dot(oc, ray.dir) / dd;
        double dist2 = LengthSquared(oc + ray.dir * tClosest);
        states[i] = {false, tClosest, dist2};
        double r2 = b.radius * b.radius;
        double h2 = (r2 - dist2) / dd;
        if (h2 <= 0) continue;
        double h = std::sqrt(h2);
        double t0 = std::max(tClosest - h, tMin), t1 = std::min(tClosest + h, tMax);
        if (t0 >= t1) continue;
        events[count++] = {t0, static_cast<int>(i), true};
        events[count++] = {t1, static_cast<int>(i), false};
        const double q = 1 - dist2 / r2;
        peakSum += b.strength * q * q;
        strengthSum += b.strength;
    }
    if (count == 0) return false;
    // Even all the balls at their peaks stay below the threshold: no root anywhere.
    if (peakSum + kFieldBoundMargin * (threshold_ + strengthSum) < threshold_) return false;
    std::sort(events, events + count, [](const Event& a, const Event& b) { return a.t < b.t; });

    int activeCount = 0;
    for (int e = 0; e + 1 < count; ++e) {
        states[events[e].ball].active = events[e].entering;
        activeCount += events[e].entering ? 1 : -1;
        double ta = events[e].t, tb = events[e + 1].t;
        if (activeCount <= 0 || tb <= ta) continue;
        double bound = 0, activeStrength = 0;
        for (size_t i = 0; i < balls_.size(); ++i) {
            if (!states[i].active) continue;
            const Ball& b = balls_[i];
            const double gap = states[i].tClosest - std::clamp(states[i].tClosest, ta, tb);
            const double q = 1 - (states[i].dist2 + dd * gap * gap) / (b.radius * b.radius);
            bound += b.strength * q * q;
            activeStrength += b.strength;
        }
        if (bound + kFieldBoundMargin * (threshold_ + activeStrength) < threshold_) continue;

        // Quartic in s = t − ta: Σ s_i·q_i(s)² − T, with q_i = 1 − ρ_i²(s)/r_i² and
        // ρ_i² = |d|²s² + 2(o'−c)·d s + |o'−c|², o' = the point at ta.
        const Vec3 start = ray.At(ta);
        double c[5] = {-threshold_, 0, 0, 0, 0};  // ascending powers
        for (size_t i = 0; i < balls_.size(); ++i) {
            if (!states[i].active) continue;
            const Ball& b = balls_[i];
            double inv = 1 / (b.radius * b.radius);
            Vec3 oc = start - b.centre;
            double a2 = -dd * inv, a1 = -2 * Dot(oc, ray.dir) * inv, a0 = 1 - LengthSquared(oc) * inv;
            c[4] += b.strength * a2 * a2;
            c[3] += b.strength * 2 * a2 * a1;
            c[2] += b.strength * (a1 * a1 + 2 * a2 * a0);
            c[1] += b.strength * 2 * a1 * a0;
            c[0] += b.strength * a0 * a0;
        }
        // Roots come nearest first and only as many as needed are computed.
        AscendingRoots roots(c, 4, 0, tb - ta);
        double s;
        while (roots.Next(s)) {
            double t = ta + s;
            if (t > tMin && t < tMax) {
                hit.t = t;
                return true;
            }
        }
    }
    return false;
}

SurfaceNormals Blob::Normal(const Vec3& p, const PrimitiveHit&) const {
    // −∇F = −Σ_inside (4·c4·ρ² + 2·c2)(X − c), c4 = s/r⁴, c2 = −2s/r².
    Vec3 g;
    for (const Ball& b : balls_) {
        Vec3 d = p - b.centre;
        double rho2 = LengthSquared(d), r2 = b.radius * b.radius;
        if (rho2 >= r2) continue;
        double c4 = b.strength / (r2 * r2), c2 = -2 * b.strength / r2;
        g += d * (4 * c4 * rho2 + 2 * c2);
    }
    Vec3 n = Normalize(-g);
    if (LengthSquared(n) == 0) n = {0, 0, 1};  // a zero gradient (pinch point): any direction
    return {n, n, false};
}

}  // namespace rs
