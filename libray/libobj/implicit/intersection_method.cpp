#include "libobj/implicit/intersection_method.h"

#include <algorithm>
#include <cmath>

#include "libobj/implicit/root_finding.h"

namespace rs {

Bounds3 PositiveSupportBounds(const Field& field) {
    Bounds3 box;
    for (int i = 0; i < static_cast<int>(field.Terms().size()); ++i) {
        if (field.Terms()[i].weight > 0) box.Extend(field.TermSupport(i));
    }
    return box;
}

double BisectBracket(const RayField& g, double a, double ga, double b, double gb, double tolT) {
    // 2000 halvings exhaust any double bracket (BisectRoot stops at adjacent doubles).
    std::optional<RootResult> r = BisectRoot(g, a, ga, b, gb, tolT, 2000);
    return r ? r->root : (std::abs(ga) <= std::abs(gb) ? a : b);
}

double NextSample(double t, double dt, double tEnd) {
    return std::min(std::max(t + dt, std::nextafter(t, tEnd)), tEnd);
}

std::optional<double> RootOfStep(const RayField& g, double ta, double ga, double tb, double gb,
                                 double tolT, double tMin, double tMax) {
    if (gb == 0 && tb > tMin && tb < tMax) return tb;
    if (ClassChanges(ga, gb)) {
        double root = BisectBracket(g, ta, ga, tb, gb, tolT);
        if (root > tMin && root < tMax) return root;
    }
    return std::nullopt;
}

std::optional<MethodHit> IntersectionMethod::Intersect(const Ray& ray, double tMin,
                                                       double tMax) const {
    std::optional<double> t = FirstRoot(ray, tMin, tMax);
    if (!t) return std::nullopt;
    return MethodHit{*t, PredominantTerm(ray.At(*t))};
}

Vec3 IntersectionMethod::Normal(const Field& whole, const Vec3& p, int) const {
    const Vec3 n = Normalize(-Gradient(whole, p));
    if (LengthSquared(n) != 0) return n;
    int own = 0;
    for (int i = 1; i < whole.Size(); ++i) {
        if (whole.TermValue(i, p) > whole.TermValue(own, p)) own = i;
    }
    return AwayFromSkeleton(whole, own, p);
}

Bounds3 IntersectionMethod::Bounds(const Field& whole) const { return PositiveSupportBounds(whole); }

Vec3 AwayFromSkeleton(const Field& field, int own, const Vec3& p) {
    Vec3 closest;
    SkeletonDistance(field.TermAt(own).skeleton, p, closest);
    const Vec3 n = Normalize(p - closest);
    return LengthSquared(n) == 0 ? Vec3{0, 0, 1} : n;
}

}  // namespace rs
