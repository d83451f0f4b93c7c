// Skeleton motion blur for the implicit primitive: the terms of an animated block over a
// shutter interval, as a moving field (field_motion.h). Beside implicit_block.h, whose
// description and term builders it uses; compiled into ray_obj.
//
// For each skeleton, the reference term is the term at the middle of [t0, t1]. Its motion
// comes from interval bounds of its numbers over [t0, t1] (DeclaredNumbers::Range, from
// Expr::EvaluateRange): with Δ_j = max(hi_j − v_j, v_j − lo_j) for number j of reference
// value v_j, and |Δv| the norm of a point's three Δ, the reach (a Hausdorff bound, see
// field_motion.h) is
//   - point, segment, triangle, polyline: max over its points of |Δv| (every skeleton
//     point is a fixed convex combination of them);
//   - box: the norm of (max(Δa_c, Δb_c))_c (min and max are 1-Lipschitz per coordinate);
//   - circle: |Δc| + ΔR + R·|Δn̂|, and cylinder: max(|Δa|, |Δb|) + r·|Δû| + Δr, where the
//     unit normal (axis) turns by |Δn̂| <= min(2, 2|ΔN|/|N|) (N the unnormalised vector):
//     the rotation taking the reference normal to the moved one moves a point at distance
//     ρ from the axis by at most ρ|Δn̂|;
// each rounded up by a relative 1e-12. The weight interval is its range. A skeleton whose
// `field` parameters are animated gets the box of their ranges (KernelBox), every corner
// of which must be a valid kernel.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "libobj/implicit/field.h"
#include "libobj/implicit/implicit_syntax.h"

namespace rs {

struct MovingTerms {
    std::vector<FieldTerm> reference;
    std::shared_ptr<const FieldMotion> motion;
    // Empty on success; else what cannot move (a number with no interval bound, a weight
    // changing sign, a circle or cylinder invalid at some time, a kernel box with an
    // invalid corner), naming the skeleton, with `place` its statement (its `field`
    // statement for a kernel box).
    std::string error;
    StatementPlace place;
};

// The moving terms of `block` over [t0, t1] (t0 < t1), `reference` being its terms at the
// middle time (BuiltImplicitBlock::termsAt).
MovingTerms BuildMovingTerms(const std::shared_ptr<const ImplicitDescription>& block,
                             std::vector<FieldTerm> reference, double t0, double t1);

}  // namespace rs
