#include "libobj/implicit/implicit_surface.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <climits>
#include <cmath>
#include <map>
#include <string>

#include "libcommon/error.h"
#include "libcommon/limits.h"
#include "libcommon/stats.h"

namespace rs {

namespace {

struct KernelSpec {
    KernelKind kind = KernelKind::GascuelQuadratic;
    AnimatedValue params[3];  // thickness, stiffness, radius; blob: strength, radius
};

KernelSpec DefaultKernel() {
    KernelSpec k;  // `field quadratic 1 1 2`: m = k(R − e) = 1
    k.params[0].value = 1;
    k.params[1].value = 1;
    k.params[2].value = 2;
    return k;
}

// One skeleton as declared; its numbers in syntax order, possibly animated.
struct ElementSpec {
    std::string name;
    std::string kind;
    std::vector<AnimatedValue> numbers;
    AnimatedValue weight;
    KernelSpec kernel;
};

bool IsAnimated(const ElementSpec& e) {
    auto animated = [](const AnimatedValue& v) { return v.IsAnimated(); };
    return std::any_of(e.numbers.begin(), e.numbers.end(), animated) || e.weight.IsAnimated() ||
           std::any_of(std::begin(e.kernel.params), std::end(e.kernel.params), animated);
}

Kernel MakeKernel(const KernelSpec& k, double time) {
    double a = k.params[0].At(time), b = k.params[1].At(time), c = k.params[2].At(time);
    switch (k.kind) {
        case KernelKind::GascuelLinear:
            return Kernel::GascuelLinear(a, b, c);
        case KernelKind::GascuelQuadratic:
            return Kernel::GascuelQuadratic(a, b, c);
        default:
            return Kernel::Blob(a, b);
    }
}

// Builds the term at `time`; returns an error message instead when the skeleton or the
// kernel is invalid.
std::string MakeTerm(const ElementSpec& e, double time, FieldTerm& term) {
    std::vector<double> n;
    for (const AnimatedValue& v : e.numbers) n.push_back(v.At(time));
    auto vec = [&n](size_t i) { return Vec3{n[i], n[i + 1], n[i + 2]}; };
    const char* who = e.name.c_str();
    if (e.kind == "point") {
        term.skeleton = PointSkeleton{vec(0)};
    } else if (e.kind == "segment") {
        term.skeleton = SegmentSkeleton{vec(0), vec(3)};
    } else if (e.kind == "polyline") {
        PolylineSkeleton p;
        for (size_t i = 0; i + 2 < n.size(); i += 3) p.points.push_back(vec(i));
        term.skeleton = p;
    } else if (e.kind == "circle") {
        Vec3 normal = vec(4);
        if (!(n[0] > 0) || LengthSquared(normal) == 0) {
            return StringPrintf("skeleton '%s': circle needs a radius > 0 and a non-zero normal",
                                who);
        }
        term.skeleton = CircleSkeleton{vec(1), Normalize(normal), n[0]};
    } else if (e.kind == "triangle") {
        term.skeleton = TriangleSkeleton{vec(0), vec(3), vec(6)};
    } else if (e.kind == "box") {
        term.skeleton = BoxSkeleton{Min(vec(0), vec(3)), Max(vec(0), vec(3))};
    } else {
        if (!(n[0] >= 0)) {
            return StringPrintf("skeleton '%s': cylinder radius must be >= 0", who);
        }
        term.skeleton = CylinderSkeleton{vec(1), vec(4), n[0]};
    }
    term.name = e.name;
    term.weight = e.weight.At(time);
    term.kernel = MakeKernel(e.kernel, time);
    if (!std::isfinite(term.weight)) {
        return StringPrintf("skeleton '%s': weight is not finite", who);
    }
    KernelStatus status = term.kernel.Validate(e.name);
    return status.ok ? std::string() : status.message;
}

KernelSpec ReadKernel(ArgReader& args) {
    KernelSpec k;
    int count = 3;
    if (args.Accept("linear")) {
        k.kind = KernelKind::GascuelLinear;
    } else if (args.Accept("quadratic")) {
        k.kind = KernelKind::GascuelQuadratic;
    } else if (args.Accept("blob")) {
        k.kind = KernelKind::Blob;
        count = 2;
    } else {
        args.Fail("expected linear, quadratic or blob after 'field'");
    }
    for (int i = 0; i < count; ++i) k.params[i] = args.ReadAnimatedNumber();
    return k;
}

// Polyline skeletons hold at most 2^20 points.

// Number count of each skeleton keyword (polyline: read separately).
int SkeletonArity(const std::string& kind) {
    static const std::map<std::string, int> arity = {
        {"point", 3}, {"segment", 6}, {"circle", 7}, {"triangle", 9}, {"box", 6}, {"cylinder", 7}};
    auto it = arity.find(kind);
    return it == arity.end() ? -1 : it->second;
}

constexpr const char* kSkeletonKinds[] = {"point",    "segment", "polyline", "circle",
                                          "triangle", "box",     "cylinder"};

}  // namespace

bool ImplicitSurface::IsBlockWord(const std::string& word) {
    static const char* const kStatements[] = {"threshold", "tolerance", "octree", "method",
                                              "field",     "blend",     "end"};
    for (const char* w : kStatements)
        if (word == w) return true;
    for (const char* w : kSkeletonKinds)
        if (word == w) return true;
    return false;
}

namespace {

// True when the next token starts a statement of the block (or ends it), so open-ended
// name lists stop there.
bool PeekStatement(ArgReader& args) {
    for (const char* word :
         {"end", "threshold", "tolerance", "octree", "method", "field", "blend"}) {
        if (args.Peek(word)) return true;
    }
    for (const char* kind : kSkeletonKinds) {
        if (args.Peek(kind)) return true;
    }
    return args.PeekNumber();
}

// Settings of a method, keeping the declared depth, Dratio and tolerance of `declared`
// (kb89's heuristics for kb89; the patches defaults otherwise, unused by the baselines).
OctreeSettings MethodSettings(ImplicitMethod method, const OctreeSettings& declared,
                              double patchesDRatio) {
    const bool kb89 = method == ImplicitMethod::Kb89;
    OctreeSettings s = kb89 ? OctreeSettings::Kb89() : OctreeSettings{};
    s.maxDepth = declared.maxDepth;
    if (!kb89) s.dRatio = patchesDRatio;
    s.tolerance = declared.tolerance;
    s.minWidth = declared.minWidth;
    return s;
}

constexpr const char kCounterPrefix[] = "Implicit ";
constexpr const char kOctreeCounterPrefix[] = "Implicit octree ";

bool StartsWith(const std::string& s, const char* prefix) {
    return s.compare(0, std::char_traits<char>::length(prefix), prefix) == 0;
}

}  // namespace

ImplicitSurface::ImplicitSurface(std::vector<FieldTerm> terms, ImplicitOptions options)
    : terms_(std::move(terms)), options_(std::move(options)) {
    static std::atomic<int> created{0};
    label_ = "Implicit object " + std::to_string(++created);
    auto reg = [this](const char* what) { return RegisterCounter(label_ + ": " + what); };
    counters_.tests = reg("intersection calls");
    counters_.hits = reg("hits");
    counters_.values = reg("field evaluations");
    counters_.gradients = reg("gradient evaluations");
    counters_.bounds = reg("bound evaluations");
    counters_.riddersIterations = reg("Ridders iterations");
    counters_.buildMicroseconds = reg("preprocessing time (microseconds)");
    counters_.cells = reg("octree cells");
    counters_.memoryBytes = reg("octree memory (bytes)");
    Build();
}

std::string ImplicitSurface::SetMethod(ImplicitMethod method) {
    ImplicitOverrides overrides;
    overrides.method = method;
    return ApplyOverrides(overrides);
}

std::string ImplicitSurface::ApplyOverrides(const ImplicitOverrides& overrides) {
    if (overrides.method) {
        const MethodEntry& entry = MethodEntryOf(*overrides.method);
        if (entry.check) {
            std::string error = entry.check(terms_);
            if (!error.empty()) return label_ + ": " + error;
        }
        options_.method = *overrides.method;
        options_.octree = MethodSettings(options_.method, options_.octree, options_.patchesDRatio);
    }
    if (overrides.maxDepth) options_.octree.maxDepth = *overrides.maxDepth;
    if (overrides.dRatio) {
        options_.patchesDRatio = *overrides.dRatio;
        if (options_.method != ImplicitMethod::Kb89) options_.octree.dRatio = *overrides.dRatio;
    }
    if (overrides.tolerance) {
        options_.octree.tolerance = *overrides.tolerance;
        options_.octree.minWidth = *overrides.tolerance;
    }
    if (overrides.step) options_.marchStep = *overrides.step;
    for (const auto& [name, on] : overrides.switches) *OctreeSwitch(options_.octree, name) = on;
    Build();
    return {};
}

std::string ImplicitSurface::PatchName(const PrimitiveHit& hit) const {
    if (hit.part < 0 || hit.part >= static_cast<int>(patches_.size())) return {};
    return terms_[patches_[hit.part].Own()].name;
}

// Builds the patches and octrees and counts the work under this object's label. Builds run
// outside rendering (parsing, PrepareFrame), so the differences of the process-wide totals
// around it are this object's; the build counters are found by their common prefix.
void ImplicitSurface::Build() {
    const std::vector<CounterValue> before = StatsSnapshot();
    const auto start = std::chrono::steady_clock::now();
    BuildStructures();
    const auto micros = std::chrono::duration_cast<std::chrono::microseconds>(
        std::chrono::steady_clock::now() - start);
    Count(counters_.buildMicroseconds, static_cast<uint64_t>(micros.count()));
    uint64_t cells = 0, memory = 0;
    for (const LGOctree& tree : trees_) {
        cells += static_cast<uint64_t>(tree.InternalCount() + tree.LeafCount());
        memory += tree.MemoryBytes();
    }
    Count(counters_.cells, cells);
    Count(counters_.memoryBytes, memory);
    const std::vector<CounterValue> after = StatsSnapshot();
    for (size_t i = 0; i < after.size(); ++i) {
        const std::string& name = after[i].name;
        uint64_t delta = after[i].value - (i < before.size() ? before[i].value : 0);
        if (delta == 0 || !StartsWith(name, kCounterPrefix) || StartsWith(name, "Implicit object")) {
            continue;
        }
        std::string what = name.substr(std::char_traits<char>::length(kCounterPrefix));
        if (!StartsWith(name, kOctreeCounterPrefix)) what = "preprocessing " + what;
        Count(RegisterCounter(label_ + ": " + what), delta);
    }
}

void ImplicitSurface::BuildStructures() {
    whole_ = Field(terms_);
    patches_.clear();
    trees_.clear();
    bounds_ = Bounds3();
    baseline_.reset();
    const double threshold = options_.threshold;
    if (const MethodEntry& entry = MethodEntryOf(options_.method); entry.create) {
        bounds_ = PositiveSupportBounds(whole_);
        MethodParams params;
        params.threshold = threshold;
        params.tolerance = options_.octree.tolerance;
        params.step = options_.marchStep;
        baseline_ = entry.create(whole_, params);
        return;
    }
    if (options_.method == ImplicitMethod::Kb89) {
        // The surface lies where some positive term is positive (F = T > 0).
        for (const FieldTerm& t : terms_) {
            if (t.weight > 0) bounds_.Extend(TermSupportBounds(t));
        }
        trees_.emplace_back(whole_, threshold, bounds_, options_.octree);
        return;
    }
    patches_ = BuildPatches(terms_, options_.blendMode, options_.blendPairs);
    trees_.reserve(patches_.size());
    for (const Patch& p : patches_) {
        trees_.push_back(BuildPatchOctree(p, threshold, options_.octree));
        bounds_.Extend(p.Box());
    }
    bvh_.clear();
    bvhOrder_.resize(patches_.size());
    for (size_t i = 0; i < patches_.size(); ++i) bvhOrder_[i] = static_cast<int>(i);
    if (!patches_.empty()) {
        bvh_.emplace_back();
        BuildBvh(0, 0, static_cast<int>(patches_.size()));
    }
}

// Fills node `index` over the entries [first, first + count) of bvhOrder_, splitting them
// at the median along the longest axis of their boxes' centres.
void ImplicitSurface::BuildBvh(int index, int first, int count) {
    Bounds3 box, centres;
    for (int i = first; i < first + count; ++i) {
        box.Extend(patches_[bvhOrder_[i]].Box());
        centres.Extend(patches_[bvhOrder_[i]].Box().Center());
    }
    bvh_[index].box = box;
    if (count <= kBvhLeafSize) {
        bvh_[index].first = first;
        bvh_[index].count = count;
        return;
    }
    Vec3 extent = centres.Extent();
    int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
    auto begin = bvhOrder_.begin() + first;
    std::nth_element(begin, begin + count / 2, begin + count, [&](int a, int b) {
        double ca = patches_[a].Box().Center()[axis], cb = patches_[b].Box().Center()[axis];
        return ca < cb || (ca == cb && a < b);
    });
    // Children are allocated as a consecutive pair so one index addresses both.
    int left = static_cast<int>(bvh_.size());
    bvh_.emplace_back();
    bvh_.emplace_back();
    bvh_[index].left = left;
    BuildBvh(left, first, count / 2);
    BuildBvh(left + 1, first + count / 2, count - count / 2);
}

std::shared_ptr<Primitive> ImplicitSurface::Create(ArgReader& args) {
    ImplicitOptions options;
    int maxDepth = options.octree.maxDepth;
    double dRatio = options.octree.dRatio, tolerance = options.octree.tolerance;
    KernelSpec defaultKernel = DefaultKernel();
    std::vector<ElementSpec> elements;
    std::map<std::string, int> index;
    std::vector<std::vector<std::string>> blends;
    while (!args.Accept("end")) {
        if (args.Accept("threshold")) {
            options.threshold = args.ReadNumber();
            if (!(options.threshold > 0)) args.Fail("implicit threshold must be > 0");
        } else if (args.Accept("tolerance")) {
            tolerance = args.ReadNumber();
            if (!(tolerance > 0)) args.Fail("implicit tolerance must be > 0");
        } else if (args.Accept("octree")) {
            maxDepth = args.ReadInt();
            if (maxDepth < 0 || maxDepth > 16) args.Fail("octree depth must be in [0, 16]");
            if (args.PeekNumber()) dRatio = args.ReadNumber();
        } else if (args.Accept("method")) {
            // Accept() rather than a name: method words such as `sphere` are keywords of the
            // scene language.
            const MethodEntry* chosen = nullptr;
            for (const MethodEntry& entry : MethodRegistry()) {
                if (args.Accept(entry.name)) {
                    chosen = &entry;
                    break;
                }
            }
            if (!chosen) args.Fail("expected a method after 'method': " + ImplicitMethodNames());
            options.method = chosen->method;
            if (options.method == ImplicitMethod::March && args.PeekNumber()) {
                options.marchStep = args.ReadNumber();
                if (!(options.marchStep > 0)) args.Fail("the march step must be > 0");
            }
        } else if (args.Accept("field")) {
            defaultKernel = ReadKernel(args);
        } else if (args.Accept("blend")) {
            std::vector<std::string> names{args.ReadName(), args.ReadName()};
            while (!PeekStatement(args)) names.push_back(args.ReadName());
            blends.push_back(std::move(names));
        } else {
            ElementSpec e;
            for (const char* kind : kSkeletonKinds) {
                if (args.Accept(kind)) {
                    e.kind = kind;
                    break;
                }
            }
            if (e.kind.empty()) {
                args.Fail("expected a skeleton (point, segment, polyline, circle, triangle, box, "
                          "cylinder), blend, field, threshold, tolerance, octree, method or end");
            }
            e.name = args.ReadName();
            if (index.count(e.name)) args.Fail("skeleton name '" + e.name + "' used twice");
            int count = SkeletonArity(e.kind);
            if (count < 0) {
                int points = args.ReadInt();
                if (points < 2) args.Fail("polyline '" + e.name + "' needs at least 2 points");
                // Each point is three numbers of the input, so a count beyond what any input
                // holds only overflows 3·points (Limits().polylinePoints, raised with
                // -L polylinePoints=N, never beyond what 3·points in an int allows).
                const long maxPoints = std::min<long>(Limits().polylinePoints, INT_MAX / 3);
                if (points > maxPoints)
                    args.Fail(StringPrintf("polyline '%s' has more than %ld points", e.name.c_str(),
                                           maxPoints));
                count = 3 * points;
            }
            for (int i = 0; i < count; ++i) e.numbers.push_back(args.ReadAnimatedNumber());
            e.weight.value = 1;
            e.kernel = defaultKernel;
            for (;;) {
                if (args.Accept("weight")) {
                    e.weight = args.ReadAnimatedNumber();
                } else if (args.Accept("field")) {
                    e.kernel = ReadKernel(args);
                } else {
                    break;
                }
            }
            index[e.name] = static_cast<int>(elements.size());
            elements.push_back(std::move(e));
        }
    }
    if (!blends.empty()) {
        options.blendMode = BlendMode::Explicit;
        for (const std::vector<std::string>& names : blends) {
            for (const std::string& n : names) {
                if (!index.count(n)) args.Fail("blend names unknown skeleton '" + n + "'");
            }
            for (size_t i = 0; i < names.size(); ++i) {
                for (size_t j = i + 1; j < names.size(); ++j) {
                    options.blendPairs.emplace_back(index[names[i]], index[names[j]]);
                }
            }
        }
    }
    if (!blends.empty() && options.method != ImplicitMethod::Patches) {
        args.Warn(StringPrintf("'blend' is ignored with 'method %s' (one field, everything "
                               "blends)",
                               ImplicitMethodName(options.method)));
    }
    OctreeSettings declared;
    declared.maxDepth = maxDepth;
    declared.tolerance = tolerance;
    declared.minWidth = tolerance;
    options.patchesDRatio = dRatio;
    options.octree = MethodSettings(options.method, declared, dRatio);

    std::vector<FieldTerm> terms(elements.size());
    bool animated = false, anyPositive = false;
    for (size_t i = 0; i < elements.size(); ++i) {
        std::string error = MakeTerm(elements[i], 0, terms[i]);
        if (!error.empty()) args.Fail(error);
        animated |= IsAnimated(elements[i]);
        anyPositive |= terms[i].weight > 0 || elements[i].weight.IsAnimated();
    }
    if (!anyPositive) {
        args.Warn("implicit object without a skeleton of positive weight, discarded");
        return nullptr;
    }
    if (const MethodEntry& entry = MethodEntryOf(options.method); entry.check) {
        std::string error = entry.check(terms);
        if (!error.empty()) args.Fail(error);
    }
    auto surface = std::make_shared<ImplicitSurface>(std::move(terms), std::move(options));
    if (animated) {
        surface->termsAt_ = [elements = std::move(elements)](double time) {
            std::vector<FieldTerm> out(elements.size());
            for (size_t i = 0; i < elements.size(); ++i) {
                std::string error = MakeTerm(elements[i], time, out[i]);
                if (!error.empty()) {
                    Report(Severity::Abort, {}, "implicit object at time %g: %s", time,
                           error.c_str());
                }
            }
            return out;
        };
    }
    return surface;
}

void ImplicitSurface::PrepareFrame(double frameTime) {
    if (!termsAt_) return;
    terms_ = termsAt_(frameTime);
    Build();
}

const IntersectionCounters& ImplicitSurface::Counters() const {
    static const IntersectionCounters counters("Implicit");
    return counters;
}

bool ImplicitSurface::Intersect(const Ray& ray, double tMin, double tMax,
                                PrimitiveHit& hit) const {
    const FieldCounters& field = FieldCounterIds();
    const CounterId ridders = RiddersIterationCounter();
    const uint64_t values = ThreadCount(field.values), gradients = ThreadCount(field.gradients),
                   bounds = ThreadCount(field.bounds), iterations = ThreadCount(ridders);
    const bool found = Search(ray, tMin, tMax, hit);
    Count(counters_.tests);
    if (found) Count(counters_.hits);
    Count(counters_.values, ThreadCount(field.values) - values);
    Count(counters_.gradients, ThreadCount(field.gradients) - gradients);
    Count(counters_.bounds, ThreadCount(field.bounds) - bounds);
    Count(counters_.riddersIterations, ThreadCount(ridders) - iterations);
    return found;
}

bool ImplicitSurface::Search(const Ray& ray, double tMin, double tMax, PrimitiveHit& hit) const {
    if (baseline_) {
        std::optional<double> t = baseline_->FirstRoot(ray, tMin, tMax);
        if (!t) return false;
        hit.t = *t;
        hit.part = -1;
        return true;
    }
    if (options_.method == ImplicitMethod::Kb89) {
        std::optional<double> t = trees_.front().FirstRoot(ray, tMin, tMax);
        if (!t) return false;
        hit.t = *t;
        hit.part = -1;
        return true;
    }
    // Front-to-back BVH walk over the patch boxes, each clipped to (tMin, best) so nodes
    // beyond the best hit so far are skipped.
    double best = tMax;
    bool found = false;
    int stack[64];
    int top = 0;
    if (!bvh_.empty()) stack[top++] = 0;
    while (top > 0) {
        const BvhNode& node = bvh_[stack[--top]];
        double t0 = tMin, t1 = best;
        if (!node.box.ClipRay(ray, t0, t1)) continue;
        if (node.count > 0) {
            for (int i = node.first; i < node.first + node.count; ++i) {
                int patch = bvhOrder_[i];
                std::optional<double> t =
                    PatchFirstRoot(patches_[patch], trees_[patch], ray, tMin, best);
                if (t) {
                    best = *t;
                    hit.part = patch;
                    found = true;
                }
            }
            continue;
        }
        // Visit the child whose box the ray enters first next (pushed last).
        int a = node.left, b = node.left + 1;
        double ta0 = tMin, ta1 = best, tb0 = tMin, tb1 = best;
        bool hitA = bvh_[a].box.ClipRay(ray, ta0, ta1), hitB = bvh_[b].box.ClipRay(ray, tb0, tb1);
        if (hitA && hitB && tb0 < ta0) std::swap(a, b);
        if (hitA && hitB) {
            stack[top++] = b;
            stack[top++] = a;
        } else if (hitA || hitB) {
            stack[top++] = hitA ? a : b;
        }
    }
    if (found) hit.t = best;
    return found;
}

SurfaceNormals ImplicitSurface::Normal(const Vec3& p, const PrimitiveHit& hit) const {
    bool usePatch = hit.part >= 0 && hit.part < static_cast<int>(patches_.size());
    const Field& field = usePatch ? patches_[hit.part].GetField() : whole_;
    Vec3 n = Normalize(-field.Gradient(p));
    if (LengthSquared(n) == 0) {
        // Zero gradient: point away from the dominant (or own) skeleton.
        int own = 0;
        if (!usePatch) {
            for (int i = 1; i < field.Size(); ++i) {
                if (field.TermValue(i, p) > field.TermValue(own, p)) own = i;
            }
        }
        Vec3 closest;
        SkeletonDistance(field.Terms()[own].skeleton, p, closest);
        n = Normalize(p - closest);
        if (LengthSquared(n) == 0) n = {0, 0, 1};
    }
    return {n, n, false};
}

}  // namespace rs
