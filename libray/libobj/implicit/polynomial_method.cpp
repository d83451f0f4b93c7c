#include "libobj/implicit/polynomial_method.h"

#include "libcommon/error.h"
#include "libcommon/stats.h"

namespace rs {

std::string CheckPolynomialTerms(const std::vector<FieldTerm>& terms) {
    for (const FieldTerm& t : terms) {
        const bool pointOrSegment = std::holds_alternative<PointSkeleton>(t.skeleton) ||
                                    std::holds_alternative<SegmentSkeleton>(t.skeleton);
        if (!pointOrSegment || t.kernel.Kind() != KernelKind::Blob) {
            const bool blob = t.kernel.Kind() == KernelKind::Blob;
            return StringPrintf("method polynomial needs point or segment skeletons with the "
                                "blob kernel ('field blob ...'); skeleton '%s' is a %s%s",
                                t.name.c_str(), SkeletonKindName(t.skeleton),
                                blob ? "" : " with a Gascuel kernel");
        }
    }
    return {};
}

namespace {

// The metaball of a term (CheckPolynomialTerms accepts it).
Metaball MetaballOf(const FieldTerm& t) {
    const double strength = t.weight * t.kernel.Strength();
    if (const auto* segment = std::get_if<SegmentSkeleton>(&t.skeleton)) {
        return {segment->a, t.kernel.Radius(), strength, segment->b - segment->a};
    }
    return {std::get<PointSkeleton>(t.skeleton).center, t.kernel.Radius(), strength};
}

}  // namespace

PolynomialMethod::PolynomialMethod(const Field& field, const MethodParams& params)
    : sum_(params.threshold, field.Terms().size(),
           [&terms = field.Terms()](size_t i) { return MetaballOf(terms[i]); }) {}

std::optional<double> PolynomialMethod::FirstRoot(const Ray& ray, double tMin,
                                                  double tMax) const {
    int quartics = 0;
    std::optional<double> t = sum_.FirstRoot(ray, tMin, tMax, &quartics);
    Count(FieldCounterIds().values, static_cast<uint64_t>(quartics));
    return t;
}

// The field's terms are the metaballs of sum_, in the same order.
Vec3 PolynomialMethod::Gradient(const Field&, const Vec3& p) const { return sum_.Gradient(p); }

}  // namespace rs
