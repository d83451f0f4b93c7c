// Layer 8 of the implicit module (compiled into ray_obj): the registry of intersection
// methods, name → factory, so the primitive and the command-line overrides dispatch through
// one table. The octree methods (patches, kb89) are built by ImplicitSurface itself and have
// no factory; the baselines (intersection_method.h) are made by theirs. `auto` is a rule,
// not a method: it becomes patches or polynomial (ResolveAutoMethod).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "libobj/implicit/intersection_method.h"

namespace rs {

enum class ImplicitMethod { Patches, Kb89, March, Sphere, Segment, Polynomial, Exact, Auto };

struct MethodEntry {
    ImplicitMethod method;
    const char* name;
    // Makes the method for the plain sum `field` (which must outlive it); null for the
    // octree methods.
    std::unique_ptr<IntersectionMethod> (*create)(const Field& field, const MethodParams& params);
    // Why the method cannot serve these terms (a message naming a skeleton), or empty; null
    // when every object is accepted.
    std::string (*check)(const std::vector<FieldTerm>& terms);
};

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

}  // namespace rs
