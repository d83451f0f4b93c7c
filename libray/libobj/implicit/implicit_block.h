// Turns an implicit block's description (implicit_syntax.h) into the object's terms and
// options: skeletons and kernels into field terms (again at each frame when some number is
// time-varying), names in blend, contact and propagation statements into term indices.
// Every error and warning is reported at the statement at fault.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "libcommon/arg_reader.h"
#include "libobj/implicit/field.h"
#include "libobj/implicit/implicit_options.h"
#include "libobj/implicit/implicit_syntax.h"

namespace rs {

struct BuiltImplicitBlock {
    // The terms at time 0; empty when the object is discarded (no skeleton of positive
    // weight, warned).
    std::vector<FieldTerm> terms;
    ImplicitOptions options;  // the method resolved (never Auto) and checked
    // The terms at a time; set only when some number of the block is time-varying.
    std::function<std::vector<FieldTerm>(double)> termsAt;
    // The block, kept when termsAt is set (skeleton motion blur rebuilds from it).
    std::shared_ptr<const ImplicitDescription> description;
};

// Whether some number of skeleton `index` (its own, its weight's or its kernel's) is
// time-varying; whether its kernel's are.
bool IsAnimatedSkeleton(const ImplicitDescription& d, size_t index);
bool HasAnimatedKernel(const ImplicitDescription& d, size_t index);

// The kernel of `kind` with a `field` statement's parameters in its order (Gascuel
// thickness, stiffness, radius; blob strength, radius), not validated.
Kernel KernelWithParameters(KernelKind kind, const double (&params)[3]);
// The kernel of skeleton `index` at `time`, not validated.
Kernel MakeKernelAt(const ImplicitDescription& d, size_t index, double time);

// The skeleton of skeleton `index` at `time`, or an error message for invalid parameters
// (circle radius <= 0 or normal 0, cylinder radius < 0).
std::string MakeSkeletonAt(const ImplicitDescription& d, size_t index, double time,
                           Skeleton& skeleton);

// Fails through `args` (at the statement's location) on an unknown name, a pair both
// blended and in contact, invalid skeleton or kernel parameters, or a method that cannot
// serve the terms.
BuiltImplicitBlock BuildImplicitBlock(ImplicitDescription description, ArgReader& args);

}  // namespace rs
