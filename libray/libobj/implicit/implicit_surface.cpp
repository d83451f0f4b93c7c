#include "libobj/implicit/implicit_surface.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "libcommon/error.h"
#include "libobj/implicit/implicit_block.h"
#include "libobj/implicit/implicit_syntax.h"
#include "libcommon/stats.h"

namespace rs {

bool ImplicitSurface::IsBlockWord(const std::string& word) {
    return IsImplicitStatementWord(word);
}

OctreeSettings MethodOctreeSettings(ImplicitMethod method, const OctreeSettings& declared,
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

namespace {

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
        options_.octree = MethodOctreeSettings(options_.method, options_.octree, options_.patchesDRatio);
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

std::shared_ptr<Primitive> ImplicitSurface::Create(ArgReader& args) {
    BuiltImplicitBlock block = BuildImplicitBlock(ReadImplicitBlock(args), args);
    if (block.terms.empty()) return nullptr;  // discarded (BuildImplicitBlock warned)
    auto surface =
        std::make_shared<ImplicitSurface>(std::move(block.terms), std::move(block.options));
    surface->termsAt_ = std::move(block.termsAt);
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
