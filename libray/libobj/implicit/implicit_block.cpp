#include "libobj/implicit/implicit_block.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "libcommon/error.h"
#include "libcommon/large_buffer.h"

namespace rs {

Kernel KernelWithParameters(KernelKind kind, const double (&params)[3]) {
    switch (kind) {
        case KernelKind::GascuelLinear:
            return Kernel::GascuelLinear(params[0], params[1], params[2]);
        case KernelKind::GascuelQuadratic:
            return Kernel::GascuelQuadratic(params[0], params[1], params[2]);
        default:
            return Kernel::Blob(params[0], params[1]);
    }
}

Kernel MakeKernelAt(const ImplicitDescription& d, size_t index, double time) {
    const KernelSpec& k = d.kernels[d.skeletons[index].kernel];
    double params[3] = {};
    for (int i = 0; i < k.paramCount; ++i) params[i] = d.numbers.At(k.params[i], time);
    return KernelWithParameters(k.kind, params);
}

namespace {

// What is wrong with a skeleton's term, and the statement at fault: the skeleton's, or the
// `field` statement of its kernel when the kernel's parameters are invalid.
struct TermError {
    std::string message;
    StatementPlace place;
    bool Failed() const { return !message.empty(); }
};

}  // namespace

bool HasAnimatedKernel(const ImplicitDescription& d, size_t index) {
    const KernelSpec& k = d.kernels[d.skeletons[index].kernel];
    for (int i = 0; i < k.paramCount; ++i) {
        if (d.numbers.IsAnimated(k.params[i])) return true;
    }
    return false;
}

bool IsAnimatedSkeleton(const ImplicitDescription& d, size_t index) {
    const SkeletonSpec& e = d.skeletons[index];
    for (size_t i = e.firstNumber; i < e.firstNumber + e.numberCount; ++i) {
        if (d.numbers.IsAnimated(i)) return true;
    }
    return HasAnimatedKernel(d, index) || d.numbers.IsAnimated(e.weight);
}

std::string MakeSkeletonAt(const ImplicitDescription& d, size_t index, double time,
                           Skeleton& skeleton) {
    const SkeletonSpec& e = d.skeletons[index];
    const std::string& name = d.names.Name(index);
    auto n = [&](size_t i) { return d.numbers.At(e.firstNumber + i, time); };
    auto vec = [&n](size_t i) { return Vec3{n(i), n(i + 1), n(i + 2)}; };
    const char* who = name.c_str();
    switch (e.kind) {
        case SkeletonKind::Point:
            skeleton = PointSkeleton{vec(0)};
            break;
        case SkeletonKind::Segment:
            skeleton = SegmentSkeleton{vec(0), vec(3)};
            break;
        case SkeletonKind::Polyline: {
            PolylineSkeleton p;
            p.points.reserve(e.numberCount / 3);
            for (size_t i = 0; i + 2 < e.numberCount; i += 3) p.points.push_back(vec(i));
            skeleton = std::move(p);
            break;
        }
        case SkeletonKind::Circle: {
            const double radius = n(0);
            const Vec3 normal = vec(4);
            if (!(radius > 0) || LengthSquared(normal) == 0) {
                return StringPrintf(
                    "skeleton '%s': circle needs a radius > 0 and a non-zero normal", who);
            }
            skeleton = CircleSkeleton{vec(1), Normalize(normal), radius};
            break;
        }
        case SkeletonKind::Triangle:
            skeleton = TriangleSkeleton{vec(0), vec(3), vec(6)};
            break;
        case SkeletonKind::Box: {
            const Vec3 a = vec(0), b = vec(3);
            skeleton = BoxSkeleton{Min(a, b), Max(a, b)};
            break;
        }
        case SkeletonKind::Cylinder: {
            const double radius = n(0);
            if (!(radius >= 0)) {
                return StringPrintf("skeleton '%s': cylinder radius must be >= 0", who);
            }
            skeleton = CylinderSkeleton{vec(1), vec(4), radius};
            break;
        }
    }
    return {};
}

namespace {

// Builds the term of skeleton `index` at `time`.
TermError MakeTerm(const ImplicitDescription& d, size_t index, double time, FieldTerm& term) {
    const SkeletonSpec& e = d.skeletons[index];
    const std::string& name = d.names.Name(index);
    if (std::string error = MakeSkeletonAt(d, index, time, term.skeleton); !error.empty()) {
        return {std::move(error), e.place};
    }
    term.name = name;
    term.weight = d.numbers.At(e.weight, time);
    const KernelSpec& kernel = d.kernels[e.kernel];
    term.kernel = MakeKernelAt(d, index, time);
    if (!std::isfinite(term.weight)) {
        return {StringPrintf("skeleton '%s': weight is not finite", name.c_str()), e.place};
    }
    KernelStatus status = term.kernel.Validate(name);
    if (status.ok) return {};
    // The default kernel has no statement: its parameters are valid, unless animated.
    return {status.message, kernel.place.line > 0 ? kernel.place : e.place};
}

// Builds the terms of every skeleton at `time` into `terms` (empty); returns the first
// skeleton's error instead.
TermError MakeTerms(const ImplicitDescription& d, double time, std::vector<FieldTerm>& terms) {
    terms.reserve(d.skeletons.size());
    AdviseHugePages(terms.data(), terms.capacity() * sizeof(FieldTerm));
    for (size_t i = 0; i < d.skeletons.size(); ++i) {
        TermError error = MakeTerm(d, i, time, terms.emplace_back());
        if (error.Failed()) return error;
    }
    return {};
}

// The term index of a name in a statement, failing at the statement when it is unknown.
int FindSkeleton(const ImplicitDescription& d, const std::string& name, const char* statement,
                 StatementPlace place, ArgReader& args) {
    const long i = d.names.Find(name);
    if (i < 0) {
        args.FailAtLocation(d.Where(place),
                    StringPrintf("%s names unknown skeleton '%s'", statement, name.c_str()));
    }
    return static_cast<int>(i);
}

// The blend graph: every pair of a list, or the hub with each listed skeleton. `pairBlend`
// gets the blend statement of each pair, for messages.
void ResolveBlends(const ImplicitDescription& d, ArgReader& args, ImplicitOptions& options,
                   std::vector<size_t>& pairBlend) {
    if (d.blends.empty()) return;
    options.blendMode = BlendMode::Explicit;
    for (size_t b = 0; b < d.blends.size(); ++b) {
        const BlendSpec& blend = d.blends[b];
        std::vector<int> listed;
        for (const std::string& n : blend.names) {
            listed.push_back(FindSkeleton(d, n, "blend", blend.place, args));
        }
        if (!blend.hub.empty()) {
            const int hub = FindSkeleton(d, blend.hub, "blend", blend.place, args);
            for (size_t i = 0; i < listed.size(); ++i) {
                if (listed[i] == hub) {
                    args.FailAtLocation(d.Where(blend.place),
                                "blend lists its hub '" + blend.hub + "' after the ':'");
                }
                options.blendPairs.emplace_back(hub, listed[i]);
                pairBlend.push_back(b);
            }
            continue;
        }
        for (size_t i = 0; i < listed.size(); ++i) {
            for (size_t j = i + 1; j < listed.size(); ++j) {
                options.blendPairs.emplace_back(listed[i], listed[j]);
                pairBlend.push_back(b);
            }
        }
    }
    if (options.method != ImplicitMethod::Patches && options.method != ImplicitMethod::Auto) {
        args.WarnAtLocation(d.Where(d.blends[0].place),
                    StringPrintf("'blend' is ignored with 'method %s' (one field, everything "
                                 "blends)",
                                 ImplicitMethodName(options.method)));
    }
}

void ResolveContacts(const ImplicitDescription& d, ArgReader& args, ImplicitOptions& options,
                     const std::vector<size_t>& pairBlend) {
    for (const ContactSpec& c : d.contacts) {
        const int ia = FindSkeleton(d, c.a, "contact", c.place, args);
        const int ib = FindSkeleton(d, c.b, "contact", c.place, args);
        if (ia == ib) {
            args.FailAtLocation(d.Where(c.place),
                        "contact needs two different skeletons, not '" + c.a + "' twice");
        }
        for (size_t p = 0; p < options.blendPairs.size(); ++p) {
            const auto [x, y] = options.blendPairs[p];
            if ((x == ia && y == ib) || (x == ib && y == ia)) {
                args.FailAtLocation(d.Where(c.place),
                            StringPrintf("skeletons '%s' and '%s' both blend (line %d) and are "
                                         "in contact",
                                         c.a.c_str(), c.b.c_str(),
                                         d.blends[pairBlend[p]].place.line));
            }
        }
        options.contacts.push_back({ia, ib});
    }
    for (const PropagationSpec& p : d.propagations) {
        const int term = FindSkeleton(d, p.name, "propagation", p.place, args);
        bool inContact = std::any_of(options.contacts.begin(), options.contacts.end(),
                                     [term](const ContactPair& c) {
                                         return c.a == term || c.b == term;
                                     });
        if (!inContact && !options.autoContacts) {
            args.WarnAtLocation(d.Where(p.place),
                        "propagation of '" + p.name + "', which is in no contact");
        }
        options.propagations.push_back({term, p.width, p.height});
    }
    if (!d.contacts.empty() && options.method != ImplicitMethod::Patches &&
        options.method != ImplicitMethod::Auto) {
        args.WarnAtLocation(d.Where(d.contacts[0].place),
                    StringPrintf("'contact' is ignored with 'method %s' (one field, everything "
                                 "blends)",
                                 ImplicitMethodName(options.method)));
    }
}

// The options of the block's settings, with the method possibly still Auto.
ImplicitOptions SettingsOptions(const BlockSettings& s) {
    ImplicitOptions options;
    options.threshold = s.threshold;
    options.autoDepth = s.autoDepth;
    options.method = s.method;
    options.marchStep = s.marchStep;
    options.autoContacts = s.autoContacts;
    options.search.tolerance = s.tolerance;
    options.search.minWidth = s.tolerance;
    options.search.autoTolerance = s.autoTolerance;
    options.patchesDRatio = s.dRatio;
    options.octree = MethodOctreeHeuristics(options.method, s.maxDepth, s.dRatio);
    return options;
}

}  // namespace

BuiltImplicitBlock BuildImplicitBlock(ImplicitDescription description, ArgReader& args) {
    const ImplicitDescription& d = description;
    BuiltImplicitBlock built;
    built.options = SettingsOptions(d.settings);
    std::vector<size_t> pairBlend;
    ResolveBlends(d, args, built.options, pairBlend);
    ResolveContacts(d, args, built.options, pairBlend);
    if (TermError error = MakeTerms(d, 0, built.terms); error.Failed()) {
        args.FailAtLocation(d.Where(error.place), error.message);
    }
    bool animated = false, anyPositive = false;
    for (size_t i = 0; i < built.terms.size(); ++i) {
        const SkeletonSpec& e = d.skeletons[i];
        animated |= IsAnimatedSkeleton(d, i);
        anyPositive |= built.terms[i].weight > 0 || d.numbers.IsAnimated(e.weight);
    }
    if (!anyPositive) {
        args.Warn("implicit object without a skeleton of positive weight, discarded");
        return {};
    }
    ImplicitOptions& options = built.options;
    if (std::string error = ChooseMethod(options.method, built.terms, options, options.method);
        !error.empty()) {
        const StatementPlace method = d.settings.methodPlace;
        method.line > 0 ? args.FailAtLocation(d.Where(method), error) : args.Fail(error);
    }
    if (animated) {
        built.description = std::make_shared<const ImplicitDescription>(std::move(description));
        built.termsAt = [block = built.description](double time) {
            std::vector<FieldTerm> out;
            if (TermError error = MakeTerms(*block, time, out); error.Failed()) {
                Report(Severity::Abort, block->Where(error.place),
                       "implicit object at time %g: %s", time, error.message.c_str());
            }
            return out;
        };
    }
    return built;
}

}  // namespace rs
