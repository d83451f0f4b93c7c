#include "libobj/implicit/contact.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "libcommon/error.h"
#include "libcommon/stats.h"

namespace rs {

namespace {

// δ = w·q(s) on the bulge piece, s = u/w, with
//   q(s)   = s(1 − s)²(1 + 2ηs) = s + (2η − 2)s² + (1 − 4η)s³ + 2ηs⁴,
//   q'(s)  = 1 + (4η − 4)s + (3 − 12η)s² + 8ηs³      (δ' = q'),
//   q''(s) = (4η − 4) + (6 − 24η)s + 24ηs²            (δ'' = q''/w).
double Q(double eta, double s) { return s * (1 - s) * (1 - s) * (1 + 2 * eta * s); }
double Q1(double eta, double s) {
    return 1 + s * ((4 * eta - 4) + s * ((3 - 12 * eta) + s * 8 * eta));
}
double Q2(double eta, double s) { return (4 * eta - 4) + s * ((6 - 24 * eta) + s * 24 * eta); }

// Build counters; an ImplicitSurface reports them per object as "preprocessing contact ...".
struct ContactCounters {
    CounterId deformed = RegisterCounter("Implicit contact deformed patches");
    CounterId bulges = RegisterCounter("Implicit contact bulges");
};

const ContactCounters& Counters() {
    static const ContactCounters counters;
    return counters;
}

// The zone and affected boxes stop subdividing at this depth (cells of 1/32 of the
// starting box per axis).
constexpr int kZoneDepth = 5;

// Child i of a box split at its centre (bit 0: upper x half, bit 1: y, bit 2: z).
Bounds3 Octant(const Bounds3& box, int i) {
    Vec3 c = box.Center();
    return Bounds3(
        Vec3{(i & 1) ? c.x : box.lo.x, (i & 2) ? c.y : box.lo.y, (i & 4) ? c.z : box.lo.z},
        Vec3{(i & 1) ? box.hi.x : c.x, (i & 2) ? box.hi.y : c.y, (i & 4) ? box.hi.z : c.z});
}

}  // namespace

BulgeProfile::BulgeProfile(double width, double height) : width_(width), height_(height) {
    // Root in (0, 1) of 8ηs² + bs − 1 (b = 3 − 4η), in the cancellation-free form
    // 2/(b + sqrt(b² + 32η)); 1/3 at η = 0.
    double b = 3 - 4 * height_;
    peakS_ = 2 / (b + std::sqrt(b * b + 32 * height_));
}

double BulgeProfile::Value(double u) const {
    if (u <= 0) return u;
    if (u >= width_) return 0;
    return width_ * Q(height_, u / width_);
}

double BulgeProfile::Derivative(double u) const {
    if (u <= 0) return 1;
    if (u >= width_) return 0;
    return Q1(height_, u / width_);
}

double BulgeProfile::SecondDerivative(double u) const {
    if (u <= 0 || u >= width_) return 0;
    return Q2(height_, u / width_) / width_;
}

ProfileBounds BulgeProfile::Bounds(double u0, double u1) const {
    ProfileBounds pb;
    // δ increases up to its peak and does not increase after it: the minimum is at an end,
    // the maximum at the peak when the interval contains it.
    pb.valueMin = std::min(Value(u0), Value(u1));
    pb.valueMax = Value(std::clamp(PeakU(), u0, u1));
    if (u0 <= 0) pb.maxSlope = 1;  // the compression piece, δ' = 1, δ'' = 0
    if (width_ == 0 && u0 <= 0 && u1 >= 0) {
        // min(u, 0) has a kink at 0: no second-derivative bound across it.
        pb.maxSecond = std::numeric_limits<double>::infinity();
    }
    double lo = std::max(u0, 0.0), hi = std::min(u1, width_);
    if (width_ > 0 && lo <= hi) {
        // Bulge piece on the closed [lo, hi] (its one-sided limits at 0 and w included).
        double sLo = lo / width_, sHi = hi / width_;
        const double eta = height_;
        auto consider = [&](double s) {
            pb.maxSlope = std::max(pb.maxSlope, std::abs(Q1(eta, s)));
            pb.maxSecond = std::max(pb.maxSecond, std::abs(Q2(eta, s)) / width_);
        };
        consider(sLo);
        consider(sHi);
        // Interior extrema of q' are roots of q''; of q'', its vertex.
        double a2 = 24 * eta, a1 = 6 - 24 * eta, a0 = 4 * eta - 4;
        double roots[3];
        int n = 0;
        if (a2 == 0) {
            roots[n++] = -a0 / a1;
        } else {
            double disc = std::sqrt(a1 * a1 - 4 * a2 * a0);  // 36 + 96η + 192η² > 0
            roots[n++] = (-a1 - disc) / (2 * a2);
            roots[n++] = (-a1 + disc) / (2 * a2);
            roots[n++] = -a1 / (2 * a2);
        }
        for (int i = 0; i < n; ++i) {
            if (roots[i] > sLo && roots[i] < sHi) consider(roots[i]);
        }
    }
    return pb;
}

ContactDeformation::ContactDeformation(Field opponent, double threshold, BulgeProfile profile)
    : opponent_(std::move(opponent)), threshold_(threshold), profile_(profile) {
    Bounds3 support = opponent_.SupportBounds();
    if (!support.IsEmpty()) GrowZone(support, 0);
}

// Adds to zone_ the cells of `box` where O may exceed T − w (the value-range bound is sound,
// so the cells left out have O <= T − w everywhere, where δ = 0).
void ContactDeformation::GrowZone(const Bounds3& box, int depth) {
    const double edge = threshold_ - profile_.Width();
    FieldBound fb = opponent_.Bound(box);
    if (fb.valueMax <= edge) return;
    if (fb.valueMin > edge || depth == kZoneDepth) {
        zone_.Extend(box);
        return;
    }
    for (int i = 0; i < 8; ++i) GrowZone(Octant(box, i), depth + 1);
}

double ContactDeformation::Value(const Vec3& p) const {
    if (!zone_.Contains(p)) return 0;
    return profile_.Value(threshold_ - opponent_.Value(p));
}

Vec3 ContactDeformation::Gradient(const Vec3& p) const {
    if (!zone_.Contains(p)) return {};
    double slope = profile_.Derivative(threshold_ - opponent_.Value(p));
    if (slope == 0) return {};
    return opponent_.Gradient(p) * -slope;
}

FieldBound ContactDeformation::Bound(const Bounds3& box) const {
    FieldBound out;
    out.minDistance = std::numeric_limits<double>::infinity();
    if (Intersection(box, zone_).IsEmpty()) return out;
    FieldBound ob = opponent_.Bound(box);
    ProfileBounds pb = profile_.Bounds(threshold_ - ob.valueMax, threshold_ - ob.valueMin);
    out.valueMin = pb.valueMin;
    out.valueMax = pb.valueMax;
    // Products written so that a zero factor wins over an infinite one (0·∞ would be NaN).
    auto times = [](double a, double b) { return a == 0 || b == 0 ? 0.0 : a * b; };
    out.L = times(pb.maxSlope, ob.L);
    out.G = times(pb.maxSecond, ob.L * ob.L) + times(pb.maxSlope, ob.G);
    return out;
}

namespace {

// The global term indices in the member lists of `patchIndices`, each once, ascending.
std::vector<int> UnionOfMembers(const std::vector<Patch>& patches,
                                const std::vector<int>& patchIndices) {
    std::vector<int> out;
    for (int p : patchIndices) {
        out.insert(out.end(), patches[p].Members().begin(), patches[p].Members().end());
    }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
}

// The zone width in field units for patch `self` against `opponents` (see the header), or
// nothing when it cannot be measured; `interpenetrates` tells whether the ray saw the
// volumes overlap.
struct WidthMeasure {
    bool measured = false;
    bool interpenetrates = false;
    double fieldWidth = 0;
};

WidthMeasure MeasureWidth(const std::vector<FieldTerm>& terms, const std::vector<Patch>& patches,
                          const std::vector<LGOctree>& trees, int self,
                          const std::vector<int>& opponents, const Field& opponentField,
                          double threshold, double width) {
    WidthMeasure m;
    const Skeleton& own = terms[patches[self].Own()].skeleton;
    Bounds3 targets;
    for (int o : opponents) targets.Extend(SkeletonBounds(terms[patches[o].Own()].skeleton));
    Vec3 from;
    SkeletonDistance(own, targets.Center(), from);
    Vec3 to;
    double nearest = std::numeric_limits<double>::infinity();
    for (int o : opponents) {
        Vec3 c;
        double d = SkeletonDistance(terms[patches[o].Own()].skeleton, from, c);
        if (d < nearest) {
            nearest = d;
            to = c;
        }
    }
    if (!(nearest > 0)) return m;
    // Along the line from A's skeleton point towards the opponent's, or away from it when A's
    // skeleton point already lies inside the opponent (deep contact): either way the ray
    // meets the opponent's surface at `entry`, and the zone is measured on A's side of it.
    const bool deep = opponentField.Value(from) >= threshold;
    Ray ray{from, (deep ? from - to : to - from) / nearest};
    const double far = std::numeric_limits<double>::infinity();
    double entry = far;
    for (int o : opponents) {
        std::optional<double> t = PatchFirstRoot(patches[o], trees[o], ray, 0, entry);
        if (t) entry = *t;
    }
    if (entry == far) return m;
    m.measured = true;
    double w;
    if (deep) {
        m.interpenetrates = true;
        w = threshold - opponentField.Value(ray.At(entry + width));
    } else {
        std::optional<double> exit = PatchFirstRoot(patches[self], trees[self], ray, 0, far);
        m.interpenetrates = exit && entry < *exit;
        w = threshold - opponentField.Value(ray.At(entry - width));
    }
    m.fieldWidth = std::clamp(w, 0.0, threshold);
    return m;
}

// Adds to `out` the cells of `box` where both the opponent may exceed T − w and the own
// undeformed field may exceed T − peak (value-range bounds, so no such point is left out).
void GrowAffected(const Field& own, const Field& opponent, double ownEdge, double opponentEdge,
                  const Bounds3& box, int depth, Bounds3& out) {
    FieldBound ob = opponent.Bound(box);
    if (ob.valueMax <= opponentEdge) return;
    FieldBound fb = own.Bound(box);
    if (fb.valueMax <= ownEdge) return;
    if (depth == kZoneDepth) {
        out.Extend(box);
        return;
    }
    for (int i = 0; i < 8; ++i) {
        GrowAffected(own, opponent, ownEdge, opponentEdge, Octant(box, i), depth + 1, out);
    }
}

}  // namespace

namespace {

// Whether p lies inside patch a's undeformed volume and inside b's.
bool InsideBoth(const Patch& a, const Patch& b, double threshold, const Vec3& p) {
    return a.GetField().Value(p) > threshold && b.GetField().Value(p) > threshold &&
           a.Predominates(p) && b.Predominates(p);
}

// False only when the patch's own term predominates nowhere in the box: some neighbour's
// term exceeds it at every point (the lowest value of that term's range over the box is
// above the highest of the own term's; TermRange holds at every time of a moving field).
bool MayPredominateIn(const Patch& patch, const Bounds3& box) {
    const Field& field = patch.GetField();
    double ownLo, ownHi;
    field.TermRange(patch.Own(), box, ownLo, ownHi);
    for (const int j : patch.Members()) {
        if (j == patch.Own()) continue;
        double lo, hi;
        field.TermRange(j, box, lo, hi);
        if (lo > ownHi) return false;
    }
    return true;
}

// VolumesInterpenetrate below `box` at `depth`. A cell is cleared where either field stays
// <= T or either own term cannot predominate (inside the volume of a neighbour that both
// patches blend with, say).
bool BothInside(const Patch& a, const Patch& b, double threshold, const Bounds3& box,
                int depth) {
    if (!(a.GetField().Bound(box).valueMax > threshold)) return false;
    if (!(b.GetField().Bound(box).valueMax > threshold)) return false;
    if (!MayPredominateIn(a, box) || !MayPredominateIn(b, box)) return false;
    if (InsideBoth(a, b, threshold, box.Center())) return true;
    if (depth == kInterpenetrationDepth) return false;
    for (int i = 0; i < 8; ++i) {
        if (BothInside(a, b, threshold, Octant(box, i), depth + 1)) return true;
    }
    return false;
}

bool IsMember(const Patch& patch, int term) {
    const std::vector<int>& m = patch.Members();
    return std::find(m.begin(), m.end(), term) != m.end();
}

}  // namespace

bool VolumesInterpenetrate(const Patch& a, const Patch& b, double threshold) {
    const Bounds3 overlap = Intersection(a.Box(), b.Box());
    if (overlap.IsEmpty()) return false;
    return BothInside(a, b, threshold, overlap, 0);
}

std::vector<ContactPair> AutomaticContacts(const std::vector<Patch>& patches, double threshold) {
    // Sweep along x: after sorting by the boxes' low x, the boxes that may overlap box i's
    // follow it until one starts beyond its high x.
    std::vector<int> order(patches.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
    std::sort(order.begin(), order.end(), [&](int p, int q) {
        return patches[p].Box().lo.x < patches[q].Box().lo.x;
    });
    std::vector<ContactPair> pairs;
    for (size_t i = 0; i < order.size(); ++i) {
        const Patch& pa = patches[order[i]];
        for (size_t j = i + 1; j < order.size(); ++j) {
            const Patch& pb = patches[order[j]];
            if (pb.Box().lo.x > pa.Box().hi.x) break;
            if (IsMember(pa, pb.Own()) || IsMember(pb, pa.Own())) continue;
            if (!VolumesInterpenetrate(pa, pb, threshold)) continue;
            pairs.push_back({std::min(pa.Own(), pb.Own()), std::max(pa.Own(), pb.Own())});
        }
    }
    std::sort(pairs.begin(), pairs.end());
    return pairs;
}

std::vector<ContactPair> UndeclaredContacts(const std::vector<ContactPair>& found,
                                            const std::vector<ContactPair>& declared) {
    std::vector<ContactPair> out;
    for (const ContactPair& c : found) {
        const bool named = std::any_of(declared.begin(), declared.end(), [&](const ContactPair& d) {
            return (d.a == c.a && d.b == c.b) || (d.a == c.b && d.b == c.a);
        });
        if (!named) out.push_back(c);
    }
    return out;
}

std::vector<std::pair<int, int>> SeparatePairs(const std::vector<ContactPair>& contacts) {
    std::vector<std::pair<int, int>> pairs;
    pairs.reserve(contacts.size());
    for (const ContactPair& c : contacts) pairs.emplace_back(c.a, c.b);
    return pairs;
}

namespace {

// The opponents of each patch (patch indices, sorted, without repeats): the patches of the
// terms each contact pairs it with. Pairs naming a term without a patch are ignored.
std::vector<std::vector<int>> ContactOpponents(const std::vector<ContactPair>& contacts,
                                               const std::vector<Patch>& patches, int termCount) {
    std::vector<int> patchOf(termCount, -1);
    for (size_t i = 0; i < patches.size(); ++i) patchOf[patches[i].Own()] = static_cast<int>(i);
    std::vector<std::vector<int>> opponents(patches.size());
    for (const ContactPair& c : contacts) {
        if (c.a < 0 || c.b < 0 || c.a >= termCount || c.b >= termCount || c.a == c.b) continue;
        int pa = patchOf[c.a], pb = patchOf[c.b];
        if (pa < 0 || pb < 0) continue;
        opponents[pa].push_back(pb);
        opponents[pb].push_back(pa);
    }
    for (std::vector<int>& opp : opponents) {
        std::sort(opp.begin(), opp.end());
        opp.erase(std::unique(opp.begin(), opp.end()), opp.end());
    }
    return opponents;
}

// A patch's contact before it deforms: its opponents' field and its bulge profile, measured
// on the undeformed trees.
struct ContactPlan {
    DeformedPatch result;
    Field opponent;
    BulgeProfile profile;
};

ContactPlan PlanContact(const std::vector<FieldTerm>& terms,
                        const std::vector<Propagation>& propagations, double threshold,
                        const std::vector<Patch>& patches, const std::vector<LGOctree>& trees,
                        int patch, const std::vector<int>& opponents) {
    // The opponents' terms as rows of the patches' shared table: a moving field's opponent
    // moves with it (values at the ray's time, bounds over the whole interval).
    ContactPlan plan;
    plan.result.patch = patch;
    plan.opponent = patches[patch].GetField().Subset(UnionOfMembers(patches, opponents));
    const int own = patches[patch].Own();
    for (const Propagation& prop : propagations) {
        if (prop.term != own || !(prop.width > 0)) continue;
        WidthMeasure m = MeasureWidth(terms, patches, trees, patch, opponents, plan.opponent,
                                      threshold, prop.width);
        if (!m.measured) {
            Report(Severity::Warn, {},
                   "implicit contact: no propagation zone for '%s' (the line from its "
                   "skeleton to the opponent's meets no opponent surface)",
                   terms[own].name.c_str());
            continue;
        }
        plan.result.interpenetrates = m.interpenetrates;
        if (m.interpenetrates) {
            plan.result.fieldWidth = m.fieldWidth;
            plan.profile = BulgeProfile(m.fieldWidth, prop.height);
        }
    }
    return plan;
}

}  // namespace

std::vector<DeformedPatch> ApplyContacts(const std::vector<FieldTerm>& terms,
                                         const std::vector<ContactPair>& contacts,
                                         const std::vector<Propagation>& propagations,
                                         double threshold, const OctreeSettings& settings,
                                         std::vector<Patch>& patches,
                                         std::vector<LGOctree>& trees) {
    const std::vector<std::vector<int>> opponents =
        ContactOpponents(contacts, patches, static_cast<int>(terms.size()));
    // Measure every width on the undeformed trees first, then deform.
    std::vector<ContactPlan> plans;
    for (size_t i = 0; i < patches.size(); ++i) {
        if (opponents[i].empty()) continue;
        plans.push_back(PlanContact(terms, propagations, threshold, patches, trees,
                                    static_cast<int>(i), opponents[i]));
    }
    // The deformed field's G is dominated near the contact by max|δ''|·L_O², up to
    // (2 + 4η)L_O²/w: leaves must be small for the search's monotonicity test (λ < 2L/G) to
    // fire, or each span falls back to per-segment bounds. Two more levels before heuristics
    // 3 and 3bis may stop (within the declared maximum depth) paid off on the figure-7 scene
    // (bench/contact.sh, 400×400): +0/+1/+2/+3 levels gave 14.0/10.4/8.3/7.6 evaluations per
    // ray against 7.6 undeformed, for 8/8/11/32 ms of build and 1.72/1.28/1.25/1.36 times
    // the undeformed render time.
    OctreeSettings deformed = settings;
    deformed.minDepth = std::min(settings.minDepth + 2, settings.maxDepth);
    std::vector<DeformedPatch> out;
    for (ContactPlan& plan : plans) {
        const int i = plan.result.patch;
        auto deformation =
            std::make_shared<ContactDeformation>(std::move(plan.opponent), threshold, plan.profile);
        plan.result.zone = deformation->Zone();
        const BulgeProfile& profile = deformation->Profile();
        Bounds3 region = Intersection(deformation->Zone(), patches[i].Box());
        if (!region.IsEmpty()) {
            GrowAffected(patches[i].GetField(), deformation->Opponent(),
                         threshold - profile.Value(profile.PeakU()), threshold - profile.Width(),
                         region, 0, plan.result.affected);
        }
        // With no affected point the deformed and undeformed fields agree in sign over the
        // whole patch box, and the term vanishes on the surface with its gradient: the
        // surface and its normals are unchanged, so the patch keeps its undeformed field.
        plan.result.deformed = !plan.result.affected.IsEmpty();
        if (plan.result.deformed) {
            Count(Counters().deformed);
            if (profile.Width() > 0) Count(Counters().bulges);
            patches[i].Deform(std::move(deformation));
            trees[i] = BuildPatchOctree(patches[i], threshold, deformed);
        }
        out.push_back(plan.result);
    }
    return out;
}

}  // namespace rs
