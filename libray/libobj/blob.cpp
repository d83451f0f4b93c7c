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

bool Blob::Intersect(const Ray& ray, double tMin, double tMax, PrimitiveHit& hit) const {
    // Influence-sphere boundary events along the ray, clipped to (tMin, tMax).
    struct Event {
        double t;
        int ball;
        bool entering;
    };
    const double dd = LengthSquared(ray.dir);
    if (!(dd > 0)) return false;
    Event stackEvents[32];
    std::vector<Event> heapEvents;
    Event* events = stackEvents;
    if (balls_.size() > 16) {
        heapEvents.resize(2 * balls_.size());
        events = heapEvents.data();
    }
    int count = 0;
    for (size_t i = 0; i < balls_.size(); ++i) {
        const Ball& b = balls_[i];
        // |o + t d − c|² = r²: solved around the closest approach for stability.
        Vec3 oc = ray.origin - b.centre;
        double tClosest = -Dot(oc, ray.dir) / dd;
        double dist2 = LengthSquared(oc + ray.dir * tClosest);
        double h2 = (b.radius * b.radius - dist2) / dd;
        if (h2 <= 0) continue;
        double h = std::sqrt(h2);
        double t0 = std::max(tClosest - h, tMin), t1 = std::min(tClosest + h, tMax);
        if (t0 >= t1) continue;
        events[count++] = {t0, static_cast<int>(i), true};
        events[count++] = {t1, static_cast<int>(i), false};
    }
    if (count == 0) return false;
    std::sort(events, events + count, [](const Event& a, const Event& b) { return a.t < b.t; });

    int activeCount = 0;
    char stackActive[16];
    std::vector<char> heapActive;
    char* active = stackActive;
    if (balls_.size() > 16) {
        heapActive.resize(balls_.size());
        active = heapActive.data();
    }
    std::fill(active, active + balls_.size(), 0);
    for (int e = 0; e + 1 < count; ++e) {
        active[events[e].ball] = events[e].entering;
        activeCount += events[e].entering ? 1 : -1;
        double ta = events[e].t, tb = events[e + 1].t;
        if (activeCount <= 0 || tb <= ta) continue;

        // Quartic in s = t − ta: Σ s_i·q_i(s)² − T, with q_i = 1 − ρ_i²(s)/r_i² and
        // ρ_i² = |d|²s² + 2(o'−c)·d s + |o'−c|², o' = the point at ta.
        const Vec3 start = ray.At(ta);
        double c[5] = {-threshold_, 0, 0, 0, 0};  // ascending powers
        for (size_t i = 0; i < balls_.size(); ++i) {
            if (!active[i]) continue;
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
