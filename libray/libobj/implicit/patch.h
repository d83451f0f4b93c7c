// Layer 5 of the implicit module: implicit patches (Gascuel 1995 §2, §2.1, §3.4).
//
// An object is a list of terms (skeleton, kernel, weight), indexed 0..n−1. Every term of
// positive weight owns one patch. A patch's field is its own term plus its neighbours'
// terms; the patch's surface is the part of {patch field = T} where the own term
// predominates, and the object is the union of the patches.
//
// Neighbours:
//   - automatic: every other term whose support box overlaps the own support box. At any
//     point where the own term is positive, every non-zero term is then in the list, so the
//     patch field equals the full sum there and the union of patches is exactly the surface
//     of the plain sum (the own term is positive wherever it predominates on the surface,
//     since F = T > 0 needs a positive term and the own one is the largest);
//   - explicit blend graph: only declared pairs blend. Non-blending parts form separate
//     surfaces whose union is rendered (with a crease where they overlap).
//
// Predominance at p: for every neighbour j, c_own > c_j, or c_own == c_j and own < j
// (c = w·f(d), signed), so exactly one term wins any tie, the lowest index.
//
// Patch box: the own support box (skeleton box padded by R). Accepted roots lie inside it,
// because the own term must be positive there (see above; requires threshold T > 0).
// Negative-weight terms own no patch: where the surface exists some positive term exceeds
// them.
#pragma once

#include <limits>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include "libcommon/ray.h"
#include "libobj/implicit/field.h"

namespace rs {

class Patch {
  public:
    // `members` are term indices (rows of `object`'s table), the own term first. The patch
    // field shares the object's term table (Field::Subset): a patch stores its member list,
    // not copies of its terms.
    Patch(const Field& object, std::vector<int> members);

    int Own() const { return field_.Rows().front(); }
    const std::vector<int>& Members() const { return field_.Rows(); }
    // The patch field: the terms of Members(), summed in that order (own term first); its
    // term indices are the object's.
    const Field& GetField() const { return field_; }
    const Bounds3& Box() const { return box_; }

    // Whether the own term predominates at p (ties to the lowest term index).
    bool Predominates(const Vec3& p) const {
        return PredominanceAt(p, 0) == Predominance::Strict;
    }
    // The seam rule: whether the own term may predominate at some point within distance
    // `uncertainty` of p, i.e. for every neighbour j
    //     c_j(p) − c_own(p) <= (λ_own + λ_j)·uncertainty + κ,
    // with λ_i = |w_i|·max|f_i'| term i's Lipschitz constant in space (distances to a
    // skeleton are 1-Lipschitz) and κ = kValueRounding·(|c_j| + |c_own|) the rounding of
    // the two values; an exact tie (c_j == c_own) keeps the tie rule. So a root found
    // within `uncertainty` of a true root where the own term predominates is never
    // rejected, at a seam between patches or anywhere else; a root accepted by two patches
    // near their seam is harmless (the nearest one wins, and both lie within the
    // uncertainty of the surface). uncertainty = 0: exact predominance.
    bool PredominatesNear(const Vec3& p, double uncertainty) const {
        return PredominanceAt(p, uncertainty) != Predominance::None;
    }
    // Both tests in one pass over the neighbours: Strict where Predominates holds, Near
    // where only PredominatesNear does, None otherwise.
    enum class Predominance { Strict, Near, None };
    Predominance PredominanceAt(const Vec3& p, double uncertainty) const;
    // Relative rounding of a computed point o + t·d (of |o| + |t|·|d|) and of a term value:
    // a few ulps, generously.
    static constexpr double kPositionRounding = 8 * 0x1p-52, kValueRounding = 8 * 0x1p-52;
    // False only when the ray's piece (tMin, tMax) surely misses the own term's support
    // {d < R}, where no root can be accepted (the own term is 0 there; see Box()), so the
    // patch's search may be skipped, and its tree left unbuilt. Point skeletons test the
    // ball of radius R around the centre (its span along the ray too), segments the
    // capsule (the distance from the ray's line to the segment), both enlarged for
    // rounding; other kinds are not tested (true: their support box, Box(), is the test
    // the caller makes).
    bool MayHoldRoot(const Ray& ray, double tMin, double tMax) const;
    // MayHoldRoot's test as a ball alone, for callers that keep the balls of many patches
    // together (a million patches' own terms are a cache miss each): a static point
    // skeleton's own ball, for which MayHoldRoot(ray, tMin, tMax) equals
    // ball.MayMeet(ray, tMin, tMax) for every ray; nothing for other kinds and moving fields.
    struct SupportBall {
        Vec3 centre;
        double reach;  // the kernel radius enlarged by kSupportMargin
        bool MayMeet(const Ray& ray, double tMin, double tMax) const;
    };
    std::optional<SupportBall> StaticSupportBall() const;
    // The enlargement: relative 1e-6 of R plus 1e-9 of the distances from the ray origin
    // to the skeleton's points (centre, or both ends). The closest approaches and the
    // accepted points o + t·d are computed with errors of a few ulps of those lengths
    // (~1e-15 relative), far inside it.
    static constexpr double kSupportMargin = 1e-6, kOriginMargin = 1e-9;
    // Narrows (t0, t1) to the part of the ray inside Box() where the own term may
    // predominate; false when none is left. Used where it pays (objects of many point
    // skeletons, PatchesMethod) and exact only in that sense: for a static, undeformed
    // point skeleton, each neighbour that is a point of the same kernel and weight
    // predominates wherever it is the nearer one (the kernels are strictly decreasing on
    // [0, R), Kernel::Validate), so the own term can win only on its side of their
    // bisector plane; the ray's piece is cut to the intersection of those half-spaces,
    // each moved outwards by kSeamMargin·R + `uncertainty` (the largest distance between a
    // root a search may accept and a true root, in world units) plus the rounding of the
    // points o + t·d (kOriginMargin of their size). Every point where the seam rule may
    // accept a root (the own term is positive there: d_own < R) stays inside, so a search of the narrowed piece returns what the
    // whole piece's search would, up to which tolerance-sized root. Other neighbours and
    // other kinds leave the piece as it is.
    // After LimitToSurface, the piece is also cut to the ball of radius SurfaceReach()
    // around the centre, grown by the same margin: every true root of the own part lies
    // inside that ball, so the search of the cut piece still finds it.
    bool ClipToOwnRegion(const Ray& ray, double uncertainty, double& t0, double& t1) const;
    static constexpr double kSeamMargin = 1e-3;
    // Bounds the own part of the patch's solid {patch field >= threshold, own term
    // predominates} by a ball around a static, undeformed point skeleton (see the .cpp for
    // the bound) and keeps its radius as SurfaceReach(); other skeletons and moving fields
    // keep the unbounded reach. Needs threshold > 0.
    void LimitToSurface(double threshold);
    // The radius of that ball (at most the own kernel radius R, up to R/2^15 above the
    // bound's crossing); infinity before LimitToSurface or where it bounds nothing.
    double SurfaceReach() const { return surfaceReach_; }
    // Adds a deformation term to the patch field (contact.h); predominance, members and box
    // are unchanged.
    void Deform(std::shared_ptr<const FieldDeformation> deformation) {
        field_.SetDeformation(std::move(deformation));
    }

  private:
    // MayHoldRoot's test for the skeleton of `own` with its support radius grown by `moved`.
    static bool MayMeetSupport(const FieldTerm& own, double moved, const Ray& ray, double tMin,
                               double tMax);
    // The support radius those tests use: R enlarged by kSupportMargin, plus `moved`.
    static double SupportReach(const FieldTerm& own, double moved);

    Field field_;
    Bounds3 box_;
    double surfaceReach_ = std::numeric_limits<double>::infinity();
};

enum class BlendMode { Automatic, Explicit };

// The automatic neighbour lists of an object's terms, made one patch at a time: Members(i)
// is the member list BuildPatches gives term i's patch in Automatic mode (i, then every
// other term whose support box overlaps i's and that is not paired with i in `separate`,
// in increasing order). The index (a uniform grid of the support boxes, see the .cpp) is
// made once; Members is const and may be called from any thread. `object` must outlive it.
class AutomaticNeighbours {
  public:
    explicit AutomaticNeighbours(const Field& object);
    ~AutomaticNeighbours();
    AutomaticNeighbours(const AutomaticNeighbours&) = delete;
    AutomaticNeighbours& operator=(const AutomaticNeighbours&) = delete;
    // `separate`: symmetric pairs as sorted (low, high) pairs (empty: none).
    std::vector<int> Members(int i, const std::vector<std::pair<int, int>>& separate = {}) const;

  private:
    class Grid;
    const Field& object_;
    std::unique_ptr<const Grid> grid_;
};

// Builds one patch per positive-weight term of `object` (a field made from the object's
// terms, whose table the patches share). In Explicit mode `blendPairs` lists the term
// index pairs that blend (symmetric; others are ignored); in Automatic mode it is unused.
// `separatePairs` (symmetric) never blend, in either mode: the pairs in contact (contact.h).
std::vector<Patch> BuildPatches(const Field& object, BlendMode mode,
                                const std::vector<std::pair<int, int>>& blendPairs = {},
                                const std::vector<std::pair<int, int>>& separatePairs = {});

}  // namespace rs
