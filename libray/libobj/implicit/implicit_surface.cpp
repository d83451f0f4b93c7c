#include "libobj/implicit/implicit_surface.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <climits>
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "libcommon/error.h"
#include "libcommon/large_buffer.h"
#include "libcommon/limits.h"
#include "libcommon/name_index.h"
#include "libcommon/stats.h"

namespace rs {

namespace {

// The numbers of an implicit block, indexed in reading order: a plain value each, and the
// expression of those that are animated (usually none).
class DeclaredNumbers {
  public:
    size_t Size() const { return values_.size(); }
    // Stores `v` at index Size().
    size_t Add(AnimatedValue v) {
        const size_t index = values_.size();
        values_.push_back(v.value);
        if (v.IsAnimated()) animated_.emplace_back(index, std::move(v.at));
        return index;
    }
    bool IsAnimated(size_t index) const { return Expression(index) != nullptr; }
    double At(size_t index, double time) const {
        const std::function<double(double)>* at = Expression(index);
        return at ? (*at)(time) : values_[index];
    }

  private:
    const std::function<double(double)>* Expression(size_t index) const {
        if (animated_.empty()) return nullptr;
        const auto it = std::lower_bound(
            animated_.begin(), animated_.end(), index,
            [](const std::pair<size_t, std::function<double(double)>>& a, size_t i) {
                return a.first < i;
            });
        return it != animated_.end() && it->first == index ? &it->second : nullptr;
    }

    std::vector<double, LargeBufferAllocator<double>> values_;
    std::vector<std::pair<size_t, std::function<double(double)>>> animated_;  // by index
};

struct KernelSpec {
    KernelKind kind = KernelKind::GascuelQuadratic;
    // Indices of the parameters in DeclaredNumbers: thickness, stiffness, radius; blob:
    // strength, radius (paramCount 2).
    size_t params[3] = {};
    int paramCount = 3;
};

enum class SkeletonKind : uint8_t { Point, Segment, Polyline, Circle, Triangle, Box, Cylinder };

struct SkeletonSyntax {
    SkeletonKind kind;
    const char* keyword;
    int arity;  // count of numbers; -1 for polyline, whose point count comes first
};

constexpr SkeletonSyntax kSkeletonSyntax[] = {
    {SkeletonKind::Point, "point", 3},       {SkeletonKind::Segment, "segment", 6},
    {SkeletonKind::Polyline, "polyline", -1}, {SkeletonKind::Circle, "circle", 7},
    {SkeletonKind::Triangle, "triangle", 9}, {SkeletonKind::Box, "box", 6},
    {SkeletonKind::Cylinder, "cylinder", 7}};

// One skeleton as declared; its numbers, weight and kernel parameters are indices in the
// block's DeclaredNumbers.
struct ElementSpec {
    SkeletonKind kind = SkeletonKind::Point;
    size_t firstNumber = 0, numberCount = 0;  // in syntax order
    size_t weight = 0;
    size_t kernel = 0;  // index in Declaration::kernels
};

// An implicit block's skeletons (names[i] names elements[i]) with the numbers and kernels
// they refer to.
struct Declaration {
    NameIndex names;
    DeclaredNumbers numbers;
    std::vector<KernelSpec> kernels;
    std::vector<ElementSpec, LargeBufferAllocator<ElementSpec>> elements;
};

bool IsAnimated(const Declaration& d, const ElementSpec& e) {
    const KernelSpec& k = d.kernels[e.kernel];
    for (size_t i = e.firstNumber; i < e.firstNumber + e.numberCount; ++i) {
        if (d.numbers.IsAnimated(i)) return true;
    }
    for (int i = 0; i < k.paramCount; ++i) {
        if (d.numbers.IsAnimated(k.params[i])) return true;
    }
    return d.numbers.IsAnimated(e.weight);
}

Kernel MakeKernel(const KernelSpec& k, const DeclaredNumbers& numbers, double time) {
    const double a = numbers.At(k.params[0], time), b = numbers.At(k.params[1], time);
    switch (k.kind) {
        case KernelKind::GascuelLinear:
            return Kernel::GascuelLinear(a, b, numbers.At(k.params[2], time));
        case KernelKind::GascuelQuadratic:
            return Kernel::GascuelQuadratic(a, b, numbers.At(k.params[2], time));
        default:
            return Kernel::Blob(a, b);
    }
}

// Builds the term of skeleton `element` at `time`; returns an error message instead when
// the skeleton or the kernel is invalid.
std::string MakeTerm(const Declaration& d, size_t element, double time, FieldTerm& term) {
    const ElementSpec& e = d.elements[element];
    const std::string& name = d.names.Name(element);
    auto n = [&](size_t i) { return d.numbers.At(e.firstNumber + i, time); };
    auto vec = [&n](size_t i) { return Vec3{n(i), n(i + 1), n(i + 2)}; };
    const char* who = name.c_str();
    switch (e.kind) {
        case SkeletonKind::Point:
            term.skeleton = PointSkeleton{vec(0)};
            break;
        case SkeletonKind::Segment:
            term.skeleton = SegmentSkeleton{vec(0), vec(3)};
            break;
        case SkeletonKind::Polyline: {
            PolylineSkeleton p;
            p.points.reserve(e.numberCount / 3);
            for (size_t i = 0; i + 2 < e.numberCount; i += 3) p.points.push_back(vec(i));
            term.skeleton = std::move(p);
            break;
        }
        case SkeletonKind::Circle: {
            const double radius = n(0);
            const Vec3 normal = vec(4);
            if (!(radius > 0) || LengthSquared(normal) == 0) {
                return StringPrintf(
                    "skeleton '%s': circle needs a radius > 0 and a non-zero normal", who);
            }
            term.skeleton = CircleSkeleton{vec(1), Normalize(normal), radius};
            break;
        }
        case SkeletonKind::Triangle:
            term.skeleton = TriangleSkeleton{vec(0), vec(3), vec(6)};
            break;
        case SkeletonKind::Box: {
            const Vec3 a = vec(0), b = vec(3);
            term.skeleton = BoxSkeleton{Min(a, b), Max(a, b)};
            break;
        }
        case SkeletonKind::Cylinder: {
            const double radius = n(0);
            if (!(radius >= 0)) {
                return StringPrintf("skeleton '%s': cylinder radius must be >= 0", who);
            }
            term.skeleton = CylinderSkeleton{vec(1), vec(4), radius};
            break;
        }
    }
    term.name = name;
    term.weight = d.numbers.At(e.weight, time);
    term.kernel = MakeKernel(d.kernels[e.kernel], d.numbers, time);
    if (!std::isfinite(term.weight)) {
        return StringPrintf("skeleton '%s': weight is not finite", who);
    }
    KernelStatus status = term.kernel.Validate(name);
    return status.ok ? std::string() : status.message;
}

// Reads the kernel of a `field` statement, storing its parameters in `numbers`.
KernelSpec ReadKernel(ArgReader& args, DeclaredNumbers& numbers) {
    KernelSpec k;
    if (args.Accept("linear")) {
        k.kind = KernelKind::GascuelLinear;
    } else if (args.Accept("quadratic")) {
        k.kind = KernelKind::GascuelQuadratic;
    } else if (args.Accept("blob")) {
        k.kind = KernelKind::Blob;
        k.paramCount = 2;
    } else {
        args.Fail("expected linear, quadratic or blob after 'field'");
    }
    for (int i = 0; i < k.paramCount; ++i) k.params[i] = numbers.Add(args.ReadAnimatedNumber());
    return k;
}

}  // namespace

bool ImplicitSurface::IsBlockWord(const std::string& word) {
    static const char* const kStatements[] = {"threshold", "tolerance", "octree",
                                              "method",    "field",     "blend",
                                              "contact",   "propagation", "end"};
    for (const char* w : kStatements)
        if (word == w) return true;
    for (const SkeletonSyntax& s : kSkeletonSyntax)
        if (word == s.keyword) return true;
    return false;
}

namespace {

// True when the next token starts a statement of the block (or ends it), so open-ended
// name lists stop there.
bool PeekStatement(ArgReader& args) {
    for (const char* word :
         {"end", "threshold", "tolerance", "octree", "method", "field", "blend", "contact",
          "propagation"}) {
        if (args.Peek(word)) return true;
    }
    for (const SkeletonSyntax& s : kSkeletonSyntax) {
        if (args.Peek(s.keyword)) return true;
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
    s.autoTolerance = declared.autoTolerance;
    s.footprintFraction = declared.footprintFraction;
    s.autoToleranceCap = declared.autoToleranceCap;
    return s;
}

constexpr const char kCounterPrefix[] = "Implicit ";
constexpr const char kOctreeCounterPrefix[] = "Implicit octree ";

bool StartsWith(const std::string& s, const char* prefix) {
    return s.compare(0, std::char_traits<char>::length(prefix), prefix) == 0;
}

}  // namespace

ImplicitSurface::ImplicitSurface(std::vector<FieldTerm> terms, ImplicitOptions options)
    : options_(std::move(options)), whole_(std::move(terms)) {
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
        const ImplicitMethod method =
            *overrides.method == ImplicitMethod::Auto
                ? ResolveAutoMethod(Terms(), options_.blendMode == BlendMode::Explicit ||
                                                !options_.contacts.empty())
                : *overrides.method;
        const MethodEntry& entry = MethodEntryOf(method);
        if (entry.check) {
            std::string error = entry.check(Terms());
            if (!error.empty()) return label_ + ": " + error;
        }
        options_.method = method;
        options_.octree = MethodSettings(options_.method, options_.octree, options_.patchesDRatio);
    }
    if (overrides.maxDepth) {
        options_.octree.maxDepth = *overrides.maxDepth;
        options_.autoDepth = false;  // an explicit depth, as `octree N` in the scene
    }
    if (overrides.dRatio) {
        options_.patchesDRatio = *overrides.dRatio;
        if (options_.method != ImplicitMethod::Kb89) options_.octree.dRatio = *overrides.dRatio;
    }
    if (overrides.tolerance) {
        options_.octree.tolerance = *overrides.tolerance;
        options_.octree.minWidth = *overrides.tolerance;
        options_.octree.autoTolerance = false;  // fixed, as `tolerance EPS` in the scene
    }
    if (overrides.step) options_.marchStep = *overrides.step;
    for (const auto& [name, on] : overrides.switches) *OctreeSwitch(options_.octree, name) = on;
    Build();
    return {};
}

std::string ImplicitSurface::PatchName(const PrimitiveHit& hit) const {
    if (hit.part < 0 || hit.part >= static_cast<int>(termOfPart_.size())) return {};
    return Terms()[termOfPart_[hit.part]].name;
}

namespace {

// The module's counters a build advances ("Implicit octree ..." and the field, gradient
// and bound counters, i.e. every "Implicit ..." counter but the per-object ones), with the
// name of the per-object counter each is attributed to ("octree ..." or "preprocessing
// ..."). Found by name once, on the first object's construction (parsing, not rendering).
const std::vector<std::pair<CounterId, std::string>>& BuildCounterSources() {
    static const std::vector<std::pair<CounterId, std::string>> sources = [] {
        RiddersIterationCounter();  // registers the octree counters
        FieldCounterIds();
        std::vector<std::pair<CounterId, std::string>> out;
        const std::vector<CounterValue> all = StatsSnapshot();
        for (size_t i = 0; i < all.size(); ++i) {
            const std::string& name = all[i].name;
            if (!StartsWith(name, kCounterPrefix) || StartsWith(name, "Implicit object")) {
                continue;
            }
            std::string what = name.substr(std::char_traits<char>::length(kCounterPrefix));
            if (!StartsWith(name, kOctreeCounterPrefix)) what = "preprocessing " + what;
            out.emplace_back(static_cast<CounterId>(i), what);
        }
        return out;
    }();
    return sources;
}

// The radius of the own term's surface alone, {r : w·f(r) = T} (f decreases on [0, R)),
// or R when the term alone stays below T (its surface then exists only blended with others,
// hence at least as thick as theirs).
double LoneThickness(const FieldTerm& term, double threshold) {
    const double radius = term.kernel.Radius();
    auto above = [&](double r) { return term.weight * term.kernel.Value(r) > threshold; };
    if (!above(0)) return radius;
    double lo = 0, hi = radius;  // above(lo), !above(hi): f(R) = 0 < T / w
    for (int i = 0; i < 60 && hi - lo > 1e-3 * radius; ++i) {
        const double mid = 0.5 * (lo + hi);
        (above(mid) ? lo : hi) = mid;
    }
    return lo > 0 ? lo : hi;
}

}  // namespace

// Octree depth `auto`: the "deep enough" depth of heuristics 3 and 3bis (the depth where
// cells the surface crosses become leaves) is the smallest at which the leaf edge is at
// most the own skeleton's lone thickness τ (LoneThickness: the radius of its surface
// alone), i.e. a leaf never spans more than half the thinnest cross-section of the patch's
// own part, so the leaf's L and G describe one piece of surface rather than a whole
// feature. minDepth = ceil(log2(longest patch-box edge / τ)), clamped to [2, 8] (depth 8
// already means 16 million cells in a full tree, and the memory budget still applies);
// the maximum depth is at least minDepth + 3. A lone point with the blob kernel of the
// benchmark (R = 1, T = 0.6: τ = 0.47, edge 2) gets 3, Gascuel's setting.
int ImplicitSurface::AutoMinDepth(const Patch& patch, double threshold) {
    const double tau = LoneThickness(patch.GetField().Terms()[patch.Own()], threshold);
    const Vec3 extent = patch.Box().Extent();
    const double edge = std::max({extent.x, extent.y, extent.z});
    if (!(tau > 0) || !(edge > tau)) return 2;
    return std::clamp(static_cast<int>(std::ceil(std::log2(edge / tau))), 2, 8);
}

namespace {

// The evaluations this thread made inside lazy builds, so Intersect can leave them out of
// the ray's own counts.
struct BuildTally {
    uint64_t values = 0, gradients = 0, bounds = 0, riddersIterations = 0;
};
thread_local BuildTally buildTally;

}  // namespace

uint64_t ImplicitBuildEvaluations() {
    return buildTally.values + buildTally.gradients + buildTally.bounds;
}

// Builds the patches and BVH (the octrees are built lazily, see Tree) and counts the time
// under this object's label.
void ImplicitSurface::Build() {
    const auto start = std::chrono::steady_clock::now();
    BuildStructures();
    const auto micros = std::chrono::duration_cast<std::chrono::microseconds>(
        std::chrono::steady_clock::now() - start);
    Count(counters_.buildMicroseconds, static_cast<uint64_t>(micros.count()));
}

OctreeSettings ImplicitSurface::PatchSettings(const Patch& patch) const {
    OctreeSettings settings = options_.octree;
    if (options_.autoDepth) {
        settings.minDepth = AutoMinDepth(patch, options_.threshold);
        settings.maxDepth = std::min(16, std::max(settings.maxDepth, settings.minDepth + 3));
    }
    return settings;
}

const LGOctree& ImplicitSurface::Tree(int i) const {
    LazyTree& lazy = trees_[i];
    std::call_once(lazy.once, [this, i] { BuildTree(i); });
    return *lazy.tree;
}

// Builds tree i and attributes the work to this object by differences of the building
// thread's own counters (other threads may be counting at the same time).
void ImplicitSurface::BuildTree(int i) const {
    const std::vector<std::pair<CounterId, std::string>>& sources = BuildCounterSources();
    std::vector<uint64_t> before(sources.size());
    for (size_t k = 0; k < sources.size(); ++k) before[k] = ThreadCount(sources[k].first);
    const auto start = std::chrono::steady_clock::now();
    if (options_.method == ImplicitMethod::Kb89) {
        trees_[i].tree =
            std::make_unique<LGOctree>(whole_, options_.threshold, bounds_, options_.octree);
    } else {
        trees_[i].tree = std::make_unique<LGOctree>(
            BuildPatchOctree(patches_[i], options_.threshold, PatchSettings(patches_[i])));
    }
    const auto micros = std::chrono::duration_cast<std::chrono::microseconds>(
        std::chrono::steady_clock::now() - start);
    const LGOctree& tree = *trees_[i].tree;
    Count(counters_.buildMicroseconds, static_cast<uint64_t>(micros.count()));
    Count(counters_.cells, static_cast<uint64_t>(tree.InternalCount() + tree.LeafCount()));
    Count(counters_.memoryBytes, tree.MemoryBytes());
    const FieldCounters& field = FieldCounterIds();
    for (size_t k = 0; k < sources.size(); ++k) {
        const CounterId source = sources[k].first;
        const uint64_t delta = ThreadCount(source) - before[k];
        if (delta == 0) continue;
        if (source == field.values) buildTally.values += delta;
        if (source == field.gradients) buildTally.gradients += delta;
        if (source == field.bounds) buildTally.bounds += delta;
        if (source == RiddersIterationCounter()) buildTally.riddersIterations += delta;
        CounterId target = buildCounterIds_[k].load(std::memory_order_relaxed);
        if (target < 0) {
            // RegisterCounter is idempotent, so racing threads store the same id.
            target = RegisterCounter(label_ + ": " + sources[k].second);
            buildCounterIds_[k].store(target, std::memory_order_relaxed);
        }
        Count(target, delta);
    }
}

void ImplicitSurface::BuildStructures() {
    patches_.clear();
    contacts_.clear();
    bounds_ = Bounds3();
    if (!buildCounterIds_) {
        const size_t count = BuildCounterSources().size();
        buildCounterIds_ = std::make_unique<std::atomic<CounterId>[]>(count);
        for (size_t k = 0; k < count; ++k) buildCounterIds_[k].store(-1);
    }
    trees_.reset();
    baseline_.reset();
    const std::vector<FieldTerm>& terms = Terms();
    partOfTerm_.assign(terms.size(), -1);
    termOfPart_.clear();
    for (size_t i = 0; i < terms.size(); ++i) {
        if (!(terms[i].weight > 0)) continue;
        partOfTerm_[i] = static_cast<int>(termOfPart_.size());
        termOfPart_.push_back(static_cast<int>(i));
    }
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
        for (const FieldTerm& t : terms) {
            if (t.weight > 0) bounds_.Extend(TermSupportBounds(t));
        }
        trees_ = std::make_unique<LazyTree[]>(1);
        return;
    }
    std::vector<std::pair<int, int>> separate;
    for (const ContactPair& c : options_.contacts) separate.emplace_back(c.a, c.b);
    patches_ = BuildPatches(whole_, options_.blendMode, options_.blendPairs, separate);
    trees_ = std::make_unique<LazyTree[]>(patches_.size());
    for (const Patch& p : patches_) bounds_.Extend(p.Box());
    if (!options_.contacts.empty()) {
        // Contacts measure and deform with every patch's undeformed tree: build them all
        // now, then hand them to the lazy holders as already built.
        std::vector<LGOctree> trees;
        trees.reserve(patches_.size());
        for (const Patch& p : patches_) {
            trees.push_back(BuildPatchOctree(p, options_.threshold, PatchSettings(p)));
        }
        contacts_ = ApplyContacts(terms, options_.contacts, options_.propagations,
                                  options_.threshold, options_.octree, patches_, trees);
        for (size_t i = 0; i < trees.size(); ++i) {
            LazyTree& lazy = trees_[i];
            std::call_once(lazy.once,
                           [&] { lazy.tree = std::make_unique<LGOctree>(std::move(trees[i])); });
            Count(counters_.cells,
                  static_cast<uint64_t>(lazy.tree->InternalCount() + lazy.tree->LeafCount()));
            Count(counters_.memoryBytes, lazy.tree->MemoryBytes());
        }
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

namespace {

// An implicit block as read: its options (the method possibly still Auto) and skeletons.
struct ImplicitBlock {
    ImplicitOptions options;
    Declaration declaration;
    bool blendsOrContacts = false;
};

// Reads the block syntax of ImplicitSurface::Create, failing as it documents.
ImplicitBlock ReadBlock(ArgReader& args) {
    ImplicitBlock block;
    ImplicitOptions& options = block.options;
    options.autoDepth = true;
    options.method = ImplicitMethod::Auto;  // resolved once the terms are known
    bool autoTolerance = true;
    int maxDepth = options.octree.maxDepth;
    double dRatio = options.octree.dRatio, tolerance = options.octree.tolerance;
    DeclaredNumbers& numbers = block.declaration.numbers;
    std::vector<KernelSpec>& kernels = block.declaration.kernels;
    auto& elements = block.declaration.elements;
    const size_t one = numbers.Add({1, {}});
    // `field quadratic 1 1 2` (m = k(R − e) = 1) until a `field` statement.
    kernels.push_back({KernelKind::GascuelQuadratic, {one, one, numbers.Add({2, {}})}, 3});
    size_t defaultKernel = 0;
    NameIndex& skeletons = block.declaration.names;
    std::vector<std::vector<std::string>> blends;
    std::vector<std::pair<std::string, std::string>> contacts;
    struct PropagationSpec {
        std::string name;
        double width = 0, height = 0.5;
    };
    std::vector<PropagationSpec> propagations;
    while (!args.Accept("end")) {
        if (args.Accept("threshold")) {
            options.threshold = args.ReadNumber();
            if (!(options.threshold > 0)) args.Fail("implicit threshold must be > 0");
        } else if (args.Accept("tolerance")) {
            autoTolerance = args.Accept("auto");
            if (!autoTolerance) {
                tolerance = args.ReadNumber();
                if (!(tolerance > 0)) args.Fail("implicit tolerance must be > 0");
            }
        } else if (args.Accept("octree")) {
            options.autoDepth = args.Accept("auto");
            if (!options.autoDepth) {
                maxDepth = args.ReadInt();
                if (maxDepth < 0 || maxDepth > 16) args.Fail("octree depth must be in [0, 16]");
            }
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
            kernels.push_back(ReadKernel(args, numbers));
            defaultKernel = kernels.size() - 1;
        } else if (args.Accept("blend")) {
            std::vector<std::string> names{args.ReadName(), args.ReadName()};
            while (!PeekStatement(args)) names.push_back(args.ReadName());
            blends.push_back(std::move(names));
        } else if (args.Accept("contact")) {
            std::string a = args.ReadName();
            contacts.emplace_back(a, args.ReadName());
        } else if (args.Accept("propagation")) {
            PropagationSpec p;
            p.name = args.ReadName();
            p.width = args.ReadNumber();
            if (!(p.width >= 0)) args.Fail("propagation width must be >= 0");
            if (args.PeekNumber()) {
                p.height = args.ReadNumber();
                if (!(p.height >= 0 && p.height <= 1)) {
                    args.Fail("propagation height must be in [0, 1]");
                }
            }
            propagations.push_back(p);
        } else {
            const SkeletonSyntax* syntax = nullptr;
            for (const SkeletonSyntax& s : kSkeletonSyntax) {
                if (args.Accept(s.keyword)) {
                    syntax = &s;
                    break;
                }
            }
            if (!syntax) {
                args.Fail("expected a skeleton (point, segment, polyline, circle, triangle, box, "
                          "cylinder), blend, contact, propagation, field, threshold, tolerance, "
                          "octree, method or end");
            }
            ElementSpec e;
            e.kind = syntax->kind;
            if (const std::string name = args.ReadName(); !skeletons.Insert(name)) {
                args.Fail("skeleton name '" + name + "' used twice");
            }
            const std::string& name = skeletons.Name(elements.size());
            int count = syntax->arity;
            if (count < 0) {
                int points = args.ReadInt();
                if (points < 2) args.Fail("polyline '" + name + "' needs at least 2 points");
                // Each point is three numbers of the input, so a count beyond what any input
                // holds only overflows 3·points (Limits().polylinePoints, raised with
                // -L polylinePoints=N, never beyond what 3·points in an int allows).
                const long maxPoints = std::min<long>(Limits().polylinePoints, INT_MAX / 3);
                if (points > maxPoints)
                    args.Fail(StringPrintf("polyline '%s' has more than %ld points", name.c_str(),
                                           maxPoints));
                count = 3 * points;
            }
            e.firstNumber = numbers.Size();
            e.numberCount = static_cast<size_t>(count);
            for (int i = 0; i < count; ++i) numbers.Add(args.ReadAnimatedNumber());
            e.weight = one;
            e.kernel = defaultKernel;
            for (;;) {
                if (args.Accept("weight")) {
                    e.weight = numbers.Add(args.ReadAnimatedNumber());
                } else if (args.Accept("field")) {
                    kernels.push_back(ReadKernel(args, numbers));
                    e.kernel = kernels.size() - 1;
                } else {
                    break;
                }
            }
            elements.push_back(std::move(e));
        }
    }
    if (!blends.empty()) {
        options.blendMode = BlendMode::Explicit;
        for (const std::vector<std::string>& names : blends) {
            std::vector<int> listed;
            for (const std::string& n : names) {
                const long i = skeletons.Find(n);
                if (i < 0) args.Fail("blend names unknown skeleton '" + n + "'");
                listed.push_back(static_cast<int>(i));
            }
            for (size_t i = 0; i < listed.size(); ++i) {
                for (size_t j = i + 1; j < listed.size(); ++j) {
                    options.blendPairs.emplace_back(listed[i], listed[j]);
                }
            }
        }
    }
    if (!blends.empty() && options.method != ImplicitMethod::Patches &&
        options.method != ImplicitMethod::Auto) {
        args.Warn(StringPrintf("'blend' is ignored with 'method %s' (one field, everything "
                               "blends)",
                               ImplicitMethodName(options.method)));
    }
    for (const auto& [a, b] : contacts) {
        for (const std::string& n : {a, b}) {
            if (skeletons.Find(n) < 0) args.Fail("contact names unknown skeleton '" + n + "'");
        }
        if (a == b) args.Fail("contact needs two different skeletons, not '" + a + "' twice");
        const int ia = static_cast<int>(skeletons.Find(a));
        const int ib = static_cast<int>(skeletons.Find(b));
        for (auto [x, y] : options.blendPairs) {
            if ((x == ia && y == ib) || (x == ib && y == ia)) {
                args.Fail("skeletons '" + a + "' and '" + b + "' both blend and are in contact");
            }
        }
        options.contacts.push_back({ia, ib});
    }
    for (const PropagationSpec& p : propagations) {
        const int term = static_cast<int>(skeletons.Find(p.name));
        if (term < 0) args.Fail("propagation names unknown skeleton '" + p.name + "'");
        bool inContact = std::any_of(options.contacts.begin(), options.contacts.end(),
                                     [term](const ContactPair& c) {
                                         return c.a == term || c.b == term;
                                     });
        if (!inContact) args.Warn("propagation of '" + p.name + "', which is in no contact");
        options.propagations.push_back({term, p.width, p.height});
    }
    if (!contacts.empty() && options.method != ImplicitMethod::Patches &&
        options.method != ImplicitMethod::Auto) {
        args.Warn(StringPrintf("'contact' is ignored with 'method %s' (one field, everything "
                               "blends)",
                               ImplicitMethodName(options.method)));
    }
    OctreeSettings declared;
    declared.maxDepth = maxDepth;
    declared.tolerance = tolerance;
    declared.minWidth = tolerance;
    declared.autoTolerance = autoTolerance;
    options.patchesDRatio = dRatio;
    options.octree = MethodSettings(options.method, declared, dRatio);
    block.blendsOrContacts = !blends.empty() || !contacts.empty();
    return block;
}

// Builds the terms of every skeleton at `time` into `terms` (empty); returns the first
// skeleton's error instead (MakeTerm), or empty.
std::string MakeTerms(const Declaration& d, double time, std::vector<FieldTerm>& terms) {
    terms.reserve(d.elements.size());
    AdviseHugePages(terms.data(), terms.capacity() * sizeof(FieldTerm));
    for (size_t i = 0; i < d.elements.size(); ++i) {
        std::string error = MakeTerm(d, i, time, terms.emplace_back());
        if (!error.empty()) return error;
    }
    return {};
}

}  // namespace

std::shared_ptr<Primitive> ImplicitSurface::Create(ArgReader& args) {
    ImplicitOptions options;
    std::vector<FieldTerm> terms;
    std::function<std::vector<FieldTerm>(double)> termsAt;
    bool blendsOrContacts = false;
    {
        ImplicitBlock block = ReadBlock(args);
        const Declaration& declaration = block.declaration;
        if (std::string error = MakeTerms(declaration, 0, terms); !error.empty()) {
            args.Fail(error);
        }
        bool animated = false, anyPositive = false;
        for (size_t i = 0; i < terms.size(); ++i) {
            const ElementSpec& e = declaration.elements[i];
            animated |= IsAnimated(declaration, e);
            anyPositive |= terms[i].weight > 0 || declaration.numbers.IsAnimated(e.weight);
        }
        if (!anyPositive) {
            args.Warn("implicit object without a skeleton of positive weight, discarded");
            return nullptr;
        }
        if (animated) {
            termsAt = [declaration = std::move(block.declaration)](double time) {
                std::vector<FieldTerm> out;
                if (std::string error = MakeTerms(declaration, time, out); !error.empty()) {
                    Report(Severity::Abort, {}, "implicit object at time %g: %s", time,
                           error.c_str());
                }
                return out;
            };
        }
        options = std::move(block.options);
        blendsOrContacts = block.blendsOrContacts;
    }  // a static block's declaration is released before the build
    if (options.method == ImplicitMethod::Auto) {
        options.method = ResolveAutoMethod(terms, blendsOrContacts);
    }
    if (const MethodEntry& entry = MethodEntryOf(options.method); entry.check) {
        std::string error = entry.check(terms);
        if (!error.empty()) args.Fail(error);
    }
    auto surface = std::make_shared<ImplicitSurface>(std::move(terms), std::move(options));
    surface->termsAt_ = std::move(termsAt);
    return surface;
}

void ImplicitSurface::PrepareFrame(double frameTime) {
    if (!termsAt_) return;
    whole_ = Field(termsAt_(frameTime));
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
    const BuildTally built = buildTally;
    const uint64_t values = ThreadCount(field.values), gradients = ThreadCount(field.gradients),
                   bounds = ThreadCount(field.bounds), iterations = ThreadCount(ridders);
    const bool found = Search(ray, tMin, tMax, hit);
    Count(counters_.tests);
    if (found) Count(counters_.hits);
    // Less whatever lazy tree builds (BuildTree) counted during this call.
    Count(counters_.values,
          ThreadCount(field.values) - values - (buildTally.values - built.values));
    Count(counters_.gradients,
          ThreadCount(field.gradients) - gradients - (buildTally.gradients - built.gradients));
    Count(counters_.bounds,
          ThreadCount(field.bounds) - bounds - (buildTally.bounds - built.bounds));
    Count(counters_.riddersIterations,
          ThreadCount(ridders) - iterations -
              (buildTally.riddersIterations - built.riddersIterations));
    return found;
}

bool ImplicitSurface::Search(const Ray& ray, double tMin, double tMax, PrimitiveHit& hit) const {
    if (baseline_) {
        std::optional<double> t = baseline_->FirstRoot(ray, tMin, tMax);
        if (!t) return false;
        hit.t = *t;
        const int term = baseline_->PredominantTerm(ray.At(*t));
        hit.part = term >= 0 ? partOfTerm_[term] : -1;
        return true;
    }
    if (options_.method == ImplicitMethod::Kb89) {
        std::optional<double> t = Tree(0).FirstRoot(ray, tMin, tMax);
        if (!t) return false;
        hit.t = *t;
        hit.part = -1;
        return true;
    }
    // Front-to-back BVH walk over the patch boxes, each clipped to (tMin, best) so nodes
    // beyond the best hit so far are skipped. A node is clipped once, when its parent pushes
    // it, and stacked with its entry parameter `near`: its clip to (tMin, best) with the
    // smaller best at its turn succeeds exactly when near <= best (near does not depend on
    // the far end, and the slab exits already passed near).
    double best = tMax;
    bool found = false;
    struct Entry {
        int node;
        double near;
    };
    Entry stack[64];
    int top = 0;
    if (!bvh_.empty()) {
        double t0 = tMin, t1 = best;
        if (bvh_[0].box.ClipRay(ray, t0, t1)) stack[top++] = {0, t0};
    }
    while (top > 0) {
        const Entry entry = stack[--top];
        if (entry.near > best) continue;
        const BvhNode& node = bvh_[entry.node];
        if (node.count > 0) {
            for (int i = node.first; i < node.first + node.count; ++i) {
                int patch = bvhOrder_[i];
                // A ray missing the own term's support meets no acceptable root: skip the
                // patch before its tree is built (the result is the same).
                if (!patches_[patch].MayHoldRoot(ray, tMin, best)) continue;
                std::optional<double> t =
                    PatchFirstRoot(patches_[patch], Tree(patch), ray, tMin, best);
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
        if (hitA && hitB && tb0 < ta0) {
            std::swap(a, b);
            std::swap(ta0, tb0);
        }
        if (hitA && hitB) {
            stack[top++] = {b, tb0};
            stack[top++] = {a, ta0};
        } else if (hitA) {
            stack[top++] = {a, ta0};
        } else if (hitB) {
            stack[top++] = {b, tb0};
        }
    }
    if (found) hit.t = best;
    return found;
}

SurfaceNormals ImplicitSurface::Normal(const Vec3& p, const PrimitiveHit& hit) const {
    bool usePatch = hit.part >= 0 && hit.part < static_cast<int>(patches_.size());
    const Field& field = usePatch ? patches_[hit.part].GetField() : whole_;
    Vec3 n = Normalize(-(baseline_ && !usePatch ? baseline_->Gradient(whole_, p)
                                                : field.Gradient(p)));
    if (LengthSquared(n) == 0) {
        // Zero gradient: point away from the dominant (or own) skeleton.
        int own = usePatch ? patches_[hit.part].Own() : 0;
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
