// Layer 8 of the implicit module: the `implicit` primitive (Gascuel 1995, "Implicit
// Patches"), the only file of the module that knows libobj. Compiled into ray_obj.
//
// The scene syntax is read by implicit_syntax.h and documented in
// docs/implicit-reference.md. Skeleton numbers, weights and field parameters may be
// time-varying; the object is then rebuilt by PrepareFrame for each frame (Bounds()
// describes the current frame).
//
// Statistics: each object is labelled "Implicit object N" (N = 1, 2, ... in order of
// creation) and counts, under "<label>: ...", its preprocessing time (microseconds), octree
// cells and memory (bytes), each octree heuristic's firings and the evaluations made while
// building (all summed over rebuilds), and per Intersect call the rays tested, hits, field,
// gradient and bound evaluations and Ridders iterations. Intersect attributes the module's
// thread-local counters by differences (libcommon/stats.h ThreadCount): no locks.
// Octrees are built lazily, by the first ray reaching each one (patches no ray reaches
// cost nothing): their build figures, preprocessing time included, are attributed the same
// way by the building thread and excluded from that ray's evaluation counts, so the
// preprocessing time is build CPU time summed over threads, part of the rendering time.
#pragma once

#include <atomic>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "libcommon/arg_reader.h"
#include "libobj/implicit/contact.h"
#include "libobj/implicit/implicit_overrides.h"
#include "libobj/implicit/lg_octree.h"
#include "libobj/implicit/method_registry.h"
#include "libobj/primitive.h"

namespace rs {

struct ImplicitOptions {
    double threshold = 1;
    // The search and build settings of the octree methods; octree.tolerance is every
    // method's root accuracy.
    OctreeSettings octree;
    // Gascuel's Dratio as declared, restored when the method becomes Patches again.
    double patchesDRatio = 2;
    // `octree auto` (the scene default): each patch's octree depth from its own skeleton's
    // thickness (ImplicitSurface::AutoMinDepth); otherwise octree.minDepth and maxDepth.
    bool autoDepth = false;
    ImplicitMethod method = ImplicitMethod::Patches;
    // The march step (object-space distance); <= 0: DefaultMarchStep.
    double marchStep = 0;
    // The declared blend graph; used only in patches mode.
    BlendMode blendMode = BlendMode::Automatic;
    std::vector<std::pair<int, int>> blendPairs;  // term indices, Explicit mode only
    // Colliding patches and their attenuation zones (contact.h); patches mode only.
    std::vector<ContactPair> contacts;
    std::vector<Propagation> propagations;
};

// The octree settings of `method` (kb89's heuristics for kb89, the patches defaults
// otherwise, unused by the baselines), keeping the declared depth and tolerance of
// `declared` and, but for kb89, the declared Dratio.
OctreeSettings MethodOctreeSettings(ImplicitMethod method, const OctreeSettings& declared,
                                    double patchesDRatio);

// The field, gradient and bound evaluations this thread has made inside lazy octree builds
// so far; callers counting a ray's evaluations by ThreadCount differences subtract it.
uint64_t ImplicitBuildEvaluations();

class ImplicitSurface final : public Primitive {
  public:
    // Terms must have valid kernels (Kernel::Validate) and threshold > 0.
    ImplicitSurface(std::vector<FieldTerm> terms, ImplicitOptions options);

    // Reads the block syntax above; fails (located, with usage) on malformed input and
    // invalid kernels, naming the skeleton.
    static std::shared_ptr<Primitive> Create(ArgReader& args);
    // Whether `word` begins the block's statements (threshold, field, segment, end, ...),
    // so a parser can tell it from an optional surface name after `implicit`.
    static bool IsBlockWord(const std::string& word);

    const IntersectionCounters& Counters() const override;
    Bounds3 Bounds() const override { return bounds_; }
    bool IsClosed() const override { return true; }
    bool Intersect(const Ray& ray, double tMin, double tMax, PrimitiveHit& hit) const override;
    // Shading and geometric normal: normalised −∇F of the winning patch's field (which
    // equals the object's field there), falling back to the direction away from the own
    // skeleton where the gradient vanishes (pinch points), and to +z on the skeleton.
    SurfaceNormals Normal(const Vec3& p, const PrimitiveHit& hit) const override;
    void PrepareFrame(double frameTime) override;

    const std::vector<FieldTerm>& Terms() const { return whole_.Terms(); }
    int PatchCount() const { return static_cast<int>(patches_.size()); }
    // What the contacts did to the patches in the current frame (contact.h; empty without
    // contacts or in kb89 mode).
    const std::vector<DeformedPatch>& Contacts() const { return contacts_; }

    ImplicitMethod Method() const { return options_.method; }
    // Switches the intersection method (and the octree heuristics that go with it, keeping
    // the declared depth, Dratio and tolerance) and rebuilds. Returns an error message,
    // leaving the object unchanged, when the method cannot serve its terms (polynomial).
    std::string SetMethod(ImplicitMethod method);
    // Applies command-line overrides (the method first, then depth, Dratio, tolerance, step
    // and the octree switches) and rebuilds once; an error as for SetMethod.
    std::string ApplyOverrides(const ImplicitOverrides& overrides);
    // The name of the skeleton owning the patch of a hit, or empty when the hit carries no
    // patch (kb89 and the baselines but polynomial: one field for the whole object, no
    // predominance evaluated; polynomial reports the automatic patch of the predominant
    // skeleton at the hit, the patch that method patches would report).
    std::string PatchName(const PrimitiveHit& hit) const;
    // "Implicit object N", the prefix of this object's statistics counters.
    const std::string& Label() const { return label_; }

  private:
    // A bounding volume hierarchy over the patch boxes: leaves hold up to kBvhLeafSize
    // consecutive entries of bvhOrder_, inner nodes their two children at left, left + 1.
    struct BvhNode {
        Bounds3 box;
        int left = -1;   // first child (inner nodes)
        int first = 0;   // first entry of bvhOrder_ (leaves)
        int count = 0;   // > 0 for leaves
    };
    static constexpr int kBvhLeafSize = 2;

    // Per-object statistics counters (see the header comment).
    struct ObjectCounters {
        CounterId tests, hits, values, gradients, bounds, riddersIterations;
        CounterId buildMicroseconds, cells, memoryBytes;
    };

    // A tree built on first use: patch trees are built by the first ray that reaches the
    // patch (on whichever render thread), the rest never. The tree depends only on the
    // patch, so images do not depend on which thread builds it. Held by pointer, so a patch
    // no ray reaches costs 16 bytes here instead of an empty LGOctree's 432.
    struct LazyTree {
        std::once_flag once;
        std::unique_ptr<LGOctree> tree;
    };

    void Build();
    void BuildStructures();
    // Tree `i` (patch i, or the single octree at 0), building it on first use. Thread-safe.
    const LGOctree& Tree(int i) const;
    void BuildTree(int i) const;
    // The depth of heuristics 3 and 3bis for a patch under `octree auto` (see the .cpp).
    static int AutoMinDepth(const Patch& patch, double threshold);
    // The octree settings of a patch (the declared ones, with the auto depth).
    OctreeSettings PatchSettings(const Patch& patch) const;
    // Intersect without the per-object counting.
    bool Search(const Ray& ray, double tMin, double tMax, PrimitiveHit& hit) const;
    void BuildBvh(int index, int first, int count);

    ImplicitOptions options_;
    std::string label_;
    ObjectCounters counters_;
    // Rebuilds the terms for a time (set when any parameter is animated).
    std::function<std::vector<FieldTerm>(double)> termsAt_;
    std::vector<Patch> patches_;
    // One per patch, or the single octree; built lazily (Tree). The array is replaced only
    // by Build, outside rendering.
    std::unique_ptr<LazyTree[]> trees_;
    // Per-object counters fed by lazy builds ("<label>: octree ...", "preprocessing ..."),
    // registered on first use; index as BuildCounterSources(), -1 until registered.
    std::unique_ptr<std::atomic<CounterId>[]> buildCounterIds_;
    // The baseline method (march, sphere, ...) over whole_, when the method has a factory.
    std::unique_ptr<IntersectionMethod> baseline_;
    std::vector<DeformedPatch> contacts_;
    // The plain sum (normals in single-octree mode). Its table holds the object's terms,
    // stored once: the patches' fields share it.
    Field whole_;
    // The automatic patch index of each term (its rank among the positive-weight terms,
    // BuildPatches' order; −1 for the others), and the term owning each patch index: the
    // parts of the baselines that report a predominant term.
    std::vector<int> partOfTerm_, termOfPart_;
    Bounds3 bounds_;
    std::vector<BvhNode> bvh_;  // root at 0 when there are patches
    std::vector<int> bvhOrder_;
};

}  // namespace rs
