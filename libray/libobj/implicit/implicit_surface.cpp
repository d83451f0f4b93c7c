#include "libobj/implicit/implicit_surface.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "libcommon/cpu_clock.h"
#include "libobj/implicit/implicit_block.h"
#include "libobj/implicit/implicit_motion.h"
#include "libobj/implicit/implicit_syntax.h"
#include "libobj/implicit/method_registry.h"
#include "libobj/implicit/patch.h"
#include "libobj/object.h"

namespace rs {

bool ImplicitSurface::IsBlockWord(const std::string& word) {
    return IsImplicitStatementWord(word);
}

ImplicitSurface::ImplicitSurface(std::vector<FieldTerm> terms, ImplicitOptions options)
    : options_(std::move(options)), whole_(std::move(terms)) {
    if (options_.method == ImplicitMethod::Auto) {
        // `auto` always yields a method that serves the terms: there is no error to report.
        const std::string error =
            ChooseMethod(ImplicitMethod::Auto, Terms(), options_, options_.method);
        static_cast<void>(error);
    }
    Build();
}

std::shared_ptr<Primitive> ImplicitSurface::Create(ArgReader& args) {
    BuiltImplicitBlock block = BuildImplicitBlock(ReadImplicitBlock(args), args);
    if (block.terms.empty()) return nullptr;  // discarded (BuildImplicitBlock warned)
    auto surface =
        std::make_shared<ImplicitSurface>(std::move(block.terms), std::move(block.options));
    surface->termsAt_ = std::move(block.termsAt);
    surface->block_ = std::move(block.description);
    return surface;
}

std::string ImplicitSurface::SetMethod(ImplicitMethod method) {
    ImplicitOverrides overrides;
    overrides.method = method;
    return ApplyOverrides(overrides);
}

std::string ImplicitSurface::ApplyOverrides(const ImplicitOverrides& overrides) {
    if (overrides.method) {
        ImplicitMethod method;
        if (std::string error = ChooseMethod(*overrides.method, Terms(), options_, method);
            !error.empty()) {
            return stats_.Label() + ": " + error;
        }
        options_.method = method;
        options_.octree = MethodOctreeHeuristics(options_.method, options_.octree.maxDepth,
                                                 options_.patchesDRatio);
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
        options_.search.tolerance = *overrides.tolerance;
        options_.search.minWidth = *overrides.tolerance;
        options_.search.autoTolerance = false;  // fixed, as `tolerance EPS` in the scene
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

// Makes the method (patches and their BVH, or a baseline; octrees are built lazily by
// their methods) and counts the time under this object's label.
void ImplicitSurface::Build() {
    const uint64_t cpuStart = ThreadCpuMicroseconds();
    method_.reset();
    const std::vector<FieldTerm>& terms = Terms();
    partOfTerm_.assign(terms.size(), -1);
    termOfPart_.clear();
    for (size_t i = 0; i < terms.size(); ++i) {
        if (!(terms[i].weight > 0)) continue;
        partOfTerm_[i] = static_cast<int>(termOfPart_.size());
        termOfPart_.push_back(static_cast<int>(i));
    }
    methodOptions_ = options_;
    if (!slices_.empty()) {
        methodOptions_.method = MethodEntryOf(options_.method).whenMoving;
        if (methodOptions_.method != options_.method) {
            methodOptions_.octree = MethodOctreeHeuristics(
                methodOptions_.method, options_.octree.maxDepth, options_.patchesDRatio);
        }
    }
    if (whole_.Motion()) methodOptions_.octree.useHeuristic1bis = false;
    if (!slices_.empty() && methodOptions_.autoContacts) {
        // The frame's pairs were found once over the whole shutter (MakeTimeSlices): every
        // slice gets them as declared pairs.
        methodOptions_.autoContacts = false;
        methodOptions_.contacts.insert(methodOptions_.contacts.end(), frameContacts_.begin(),
                                       frameContacts_.end());
    }
    const MethodEntry& entry = MethodEntryOf(methodOptions_.method);
    if (slices_.empty()) {
        method_ = entry.create(whole_, methodOptions_, stats_);
        bounds_ = method_->Bounds(whole_);
    } else {
        bounds_ = Bounds3();
        for (TimeSlice& slice : slices_) {
            slice.method = entry.create(slice.field, methodOptions_, stats_);
            bounds_.Extend(slice.method->Bounds(slice.field));
        }
    }
    stats_.CountPreprocessing(ThreadCpuMicroseconds() - cpuStart);
}

void ImplicitSurface::PrepareFrame(double frameTime, double shutter) {
    if (!termsAt_) return;
    method_.reset();  // it refers to the terms being replaced
    slices_.clear();
    if (shutter > 0) {
        MakeTimeSlices(frameTime, frameTime + shutter);
    } else {
        whole_ = Field(termsAt_(frameTime));
    }
    Build();
}

void ImplicitSurface::MakeTimeSlices(double t0, double t1) {
    double relativeReach = 0;
    Field whole = MovingField(t0, t1, &relativeReach);
    // Halving the interval about halves the reach of smooth motions.
    const int count = std::clamp(static_cast<int>(std::ceil(relativeReach / kSliceReach)), 1,
                                 kMaxTimeSlices);
    frameContacts_.clear();
    if (options_.autoContacts && options_.method == ImplicitMethod::Patches) {
        frameContacts_ = FrameContacts(t0, t1, count);
    }
    if (count == 1) {
        // The whole interval is the one slice: its field is the one just made.
        slices_.push_back({t1, std::move(whole), nullptr});
    } else {
        for (int k = 0; k < count; ++k) {
            const double start = k == 0 ? t0 : slices_.back().end;
            const double end = k + 1 == count ? t1 : t0 + (t1 - t0) * (k + 1) / count;
            slices_.push_back({end, MovingField(start, end), nullptr});
        }
    }
    whole_ = slices_.front().field;
}

// The undeclared pairs of `contact auto` over the shutter: the union of the pairs found in
// the static objects at the start, middle and end of every time slice (2·slices + 1 times,
// evenly spaced), each pair counted once for the frame. Static patches, not the moving
// ones: their tight bounds prune the interpenetration search far better than swept ones.
std::vector<ContactPair> ImplicitSurface::FrameContacts(double t0, double t1, int slices) const {
    const uint64_t cpuStart = ThreadCpuMicroseconds();
    std::vector<ContactPair> found;
    for (int k = 0; k <= 2 * slices; ++k) {
        const Field atTime(termsAt_(t0 + (t1 - t0) * k / (2 * slices)));
        const std::vector<Patch> patches = BuildPatches(
            atTime, options_.blendMode, options_.blendPairs, SeparatePairs(options_.contacts));
        const std::vector<ContactPair> pairs = AutomaticContacts(patches, options_.threshold);
        found.insert(found.end(), pairs.begin(), pairs.end());
    }
    std::sort(found.begin(), found.end());
    found.erase(std::unique(found.begin(), found.end()), found.end());
    std::vector<ContactPair> pairs = UndeclaredContacts(found, options_.contacts);
    for (size_t i = 0; i < pairs.size(); ++i) stats_.CountAutomaticContact();
    stats_.CountPreprocessing(ThreadCpuMicroseconds() - cpuStart);
    return pairs;
}

const ImplicitSurface::TimeSlice* ImplicitSurface::SliceAt(double time) const {
    if (slices_.empty()) return nullptr;
    for (const TimeSlice& slice : slices_) {
        if (time <= slice.end) return &slice;
    }
    return &slices_.back();
}

Field ImplicitSurface::MovingField(double t0, double t1, double* relativeReach) const {
    MovingTerms moving = BuildMovingTerms(block_, termsAt_(0.5 * (t0 + t1)), t0, t1);
    if (!moving.error.empty()) {
        Report(Severity::Abort, block_->Where(moving.place),
               "implicit object, shutter [%g, %g]: %s", t0, t1, moving.error.c_str());
    }
    if (relativeReach) {
        *relativeReach = 0;
        for (size_t i = 0; i < moving.reference.size(); ++i) {
            const TermMotion& m = moving.motion->Of(static_cast<int>(i));
            if (!m.moving) continue;
            // A radius changing by ΔR loosens the swept bounds as a skeleton moving by ΔR.
            const double spread = m.kernelMoves ? m.kernels.Radius() - m.kernels.Lo().Radius() : 0;
            *relativeReach = std::max(*relativeReach,
                                      (m.reach + spread) / moving.reference[i].kernel.Radius());
        }
    }
    return Field(std::move(moving.reference), std::move(moving.motion));
}

const IntersectionCounters& ImplicitSurface::Counters() const {
    static const IntersectionCounters counters("Implicit");
    return counters;
}

bool ImplicitSurface::Intersect(const Ray& ray, double tMin, double tMax,
                                PrimitiveHit& hit) const {
    return stats_.CountIntersect([&] {
        // A moving field is evaluated at the ray's time; the hit keeps it for Normal.
        const TimeSlice* slice = SliceAt(ray.time);
        const RayTimeScope time(slice ? ray.time : kNoRayTime);
        const std::optional<MethodHit> found =
            (slice ? *slice->method : *method_).Intersect(ray, tMin, tMax);
        if (!found) return false;
        hit.t = found->t;
        if (slice) hit.a = ray.time;
        hit.part = found->term >= 0 ? partOfTerm_[found->term] : -1;
        return true;
    });
}

SurfaceNormals ImplicitSurface::Normal(const Vec3& p, const PrimitiveHit& hit) const {
    const TimeSlice* slice = SliceAt(hit.a);
    const RayTimeScope time(slice ? hit.a : kNoRayTime);
    const bool hasPart = hit.part >= 0 && hit.part < static_cast<int>(termOfPart_.size());
    const int own = hasPart ? termOfPart_[hit.part] : -1;
    const Vec3 n =
        slice ? slice->method->Normal(slice->field, p, own) : method_->Normal(whole_, p, own);
    return {n, n, false};
}

namespace {

bool ApplyBelow(Object& node, const ImplicitOverrides& overrides, std::set<const Object*>& seen,
                int& count, std::string& error) {
    if (!seen.insert(&node).second) return true;
    switch (node.kind()) {
        case Object::Kind::Primitive:
            if (auto* implicit = dynamic_cast<ImplicitSurface*>(node.primitive())) {
                error = implicit->ApplyOverrides(overrides);
                if (!error.empty()) return false;
                ++count;
            }
            return true;
        case Object::Kind::Aggregate:
            for (const std::shared_ptr<Object>& child : node.aggregate()->Children()) {
                if (!ApplyBelow(*child, overrides, seen, count, error)) return false;
            }
            return true;
        case Object::Kind::Instance:
            return ApplyBelow(*node.instanceOf(), overrides, seen, count, error);
    }
    return true;
}

}  // namespace

int ApplyImplicitOverrides(Object& root, const ImplicitOverrides& overrides, std::string& error) {
    std::set<const Object*> seen;
    int count = 0;
    error.clear();
    if (!ApplyBelow(root, overrides, seen, count, error)) return -1;
    return count;
}

}  // namespace rs
