// Layer 7 of the implicit module: precise contact and propagation between colliding patches
// (Gascuel 1995 §2.2 and §3.5, after M.-P. Gascuel, SIGGRAPH '93).
//
// Notation: T the threshold (inside F > T); f_A the (undeformed) field of patch A; O_A the
// opponent field of A, the plain sum of the terms of every patch declared in contact with A
// (each term once; for one opponent B it is B's patch field f_B). Contact pairs never blend
// (patch.h separatePairs), so A's own term is not in O_A.
//
// Deformed field of A:  D_A(p) = f_A(p) + δ(u),   u = T − O_A(p),
// with the profile δ of one variable (BulgeProfile; w >= 0 the zone width in field units,
// η in [0, 1] the bulge height, s = u/w):
//     u <= 0 (inside the opponent):   δ(u) = u                       compression
//     0 < u < w (attenuation zone):   δ(u) = u(1 − s)²(1 + 2ηs)      propagation bulge
//     u >= w:                         δ(u) = 0
// Compression: where both undeformed volumes overlap (f_A > T, O_A > T) D_A − T = f_A − O_A,
// so the deformed surfaces of A and of its opponent both lie on f_A = O_A, the contact
// surface (Gascuel's term 1 − f_B, written for a threshold T). Inside the opponent but
// outside A, D_A < f_A <= T: nothing of A appears there either.
// Propagation: δ(0) = 0 and δ'(0) = 1 on both sides, so ∇D_A = ∇f_A − ∇O_A is continuous
// across the opponent's undeformed surface {O_A = T}, the border of the interpenetration
// region: the deformed surface is tangent-continuous (G1) across the rim of the contact
// zone (the paper's condition, written with the sign that makes it C¹: the bulge term's
// gradient equals the compression term's, −∇O_A). δ(w) = δ'(w) = 0: the bulge fades out
// with zero slope at the outer edge of the zone O_A = T − w. The profile is C¹ and
// piecewise C² (δ'' jumps at u = 0 and u = w), which is what the LG tests need. Without a
// zone (w = 0, compression only) δ = min(u, 0) has a kink on the opponent's surface: the
// deformed surface has a crease at the rim, and G is infinite in the cells crossing it
// (the search then relies on L and splitting there, still sound).
// Why this profile: it is the lowest-degree polynomial with the four end conditions (the
// cubic u(1 − s)², η = 0, peak 4w/27 at s = 1/3) plus the one-parameter quartic family
// u(1 − s)²(1 + 2ηs) that raises the bulge (peak ≈ 0.26w at η = 1) while keeping δ(u) <= u
// for all u: (1 − s)²(1 + 2ηs) <= (1 − s)²(1 + 2s) = 1 − 3s² + 2s³ <= 1 on [0, 1].
// No overlap, no gap: δ(u) <= u for every u means that a point inside both deformed
// volumes would satisfy f_A + T − O_A > T and f_B + T − O_B > T; for two patches in contact
// with each other only (O_A = f_B, O_B = f_A) that is f_A > f_B > f_A: impossible. So the
// deformed volumes never overlap, bulges included, and inside the interpenetration region
// they are {f_A > f_B} and {f_B > f_A}: complementary, no gap. An absolute bulge height
// would break this, hence η relative to the largest safe one (2η ≤ 2).
//
// The zone is a field distance: u is T − O_A, which equals |∇O_A| times the distance to the
// opponent's surface to first order. The user gives a geometric width W; ApplyContacts turns
// it into w once per build by firing a ray at the opponent's undeformed surface with the
// patches' own LG octrees (PatchFirstRoot): from the point of A's own skeleton nearest the
// opponent skeletons' box centre, towards the nearest opponent skeleton point, s is where
// the ray enters the opponent, and w = T − O_A at distance W before s (clamped to [0, T],
// so the zone stays inside the opponent's support). When A's skeleton point already lies
// inside the opponent (deep contact) the ray goes the other way, s is where it leaves the
// opponent, and w = T − O_A at distance W beyond s. The same ray detects the contact: the
// bulge is switched on only in deep contact or when the ray enters the opponent before it
// leaves A's own undeformed volume (the volumes interpenetrate along the line), so contacts
// may stay declared while animated skeletons move apart; compression needs no switch (it
// changes A's surface only where the volumes overlap). Using the field
// itself as the distance (instead of firing a ray per evaluation, as the paper's renderer
// did) keeps D_A C¹ with computable L and G, and costs one opponent evaluation.
//
// Moving skeletons (shutter open, field_motion.h): the opponent field is made of rows of
// the patches' own (moving) term table, so f_A and O_A are both evaluated at the ray's time
// and their box bounds hold over the whole time interval of the build; the zone box and
// the affected box, grown from those bounds, hold over it too. Compression is therefore
// exact at every time: a ray sees the deformation of the skeletons at its own time. The
// zone width w and the bulge switch are measured once per build, by the ray above, on the
// reference terms (the middle of the time slice): within one slice the bulge keeps that
// field width (exact under a common translation or rotation of the pair, which leaves the
// measure unchanged; otherwise the width of the slice's middle).
//
// Bounds (ContactDeformation::Bound, for a box with opponent bounds O ∈ [Omin, Omax], L_O,
// G_O): u ∈ [T − Omax, T − Omin]; δ's value range and max|δ'|, max|δ''| over that interval
// (BulgeProfile::Bounds, exact: δ is unimodal and the extrema of δ', δ'' are at the ends of
// each piece or at roots of polynomials solved in closed form); then, by the chain rule along
// any unit direction v (u_v = −∇O_A·v, u_vv = −vᵀ∇²O_A v):
//     |∇δ(u)| <= max|δ'|·L_O,   |d²δ/dv²| = |δ''u_v² + δ'u_vv| <= max|δ''|·L_O² + max|δ'|·G_O.
// The deformed patch's L and G are those of f_A plus these (Field::Bound adds them): the sum
// of the undeformed field's, the opponent's (through L_O, G_O) and the attenuation
// function's, as in the paper's §3.5. The term is exactly 0 wherever O_A <= T − w; the zone
// box, built once by a value-range subdivision of the opponent's support, contains every
// point with O_A > T − w, so evaluations and bounds outside it skip the opponent entirely.
#pragma once

#include <compare>
#include <memory>
#include <utility>
#include <vector>

#include "libobj/implicit/lg_octree.h"

namespace rs {

// Range of δ and of its first two derivatives over a closed interval of u.
struct ProfileBounds {
    double valueMin = 0, valueMax = 0;
    double maxSlope = 0;   // max |δ'|
    double maxSecond = 0;  // max |δ''|, one-sided values at u = 0 and u = w included;
                           // +infinity across the kink of the zone-less profile
};

class BulgeProfile {
  public:
    // Compression only (w = 0): δ(u) = min(u, 0).
    BulgeProfile() = default;
    // Requires width >= 0 and height in [0, 1].
    BulgeProfile(double width, double height);

    double Width() const { return width_; }
    double Height() const { return height_; }
    double Value(double u) const;
    double Derivative(double u) const;
    // δ'' of the piece containing u: (−∞, 0], (0, w), [w, ∞).
    double SecondDerivative(double u) const;
    // Where δ is largest: u = w·s* with s* in (0, 1) the root of 8ηs² + (3 − 4η)s − 1
    // (q'(s) = (s − 1)(8ηs² + (3 − 4η)s − 1)); 0 when w = 0.
    double PeakU() const { return width_ * peakS_; }
    ProfileBounds Bounds(double u0, double u1) const;

  private:
    double width_ = 0, height_ = 0;
    double peakS_ = 0;
};

// The deformation term δ(T − O(p)) of one patch (see the header comment).
class ContactDeformation final : public FieldDeformation {
  public:
    ContactDeformation(Field opponent, double threshold, BulgeProfile profile);

    double Value(const Vec3& p) const override;
    Vec3 Gradient(const Vec3& p) const override;
    FieldBound Bound(const Bounds3& box) const override;

    const Field& Opponent() const { return opponent_; }
    const BulgeProfile& Profile() const { return profile_; }
    // Contains every point where the term is non-zero (O > T − w); empty when there is none.
    const Bounds3& Zone() const { return zone_; }

  private:
    void GrowZone(const Bounds3& box, int depth);

    Field opponent_;
    double threshold_;
    BulgeProfile profile_;
    Bounds3 zone_;
};

// `contact A B`: the global term indices of the two own skeletons.
struct ContactPair {
    int a = -1, b = -1;
    // By a, then b.
    auto operator<=>(const ContactPair&) const = default;
};

// `propagation Name Width [Height]`: the attenuation zone of the patch owned by `term`, of
// geometric width `width` (object space) and relative bulge height `height` in [0, 1].
struct Propagation {
    int term = -1;
    double width = 0, height = 0;
};

// What ApplyContacts did to one patch (for statistics, tests and the examples' boxes).
struct DeformedPatch {
    int patch = -1;         // index into the patch list
    double fieldWidth = 0;  // w in field units; 0 when no bulge
    // The measuring ray saw the volumes overlap (measured only for patches with a zone).
    bool interpenetrates = false;
    bool deformed = false;  // the patch field was replaced (affected box not empty)
    Bounds3 zone;           // ContactDeformation::Zone()
    // Contains every point of the patch box where the deformed field and the undeformed one
    // lie on different sides of T (there the term is non-zero, O > T − w, and f_A exceeds
    // T minus the bulge's peak value): the "deformation box" of Gascuel's figure 7.
    Bounds3 affected;
};

// Whether the undeformed volumes of two patches interpenetrate: some point lies inside both
// (each patch field exceeds T there and each own term predominates in its patch, so the
// point is on both surfaces' inner side). Searched by subdividing the overlap of the two
// patch boxes, down to depth kInterpenetrationDepth (cells of 1/128 of its edges): a cell
// where either field stays <= T (Field::Bound) is cleared, and each cell's centre is tested.
// A cell where either own term cannot predominate (some neighbour's term range over the
// cell lies above the own term's) is cleared too. A "yes" is certain; an interpenetration
// thinner than the finest cells can be missed.
bool VolumesInterpenetrate(const Patch& a, const Patch& b, double threshold);
inline constexpr int kInterpenetrationDepth = 7;

// The pairs `contact auto` adds: every two patches that do not blend (neither term is a
// member of the other's patch) and whose undeformed volumes interpenetrate, as term index
// pairs (a < b) in increasing order.
std::vector<ContactPair> AutomaticContacts(const std::vector<Patch>& patches, double threshold);

// The pairs of `found` that `declared` does not name (in either order), in found's order.
std::vector<ContactPair> UndeclaredContacts(const std::vector<ContactPair>& found,
                                            const std::vector<ContactPair>& declared);

// The pairs as BuildPatches' separatePairs: patches in contact never blend.
std::vector<std::pair<int, int>> SeparatePairs(const std::vector<ContactPair>& contacts);

// Deforms every patch whose own term appears in a contact pair (pairs naming a term without
// a patch are ignored) and rebuilds its octree on the deformed field, unless its affected
// box is empty (the surface and its normals would not change: a contact declared between
// patches that do not touch costs nothing beyond the build). `trees` must be the
// undeformed trees of `patches` (BuildPatchOctree, same order); they are used to measure
// the zone widths before any patch is changed. Reports a warning (and builds no bulge) when
// the width cannot be measured (the measuring ray finds no opponent surface).
std::vector<DeformedPatch> ApplyContacts(const std::vector<FieldTerm>& terms,
                                         const std::vector<ContactPair>& contacts,
                                         const std::vector<Propagation>& propagations,
                                         double threshold, const OctreeSettings& settings,
                                         std::vector<Patch>& patches, std::vector<LGOctree>& trees);

}  // namespace rs
