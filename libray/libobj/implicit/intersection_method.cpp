#include "libobj/implicit/intersection_method.h"

#include <algorithm>
#include <cmath>

#include "libobj/implicit/root_finding.h"

namespace rs {

Bounds3 PositiveSupportBounds(const Field& field) {
    Bounds3 box;
    for (const FieldTerm& t : field.Terms()) {
        if (t.weight > 0) box.Extend(TermSupportBounds(t));
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

}  // namespace rs
