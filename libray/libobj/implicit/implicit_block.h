// Turns an implicit block's description (implicit_syntax.h) into the object's terms and
// options: skeletons and kernels into field terms (again at each frame when some number is
// time-varying), names in blend, contact and propagation statements into term indices.
// Every error and warning is reported at the statement at fault.
#pragma once

#include <functional>
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
};

// Fails through `args` (at the statement's location) on an unknown name, a pair both
// blended and in contact, invalid skeleton or kernel parameters, or a method that cannot
// serve the terms.
BuiltImplicitBlock BuildImplicitBlock(ImplicitDescription description, ArgReader& args);

}  // namespace rs
