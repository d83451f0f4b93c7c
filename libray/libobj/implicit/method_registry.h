// Layer 8 of the implicit module: the registry of intersection methods, name → factory, so
// the primitive and the command-line overrides dispatch through one table. `auto` is a rule, not a method: it becomes patches or polynomial
// (ResolveAutoMethod), so its row has no factory.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "libobj/implicit/implicit_options.h"
#include "libobj/implicit/intersection_method.h"
#include "libobj/implicit/object_stats.h"

namespace rs {

struct MethodEntry {
    ImplicitMethod method;
    const char* name;
    // Makes the method for the object whose plain sum is `whole`, with its options and
    // statistics (both must outlive the method); null for `auto` only.
    std::unique_ptr<IntersectionMethod> (*create)(const Field& whole,
                                                  const ImplicitOptions& options,
                                                  const ImplicitObjectStats& stats);
    // Why the method cannot serve these terms (a message naming a skeleton), or empty; null
    // when every object is accepted.
    std::string (*check)(const std::vector<FieldTerm>& terms);
    // The method run while the object moves within the shutter (field_motion.h): this one,
    // or, for a method whose per-object data cannot follow the motion, one searching the
    // same field that can.
    ImplicitMethod whenMoving;
};

// The parameters of the baseline methods (march, sphere, segment, polynomial, exact) in
// `options`.
MethodParams BaselineParams(const ImplicitOptions& options);

// The octree heuristics of `method` (kb89's for kb89, the patches defaults otherwise, unused
// by the baselines) with the declared maximum depth and, but for kb89, the declared Dratio.
OctreeHeuristics MethodOctreeHeuristics(ImplicitMethod method, int maxDepth,
                                        double patchesDRatio);

// Every method, in the order of ImplicitMethod.
const std::vector<MethodEntry>& MethodRegistry();
const MethodEntry& MethodEntryOf(ImplicitMethod method);

// Name <-> method; ParseImplicitMethod returns false on other words.
bool ParseImplicitMethod(const std::string& word, ImplicitMethod& method);
const char* ImplicitMethodName(ImplicitMethod method);
// "patches, kb89, march, sphere, segment, polynomial, exact, auto", for messages.
std::string ImplicitMethodNames();

// What `method auto` (the scene default) runs: polynomial where it searches the same surface
// as patches exactly, i.e. every term is a point or segment with the blob kernel and every
// pair blends
// (no blend or contact statements: the union of automatic patches is the plain sum's
// surface, patch.h); patches otherwise. The quartics find the first root to the polynomial
// solver's accuracy with no octree to build, and cost O(log N) per ray for N skeletons.
ImplicitMethod ResolveAutoMethod(const std::vector<FieldTerm>& terms, bool blendsOrContacts);

// The one place a requested method becomes the method run: `auto` resolved by
// ResolveAutoMethod from the terms and the blend graph and contacts of `options`, then the
// method's check of the terms. Returns the method in `chosen`, or an error message naming a
// skeleton when the method cannot serve the terms.
std::string ChooseMethod(ImplicitMethod requested, const std::vector<FieldTerm>& terms,
                         const ImplicitOptions& options, ImplicitMethod& chosen);

}  // namespace rs
