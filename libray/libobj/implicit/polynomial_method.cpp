#include "libobj/implicit/polynomial_method.h"

#include <algorithm>
#include <cmath>

#include "libcommon/error.h"
#include "libcommon/stats.h"
#include "libobj/polynomial.h"

namespace rs {

std::string CheckPolynomialTerms(const std::vector<FieldTerm>& terms) {
    for (const FieldTerm& t : terms) {
        if (!std::holds_alternative<PointSkeleton>(t.skeleton) ||
            t.kernel.Kind() != KernelKind::Blob) {
            const bool blob = t.kernel.Kind() == KernelKind::Blob;
            return StringPrintf("method polynomial needs point skeletons with the blob kernel "
                                "('field blob ...'); skeleton '%s' is a %s%s",
                                t.name.c_str(), SkeletonKindName(t.skeleton),
                                blob ? "" : " with a Gascuel kernel");
        }
    }
    return {};
}

PolynomialMethod::PolynomialMethod(const Field& field, const MethodParams& params)
    : field_(field), threshold_(params.threshold), box_(PositiveSupportBounds(field)) {}

namespace {

struct Span {
    double enter, exit;
    int term;
};

}  // namespace

std::optional<double> PolynomialMethod::FirstRoot(const Ray& ray, double tMin,
                                                  double tMax) const {
    double t0 = tMin, t1 = tMax;
    if (!box_.ClipRay(ray, t0, t1)) return std::nullopt;
    const std::vector<FieldTerm>& terms = field_.Terms();
    const double a = Dot(ray.dir, ray.dir);
    // Each term's sphere of influence along the ray: |o + t·d − c|² < R².
    std::vector<Span> spans;
    std::vector<double> events{t0, t1};
    for (size_t i = 0; i < terms.size(); ++i) {
        const Vec3 c = std::get<PointSkeleton>(terms[i].skeleton).center;
        const double r = terms[i].kernel.Radius();
        const Vec3 q = ray.origin - c;
        const double b = Dot(q, ray.dir);
        // Distance² of the closest approach, computed without cancellation.
        const Vec3 perp = q - ray.dir * (b / a);
        const double disc = a * (r * r - Dot(perp, perp));
        if (!(disc > 0)) continue;
        const double tc = -b / a, half = std::sqrt(disc) / a;
        Span s{tc - half, tc + half, static_cast<int>(i)};
        if (s.exit <= t0 || s.enter >= t1) continue;
        spans.push_back(s);
        events.push_back(std::clamp(s.enter, t0, t1));
        events.push_back(std::clamp(s.exit, t0, t1));
    }
    std::sort(events.begin(), events.end());
    events.erase(std::unique(events.begin(), events.end()), events.end());
    for (size_t k = 0; k + 1 < events.size(); ++k) {
        const double ta = events[k], tb = events[k + 1];
        const double mid = 0.5 * (ta + tb);
        // F − T on [ta, tb] as a quartic in u = t − ta, ascending coefficients.
        double coeffs[5] = {-threshold_, 0, 0, 0, 0};
        const Vec3 start = ray.At(ta);
        bool any = false;
        for (const Span& s : spans) {
            if (!(s.enter < mid && s.exit > mid)) continue;
            const FieldTerm& term = terms[s.term];
            const double r2 = term.kernel.Radius() * term.kernel.Radius();
            const Vec3 q = start - std::get<PointSkeleton>(term.skeleton).center;
            // h(u) = 1 − |q + u·d|²/R² = γ + βu + αu².
            const double alpha = -a / r2, beta = -2 * Dot(q, ray.dir) / r2,
                         gamma = 1 - Dot(q, q) / r2;
            const double w = term.weight * term.kernel.Strength();
            coeffs[0] += w * gamma * gamma;
            coeffs[1] += w * 2 * beta * gamma;
            coeffs[2] += w * (beta * beta + 2 * alpha * gamma);
            coeffs[3] += w * 2 * alpha * beta;
            coeffs[4] += w * alpha * alpha;
            any = true;
        }
        if (!any) continue;  // F = 0 < T on the whole interval
        Count(FieldCounterIds().values);
        AscendingRoots roots(coeffs, 4, 0, tb - ta);
        double u;
        while (roots.Next(u)) {
            const double t = ta + u;
            if (t > tMin && t < tMax) return t;
        }
    }
    return std::nullopt;
}

}  // namespace rs
