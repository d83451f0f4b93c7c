#include "libobj/implicit/patches_method.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rs {

namespace {

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
int PatchesMethod::AutoMinDepth(const Patch& patch, double threshold) {
    const double tau = LoneThickness(patch.GetField().Terms()[patch.Own()], threshold);
    const Vec3 extent = patch.Box().Extent();
    const double edge = std::max({extent.x, extent.y, extent.z});
    if (!(tau > 0) || !(edge > tau)) return 2;
    return std::clamp(static_cast<int>(std::ceil(std::log2(edge / tau))), 2, 8);
}

PatchesMethod::PatchesMethod(const Field& whole, const ImplicitOptions& options,
                             const ImplicitObjectStats& stats, std::size_t gridMinPatches)
    : threshold_(options.threshold),
      settings_(options.search, options.octree),
      autoDepth_(options.autoDepth),
      stats_(stats),
      whole_(whole) {
    const std::vector<FieldTerm>& terms = whole.Terms();
    const std::size_t positive = static_cast<std::size_t>(std::count_if(
        terms.begin(), terms.end(), [](const FieldTerm& t) { return t.weight > 0; }));
    if (options.blendMode == BlendMode::Automatic && options.contacts.empty() &&
        !options.autoContacts && positive > kPerCellMinPatches) {
        // Per-cell trees and automatic neighbours: the neighbour lists wait for FullPatch.
        neighbours_ = std::make_unique<AutomaticNeighbours>(whole);
        patches_.reserve(positive);
        for (int i = 0; i < static_cast<int>(terms.size()); ++i) {
            if (terms[i].weight > 0) patches_.emplace_back(whole, std::vector<int>{i});
        }
        lazyPatches_ = std::make_unique<LazyPatch[]>(positive);
    } else {
        patches_ = BuildPatches(whole, options.blendMode, options.blendPairs,
                                SeparatePairs(options.contacts));
    }
    patchOfTerm_.assign(whole.Terms().size(), -1);
    for (size_t i = 0; i < patches_.size(); ++i) {
        patchOfTerm_[patches_[i].Own()] = static_cast<int>(i);
    }
    trees_ = std::make_unique<LazyOctree[]>(patches_.size());
    for (const Patch& p : patches_) bounds_.Extend(p.Box());
    // Declared pairs first; `contact auto` adds the other interpenetrating pairs that do
    // not blend (declared ones never blend either, so none is found twice).
    std::vector<ContactPair> contacts = options.contacts;
    if (options.autoContacts) {
        for (const ContactPair& c :
             UndeclaredContacts(AutomaticContacts(patches_, threshold_), contacts)) {
            contacts.push_back(c);
            stats_.CountAutomaticContact();
        }
    }
    if (!contacts.empty()) {
        // Contacts measure and deform with every patch's undeformed tree: build them all
        // now, then hand them to the lazy holders as already built.
        std::vector<LGOctree> trees;
        trees.reserve(patches_.size());
        for (const Patch& p : patches_) {
            trees.push_back(BuildPatchOctree(p, threshold_, PatchSettings(p)));
        }
        contacts_ = ApplyContacts(whole.Terms(), contacts, options.propagations,
                                  threshold_, settings_, patches_, trees);
        for (size_t i = 0; i < trees.size(); ++i) {
            trees_[i].Set(std::move(trees[i]));
            stats_.CountTree(*trees_[i].Built());
        }
    }
    if (contacts.empty() && patches_.size() > kPerCellMinPatches) {
        const std::size_t perTree = std::min(settings_.memoryBudget,
                                             std::numeric_limits<std::size_t>::max() /
                                                 kCellBudgetTrees);  // no overflow
        cellStore_ = std::make_unique<LazyCellStore>(kCellBudgetTrees * perTree, &stats_);
        // ClipToOwnRegion's ball (the lazily made patches get theirs in FullPatch).
        if (!lazyPatches_) {
            for (Patch& patch : patches_) patch.LimitToSurface(threshold_);
        }
    }
    supportBalls_.reserve(patches_.size());
    for (const Patch& patch : patches_) {
        supportBalls_.push_back(
            patch.StaticSupportBall().value_or(Patch::SupportBall{Vec3{}, kNoBall}));
    }
    std::vector<Bounds3> patchBoxes;
    patchBoxes.reserve(patches_.size());
    for (const Patch& patch : patches_) patchBoxes.push_back(patch.Box());
    if (patches_.size() > gridMinPatches) {
        grid_ = std::make_unique<const PatchGrid>(patchBoxes);
    } else {
        bvh_.Build(patchBoxes);
    }
}

OctreeSettings PatchesMethod::PatchSettings(const Patch& patch) const {
    OctreeSettings settings = settings_;
    if (autoDepth_) {
        settings.minDepth = AutoMinDepth(patch, threshold_);
        settings.maxDepth = std::min(16, std::max(settings.maxDepth, settings.minDepth + 3));
    }
    return settings;
}

const Patch& PatchesMethod::FullPatch(int i) const {
    if (!lazyPatches_) return patches_[i];
    LazyPatch& lazy = lazyPatches_[i];
    std::call_once(lazy.once, [&] {
        const uint64_t cpuStart = ThreadCpuMicroseconds();
        auto patch = std::make_unique<Patch>(whole_, neighbours_->Members(patches_[i].Own()));
        patch->LimitToSurface(threshold_);  // for ClipToOwnRegion
        lazy.patch = std::move(patch);
        stats_.CountPreprocessing(ThreadCpuMicroseconds() - cpuStart);
    });
    return *lazy.patch;
}

const LGOctree& PatchesMethod::Tree(int i) const {
    return trees_[i].Get([this, i] {
        const Patch& patch = FullPatch(i);  // before BuildTree: its time is counted apart
        return stats_.BuildTree([this, &patch] {
            return BuildPatchOctree(patch, threshold_, PatchSettings(patch), cellStore_.get());
        });
    });
}

double PatchesMethod::SeamUncertainty(const Ray& ray) const {
    // Roots are accepted within the tolerance, the floor width or the automatic tolerance
    // of a sign change (lg_octree.h); twice their sum covers every case.
    return 2 * (settings_.tolerance + settings_.minWidth +
                settings_.autoToleranceCap * Length(ray.dir));
}

std::optional<double> PatchesMethod::FirstRoot(const Ray& ray, double tMin, double tMax) const {
    std::optional<MethodHit> hit = Intersect(ray, tMin, tMax);
    return hit ? std::optional<double>(hit->t) : std::nullopt;
}

template <class Visit>
void PatchesMethod::WalkPatches(const Ray& ray, double tMin, double& tMax,
                                Visit&& visit) const {
    if (grid_) {
        grid_->TraverseInEntryOrder(ray, tMin, tMax, visit);
    } else {
        bvh_.TraverseInEntryOrder(ray, tMin, tMax, visit);
    }
}

// The patches in the order the ray enters their boxes (or grid cells), the walk clipped to
// (tMin, best) so patches beyond the best hit so far are skipped.
std::optional<MethodHit> PatchesMethod::Intersect(const Ray& ray, double tMin,
                                                  double tMax) const {
    double best = tMax;
    int bestPatch = -1;
    WalkPatches(ray, tMin, best, [&](int patch) {
        // A ray missing the own term's support meets no acceptable root: skip the patch
        // before its tree is built (the result is the same).
        if (!MayHoldRoot(patch, ray, tMin, best)) return false;
        // Objects of per-cell trees search only the piece where the own term may
        // predominate (Patch::ClipToOwnRegion): at the fluids' density a ray crosses a
        // few patches' balls for each patch it may hit in.
        double t0 = tMin, t1 = best;
        const Patch& full = FullPatch(patch);
        if (cellStore_ && !full.ClipToOwnRegion(ray, SeamUncertainty(ray), t0, t1)) return false;
        std::optional<double> t = PatchFirstRoot(full, Tree(patch), ray, t0, t1);
        if (!t) return false;
        best = *t;
        bestPatch = patch;
        return true;
    });
    if (bestPatch < 0) return std::nullopt;
    return MethodHit{best, patches_[bestPatch].Own()};
}

Vec3 PatchesMethod::Normal(const Field& whole, const Vec3& p, int term) const {
    const int patch = PatchOf(term);
    if (patch < 0) return IntersectionMethod::Normal(whole, p, term);
    const Field& field = FullPatch(patch).GetField();
    const Vec3 n = Normalize(-field.Gradient(p));
    return LengthSquared(n) != 0 ? n : AwayFromSkeleton(field, patches_[patch].Own(), p);
}

}  // namespace rs
