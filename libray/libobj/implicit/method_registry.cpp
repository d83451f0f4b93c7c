#include "libobj/implicit/method_registry.h"

#include "libobj/implicit/exact_method.h"
#include "libobj/implicit/kb89_method.h"
#include "libobj/implicit/march_method.h"
#include "libobj/implicit/patches_method.h"
#include "libobj/implicit/polynomial_method.h"
#include "libobj/implicit/segment_method.h"
#include "libobj/implicit/sphere_method.h"

namespace rs {

namespace {

template <class M>
std::unique_ptr<IntersectionMethod> Make(const Field& whole, const ImplicitOptions& options,
                                         const ImplicitObjectStats&) {
    return std::make_unique<M>(whole, BaselineParams(options));
}

std::unique_ptr<IntersectionMethod> MakePatches(const Field& whole,
                                                const ImplicitOptions& options,
                                                const ImplicitObjectStats& stats) {
    return std::make_unique<PatchesMethod>(whole, options, stats);
}

std::unique_ptr<IntersectionMethod> MakeKb89(const Field& whole, const ImplicitOptions& options,
                                             const ImplicitObjectStats& stats) {
    return std::make_unique<Kb89Method>(whole, options.threshold,
                                        OctreeSettings(options.search, options.octree), stats);
}

}  // namespace

const std::vector<MethodEntry>& MethodRegistry() {
    static const std::vector<MethodEntry> registry = {
        {ImplicitMethod::Patches, "patches", MakePatches, nullptr, ImplicitMethod::Patches},
        {ImplicitMethod::Kb89, "kb89", MakeKb89, nullptr, ImplicitMethod::Kb89},
        {ImplicitMethod::March, "march", Make<MarchMethod>, nullptr, ImplicitMethod::March},
        {ImplicitMethod::Sphere, "sphere", Make<SphereMethod>, nullptr, ImplicitMethod::Sphere},
        {ImplicitMethod::Segment, "segment", Make<SegmentMethod>, nullptr,
         ImplicitMethod::Segment},
        // Its quartics are the terms' at one time: while moving, kb89 sums the same field.
        {ImplicitMethod::Polynomial, "polynomial", Make<PolynomialMethod>, CheckPolynomialTerms,
         ImplicitMethod::Kb89},
        {ImplicitMethod::Exact, "exact", Make<ExactMethod>, nullptr, ImplicitMethod::Exact},
        {ImplicitMethod::Auto, "auto", nullptr, nullptr, ImplicitMethod::Auto},
    };
    return registry;
}

MethodParams BaselineParams(const ImplicitOptions& options) {
    MethodParams params;
    params.threshold = options.threshold;
    params.tolerance = options.search.tolerance;
    params.step = options.marchStep;
    return params;
}

OctreeHeuristics MethodOctreeHeuristics(ImplicitMethod method, int maxDepth,
                                        double patchesDRatio) {
    const bool kb89 = method == ImplicitMethod::Kb89;
    OctreeHeuristics h = kb89 ? OctreeHeuristics::Kb89() : OctreeHeuristics{};
    h.maxDepth = maxDepth;
    if (!kb89) h.dRatio = patchesDRatio;
    return h;
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

std::string ChooseMethod(ImplicitMethod requested, const std::vector<FieldTerm>& terms,
                         const ImplicitOptions& options, ImplicitMethod& chosen) {
    const bool blendsOrContacts =
        options.blendMode == BlendMode::Explicit || !options.contacts.empty() ||
        options.autoContacts;
    const ImplicitMethod method = requested == ImplicitMethod::Auto
                                      ? ResolveAutoMethod(terms, blendsOrContacts)
                                      : requested;
    const MethodEntry& entry = MethodEntryOf(method);
    if (entry.check) {
        std::string error = entry.check(terms);
        if (!error.empty()) return error;
    }
    chosen = method;
    return {};
}

}  // namespace rs
