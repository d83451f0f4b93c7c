// Layer 9 of the implicit module, its adapter to libobj: the `implicit` primitive
// (Gascuel 1995, "Implicit Patches"). It holds the object's terms and options, one
// intersection method made by the registry (method_registry.h) and the object's statistics
// (object_stats.h), and calls the method; it knows no method in particular. Compiled into
// ray_obj.
//
// The scene syntax is read by implicit_syntax.h and documented in
// docs/implicit-reference.md. Skeleton numbers, weights and field parameters may be
// time-varying; the object is then rebuilt by PrepareFrame for each frame (Bounds()
// describes the current frame).
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "libcommon/arg_reader.h"
#include "libobj/implicit/implicit_options.h"
#include "libobj/implicit/implicit_overrides.h"
#include "libobj/implicit/implicit_syntax.h"
#include "libobj/implicit/intersection_method.h"
#include "libobj/implicit/object_stats.h"
#include "libobj/primitive.h"

namespace rs {

class ImplicitSurface final : public Primitive {
  public:
    // Terms must have valid kernels (Kernel::Validate) and threshold > 0, and the method
    // must serve them (ChooseMethod); Auto, the default, is resolved by ChooseMethod here.
    ImplicitSurface(std::vector<FieldTerm> terms, ImplicitOptions options);

    // Reads the block syntax (implicit_syntax.h); fails (located, with usage) on malformed
    // input and invalid kernels, naming the skeleton.
    static std::shared_ptr<Primitive> Create(ArgReader& args);
    // Whether `word` begins the block's statements (threshold, field, segment, end, ...),
    // so a parser can tell it from an optional surface name after `implicit`.
    static bool IsBlockWord(const std::string& word);

    const IntersectionCounters& Counters() const override;
    Bounds3 Bounds() const override { return bounds_; }
    bool IsClosed() const override { return true; }
    bool Intersect(const Ray& ray, double tMin, double tMax, PrimitiveHit& hit) const override;
    // Shading and geometric normal: the method's (IntersectionMethod::Normal).
    SurfaceNormals Normal(const Vec3& p, const PrimitiveHit& hit) const override;
    // Rebuilds an animated object for the frame: at frameTime with the shutter closed; with
    // it open, as moving fields over [frameTime, frameTime + shutter] (implicit_motion.h),
    // each ray then seeing the skeletons at its own time. The shutter is cut into K equal
    // time slices, each with its own swept bounds and method, K the smallest in 1..8 with
    // every moving skeleton's reach over a slice, plus the spread of an animated kernel's
    // radius, at most kSliceReach of its influence radius (loose swept bounds cost the
    // search more than K builds); `contact auto` finds
    // one set of pairs for the whole shutter (FrameContacts). Fails (Abort, at the
    // skeleton) when the motion cannot be bounded. Method polynomial,
    // whose terms cannot move, is replaced by kb89 (the same field) with the shutter open.
    void PrepareFrame(double frameTime, double shutter) override;
    bool PrepareFrameDoesWork() const override { return true; }

    const std::vector<FieldTerm>& Terms() const { return whole_.Terms(); }
    ImplicitMethod Method() const { return options_.method; }
    // The method searching this object (tests inspect the patches of PatchesMethod); with
    // the shutter open, that of the first time slice.
    const IntersectionMethod& SearchMethod() const {
        return slices_.empty() ? *method_ : *slices_.front().method;
    }
    // The number of time slices of a moving object (0 when static; see PrepareFrame).
    int TimeSlices() const { return static_cast<int>(slices_.size()); }
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

    static constexpr double kSliceReach = 1.0 / 6;
    static constexpr int kMaxTimeSlices = 8;

  private:
    // Makes the method for the current terms and options and counts the time.
    void Build();
    // The moving field of the animated terms over [t0, t1] (PrepareFrame), and the largest
    // of its moving terms' reach plus radius spread (R_hi − R_lo of an animated kernel),
    // relative to the term's influence radius.
    Field MovingField(double t0, double t1, double* relativeReach = nullptr) const;
    // Cuts [t0, t1] into time slices (PrepareFrame).
    void MakeTimeSlices(double t0, double t1);
    // `contact auto` with the shutter open: the pairs the declared ones do not name whose
    // volumes interpenetrate at a start, middle or end of the `slices` time slices of
    // [t0, t1]; counted in the statistics.
    std::vector<ContactPair> FrameContacts(double t0, double t1, int slices) const;

    // One time slice of a moving object: its field over [start, end] of the shutter and
    // the method searching it; a ray uses the slice holding its time.
    struct TimeSlice {
        double end = 0;
        Field field;
        std::unique_ptr<IntersectionMethod> method;
    };
    const TimeSlice* SliceAt(double time) const;

    ImplicitOptions options_;
    ImplicitObjectStats stats_;
    // Rebuilds the terms for a time (set when any parameter is animated).
    std::function<std::vector<FieldTerm>(double)> termsAt_;
    // The block, for motion blur (set with termsAt_).
    std::shared_ptr<const ImplicitDescription> block_;
    // The options the method is made with: options_, but with a moving field the registry's
    // method for it (MethodEntry::whenMoving) and no octree heuristic 1bis (it decides a whole cell from its centre's value and gradient,
    // which a moving skeleton changes within the shutter; heuristic 1 uses the centre's
    // value range over the shutter instead, lg_octree.cpp).
    ImplicitOptions methodOptions_;
    // The plain sum. Its table holds the object's terms, stored once: the patches' fields
    // share it.
    Field whole_;
    // A hit's part is the rank of its owning term among the positive-weight terms (the
    // patch index of method patches, for every method): the part of each term (−1 for the
    // others) and the term of each part.
    std::vector<int> partOfTerm_, termOfPart_;
    Bounds3 bounds_;
    // Holds references to whole_, methodOptions_ and stats_: declared after them.
    std::unique_ptr<IntersectionMethod> method_;
    // With the shutter open (and animated terms), the time slices, in time order; whole_
    // then shares the first one's terms (Terms(), names) and method_ is null.
    std::vector<TimeSlice> slices_;
    // With the shutter open and `contact auto`, the frame's pairs (FrameContacts), given to
    // every slice as declared pairs.
    std::vector<ContactPair> frameContacts_;
};

}  // namespace rs
