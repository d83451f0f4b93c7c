#include "libobj/implicit/method_registry.h"

#include "libobj/implicit/exact_method.h"
#include "libobj/implicit/march_method.h"
#include "libobj/implicit/polynomial_method.h"
#include "libobj/implicit/segment_method.h"
#include "libobj/implicit/sphere_method.h"

namespace rs {

namespace {

template <class M>
std::unique_ptr<IntersectionMethod> Make(const Field& field, const MethodParams& params) {
    return std::make_unique<M>(field, params);
}

}  // namespace

const std::vector<MethodEntry>& MethodRegistry() {
    static const std::vector<MethodEntry> registry = {
        {ImplicitMethod::Patches, "patches", nullptr, nullptr},
        {ImplicitMethod::Kb89, "kb89", nullptr, nullptr},
        {ImplicitMethod::March, "march", Make<MarchMethod>, nullptr},
        {ImplicitMethod::Sphere, "sphere", Make<SphereMethod>, nullptr},
        {ImplicitMethod::Segment, "segment", Make<SegmentMethod>, nullptr},
        {ImplicitMethod::Polynomial, "polynomial", Make<PolynomialMethod>, CheckPolynomialTerms},
        {ImplicitMethod::Exact, "exact", Make<ExactMethod>, nullptr},
        {ImplicitMethod::Auto, "auto", nullptr, nullptr},
    };
    return registry;
}

const MethodEntry& MethodEntryOf(ImplicitMethod method) {
    return MethodRegistry()[static_cast<size_t>(method)];
}

bool ParseImplicitMethod(const std::string& word, ImplicitMethod& method) {
    for (const MethodEntry& e : MethodRegistry()) {
        if (word == e.name) {
            method = e.method;
            return true;
        }
    }
    return false;
}

const char* ImplicitMethodName(ImplicitMethod method) { return MethodEntryOf(method).name; }

std::string ImplicitMethodNames() {
    std::string names;
    for (const MethodEntry& e : MethodRegistry()) {
        if (!names.empty()) names += ", ";
        names += e.name;
    }
    return names;
}

ImplicitMethod ResolveAutoMethod(const std::vector<FieldTerm>& terms, bool blendsOrContacts) {
    return !blendsOrContacts && CheckPolynomialTerms(terms).empty() ? ImplicitMethod::Polynomial
                                                                     : ImplicitMethod::Patches;
}

}  // namespace rs
