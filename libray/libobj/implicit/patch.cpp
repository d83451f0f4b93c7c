#include "libobj/implicit/patch.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <variant>

namespace rs {

namespace {

bool BoxesOverlap(const Bounds3& a, const Bounds3& b) {
    return !Intersection(a, b).IsEmpty();
}

}  // namespace

Patch::Patch(const Field& object, std::vector<int> members)
    : field_(object.Subset(std::move(members))),
      box_(object.TermSupport(field_.Rows().front())) {}

Patch::Predominance Patch::PredominanceAt(const Vec3& p, double uncertainty) const {
    const std::vector<int>& members = field_.Rows();
    const int ownIndex = members.front();
    const double own = field_.TermValue(ownIndex, p);
    Predominance result = Predominance::Strict;
    double ownLipschitz = -1;  // computed on first need: most points have no close rival
    for (size_t j = 1; j < members.size(); ++j) {
        const double other = field_.TermValue(members[j], p);
        if (other < own || (other == own && members[j] > ownIndex)) continue;
        // An exact tie keeps its rule (the lowest index wins), so a point computed on a
        // seam still belongs to one patch; only a strictly larger rival is weighed.
        if (other == own || !(uncertainty > 0)) return Predominance::None;
        if (ownLipschitz < 0) ownLipschitz = field_.TermLipschitz(ownIndex);
        const double slack = (ownLipschitz + field_.TermLipschitz(members[j])) *
                                 uncertainty +
                             kValueRounding * (std::abs(other) + std::abs(own));
        if (other - own > slack) return Predominance::None;
        result = Predominance::Near;
    }
    return result;
}

bool Patch::MayHoldRoot(const Ray& ray, double tMin, double tMax) const {
    // A moving skeleton stays within its reach of the reference one: that test first (no
    // term to make), then, for the patches passing it, at the ray's time when one is set.
    const double moved = field_.TermReach(Own());
    if (!MayMeetSupport(field_.Terms()[Own()], moved, ray, tMin, tMax)) return false;
    if (moved == 0 || !field_.AtRayTime()) return true;
    return MayMeetSupport(field_.TermAt(Own()), 0, ray, tMin, tMax);
}

bool Patch::SupportBall::MayMeet(const Ray& ray, double tMin, double tMax) const {
    const double a = LengthSquared(ray.dir);
    if (!(a > 0)) return true;
    // NaNs (overflow) fail every comparison below: true.
    const Vec3 oc = ray.origin - centre;
    const double radius = reach + kOriginMargin * Length(oc);
    // The closest approach to the centre, at parameter tc and squared distance d2; the
    // enlarged ball spans tc ± half.
    const double tc = -Dot(oc, ray.dir) / a;
    const double d2 = LengthSquared(ray.At(tc) - centre);
    if (d2 > radius * radius) return false;
    const double half = std::sqrt((radius * radius - d2) / a);
    return !(tc + half < tMin || tc - half > tMax);
}

std::optional<Patch::SupportBall> Patch::StaticSupportBall() const {
    if (field_.TermReach(Own()) != 0) return std::nullopt;
    const FieldTerm& own = field_.Terms()[Own()];
    const auto* point = std::get_if<PointSkeleton>(&own.skeleton);
    if (!point) return std::nullopt;
    return SupportBall{point->center, SupportReach(own, 0)};
}

double Patch::SupportReach(const FieldTerm& own, double moved) {
    return own.kernel.Radius() * (1 + kSupportMargin) + moved;
}

bool Patch::MayMeetSupport(const FieldTerm& own, double moved, const Ray& ray, double tMin,
                           double tMax) {
    const double reach = SupportReach(own, moved);
    if (const auto* point = std::get_if<PointSkeleton>(&own.skeleton)) {
        return SupportBall{point->center, reach}.MayMeet(ray, tMin, tMax);
    }
    const double a = LengthSquared(ray.dir);
    if (!(a > 0)) return true;
    if (const auto* segment = std::get_if<SegmentSkeleton>(&own.skeleton)) {
        // The distance between the ray's line and the segment: projected along the ray
        // onto the plane normal to it (a linear map), the line becomes the origin and the
        // segment the segment [qa, qb], so it is the origin's distance to [qa, qb]. An
        // inexact s only moves the point found along [qa, qb] by a rounding error.
        const Vec3 pa = segment->a - ray.origin, pb = segment->b - ray.origin;
        const Vec3 qa = pa - ray.dir * (Dot(pa, ray.dir) / a);
        const Vec3 qb = pb - ray.dir * (Dot(pb, ray.dir) / a);
        const Vec3 e = qb - qa;
        const double ee = LengthSquared(e);
        const double s = ee > 0 ? std::clamp(-Dot(qa, e) / ee, 0.0, 1.0) : 0.0;
        const double radius = reach + kOriginMargin * (Length(pa) + Length(pb));
        return !(LengthSquared(qa + e * s) > radius * radius);
    }
    return true;
}

bool Patch::ClipToOwnRegion(const Ray& ray, double uncertainty, double& t0, double& t1) const {
    if (!box_.ClipRay(ray, t0, t1)) return false;
    const FieldTerm& own = field_.Terms()[Own()];
    const auto* point = std::get_if<PointSkeleton>(&own.skeleton);
    if (!point || field_.Motion() || field_.Deformation()) return true;
    const Kernel& kernel = own.kernel;
    // Distances are measured from p0 = o + t0·d, near the box, so the squares stay small.
    const double base = t0;
    const Vec3 p0 = ray.At(base);
    const double margin =
        kSeamMargin * kernel.Radius() + uncertainty +
        kOriginMargin * (Length(ray.origin) + std::max(std::abs(t0), std::abs(t1)) *
                                                  Length(ray.dir));
    // d_own − d_j <= margin with d_own < R gives d_own² − d_j² <= margin·(2R + margin).
    const double slack = margin * (2 * kernel.Radius() + margin);
    const Vec3 fromOwn = p0 - point->center;
    const double ownSquared = LengthSquared(fromOwn);
    double lo = 0, hi = t1 - base;  // the piece as s = t − base
    if (const double a = LengthSquared(ray.dir); surfaceReach_ < kernel.Radius() && a > 0) {
        // |fromOwn + s·d|² <= reach², i.e. a·s² + 2·h·s + g <= 0 (NaNs cut nothing).
        const double reach = surfaceReach_ + margin;
        const double h = Dot(fromOwn, ray.dir), g = ownSquared - reach * reach;
        const double discriminant = h * h - a * g;
        if (discriminant < 0) return false;
        const double root = std::sqrt(discriminant);
        lo = std::max(lo, (-h - root) / a);
        hi = std::min(hi, (-h + root) / a);
        if (!(lo <= hi)) return false;
    }
    const std::vector<int>& members = field_.Rows();
    for (size_t k = 1; k < members.size(); ++k) {
        const FieldTerm& other = field_.Terms()[members[k]];
        const auto* rival = std::get_if<PointSkeleton>(&other.skeleton);
        if (!rival || other.weight != own.weight || other.kernel != kernel) continue;
        // d_own(s)² − d_j(s)² = a·s + b along the ray: keep a·s + b <= slack.
        const double a = 2 * Dot(ray.dir, rival->center - point->center);
        const double b = ownSquared - LengthSquared(p0 - rival->center) - slack;
        if (a > 0) {
            hi = std::min(hi, -b / a);
        } else if (a < 0) {
            lo = std::max(lo, -b / a);
        } else if (b > 0) {
            return false;
        }
        if (!(lo <= hi)) return false;
    }
    t0 = base + lo;
    t1 = std::min(t1, base + hi);
    return t0 <= t1;
}

// The bound. Let the own skeleton be a static point c with weight w > 0 and kernel f (f
// decreasing on [0, R), 0 beyond: Kernel::Validate), and p a point at r = |p − c| where
// the own term predominates and the patch field is at least T. Every member j's term
// c_j(p) is at most
//   - the own term w·f(r), since the own term predominates there;
//   - u_j(r) = w_j·f_j(max(0, D_j − r)) if j is a static point at distance D_j from c with
//     w_j > 0 (|p − c_j| >= D_j − r, f_j decreasing), and 0 if w_j <= 0;
// so T <= U(r) = w·f(r) + Σ_j min(w·f(r), u_j(r)). On an interval r ∈ [a, b] the own term is
// at most w·f(a) and u_j at most u_j(b), so U <= B(a, b) = w·f(a) + Σ_j min(w·f(a), u_j(b))
// there, and where B(a, b) < T no point of the solid's own part has r in [a, b]. The reach
// is the upper end b left after excluding such intervals from the outside in: [0, R] in
// steps of R/32 down to the first one not excluded, then its upper halves while they are
// (10 halvings: R/2^15 above the crossing of B). U is not monotone (u_j grows with r), so
// only intervals beyond every non-excluded one are dropped. Rounding: the distances D_j are
// shortened by 10⁻⁹ of the coordinates and B is compared with T less 10⁻⁹ of it, both far
// beyond the few ulps of their computation.
void Patch::LimitToSurface(double threshold) {
    const FieldTerm& own = field_.Terms()[Own()];
    const auto* point = std::get_if<PointSkeleton>(&own.skeleton);
    if (!point || field_.Motion() || field_.Deformation() || !(own.weight > 0) ||
        !(threshold > 0)) {
        return;
    }
    // The members that may add to the sum within R of c, by the distance `start` from c
    // beyond which each does (D_j − R_j for a point: |p − c_j| >= D_j − r >= R_j below it).
    struct Rival {
        const Kernel* kernel;  // null: not a point, bounded by the own term only
        double weight, distance, start;
        bool dominates;  // w_j·f_j(s) >= w·f(s) for every s: same kernel, w_j >= w
    };
    const double radius = own.kernel.Radius();
    thread_local std::vector<Rival> rivals;  // reused: no allocation per patch
    rivals.clear();
    const std::vector<int>& members = field_.Rows();
    for (size_t k = 1; k < members.size(); ++k) {
        const FieldTerm& other = field_.Terms()[members[k]];
        if (!(other.weight > 0)) continue;  // its term is at most 0
        const auto* centre = std::get_if<PointSkeleton>(&other.skeleton);
        if (!centre) {
            rivals.push_back({nullptr, 0, 0, -std::numeric_limits<double>::infinity(), false});
            continue;
        }
        const double rounding =
            kOriginMargin * (Length(point->center) + Length(centre->center));
        const double distance =
            std::max(0.0, Length(centre->center - point->center) - rounding);
        const double start = distance - other.kernel.Radius();
        if (!(start < radius)) continue;  // adds nothing within R
        rivals.push_back({&other.kernel, other.weight, distance, start,
                          other.kernel == own.kernel && other.weight >= own.weight});
    }
    std::sort(rivals.begin(), rivals.end(),
              [](const Rival& x, const Rival& y) { return x.start < y.start; });
    const double target = threshold * (1 - kOriginMargin);
    auto excluded = [&](double a, double b) {
        const double ownMost = own.weight * own.kernel.Value(a);
        double most = ownMost;
        for (const Rival& j : rivals) {
            if (most >= target) return false;
            if (!(j.start < b)) break;  // this one and the rest add 0 on [a, b]
            const double nearest = std::max(0.0, j.distance - b);
            most += !j.kernel || (j.dominates && nearest <= a)
                        ? ownMost
                        : std::min(ownMost, j.weight * j.kernel->Value(nearest));
        }
        return most < target;
    };
    constexpr int kSteps = 32, kHalvings = 10;
    double hi = radius;
    int step = kSteps;
    while (step > 0 && excluded(radius * (step - 1) / kSteps, hi)) {
        --step;
        hi = radius * step / kSteps;
    }
    if (step > 0) {
        double lo = radius * (step - 1) / kSteps;
        for (int i = 0; i < kHalvings; ++i) {
            const double mid = 0.5 * (lo + hi);
            (excluded(mid, hi) ? hi : lo) = mid;
        }
    }
    surfaceReach_ = hi;
}

// The automatic neighbour candidates of every term: a uniform grid of cell edge W per axis,
// W the largest support extent along that axis, each support box filed under the cell of
// its low corner. Two boxes overlap only if their low corners differ by at most W per axis,
// i.e. their cells are equal or adjacent, so the 27 cells around a box's own hold every box
// it may overlap: O(n·k) for k boxes per cell neighbourhood instead of all n² pairs. The
// occupied cells are found through an open-addressing hash of their coordinates.
class AutomaticNeighbours::Grid {
  public:
    explicit Grid(const Field& object) {
        const int n = static_cast<int>(object.Terms().size());
        const double inf = std::numeric_limits<double>::infinity();
        origin_ = {inf, inf, inf};
        for (int i = 0; i < n; ++i) {
            const Bounds3& b = object.TermSupport(i);
            if (b.IsEmpty()) continue;
            width_ = Max(width_, b.hi - b.lo);
            origin_ = Min(origin_, b.lo);
        }
        std::vector<std::pair<Cell, int>> filed;
        filed.reserve(n);
        for (int i = 0; i < n; ++i) {
            const Bounds3& b = object.TermSupport(i);
            if (!b.IsEmpty()) filed.emplace_back(CellOf(b.lo), i);
        }
        // By cell, then term (coordinates compared one by one: std::array's operators call
        // memcmp, which showed in profiles at a million terms).
        std::sort(filed.begin(), filed.end(), [](const auto& a, const auto& b) {
            for (int k = 0; k < 3; ++k) {
                if (a.first[k] != b.first[k]) return a.first[k] < b.first[k];
            }
            return a.second < b.second;
        });
        members_.reserve(filed.size());
        for (size_t k = 0; k < filed.size(); ++k) {
            if (k == 0 || !SameCell(filed[k].first, filed[k - 1].first)) {
                ranges_.push_back({filed[k].first, static_cast<int>(k), 0});
            }
            members_.push_back(filed[k].second);
            ranges_.back().end = static_cast<int>(k) + 1;
        }
        size_t capacity = 16;
        while (capacity < 2 * ranges_.size()) capacity *= 2;
        slots_.assign(capacity, -1);
        for (size_t r = 0; r < ranges_.size(); ++r) {
            size_t slot = Hash(ranges_[r].cell) & (capacity - 1);
            while (slots_[slot] >= 0) slot = (slot + 1) & (capacity - 1);
            slots_[slot] = static_cast<int>(r);
        }
    }

    // Calls visit(j) for every term j filed in the 27 cells around the cell of `lo`.
    template <class Visit>
    void ForEachNear(const Vec3& lo, Visit&& visit) const {
        const Cell c = CellOf(lo);
        for (long long dx = -1; dx <= 1; ++dx) {
            for (long long dy = -1; dy <= 1; ++dy) {
                for (long long dz = -1; dz <= 1; ++dz) {
                    const Range* range = Find({c[0] + dx, c[1] + dy, c[2] + dz});
                    if (!range) continue;
                    for (int k = range->begin; k < range->end; ++k) visit(members_[k]);
                }
            }
        }
    }

  private:
    using Cell = std::array<long long, 3>;
    struct Range {
        Cell cell;
        int begin, end;  // members_[begin, end) lie in the cell
    };

    // Cell coordinates are clamped to ±2^60, so that they and their neighbours' keys stay
    // integers for supports of absurd spread (coordinates of 1e64 and beyond): clamping is
    // monotone, so boxes in equal or adjacent cells stay so. An axis whose widest support is
    // not finite has one cell, as does one of zero width; a NaN quotient (infinite supports)
    // goes to cell 0.
    Cell CellOf(const Vec3& p) const {
        constexpr double kMaxCell = 0x1p60;
        Cell c{};
        for (int a = 0; a < 3; ++a) {
            if (!(width_[a] > 0 && std::isfinite(width_[a]))) continue;
            const double q = std::floor((p[a] - origin_[a]) / width_[a]);
            c[a] = std::isnan(q) ? 0 : static_cast<long long>(std::clamp(q, -kMaxCell, kMaxCell));
        }
        return c;
    }
    static bool SameCell(const Cell& a, const Cell& b) {
        return a[0] == b[0] && a[1] == b[1] && a[2] == b[2];
    }
    static size_t Hash(const Cell& c) {
        uint64_t h = 0x9e3779b97f4a7c15ull;
        for (long long v : c) {
            h ^= static_cast<uint64_t>(v) + 0x9e3779b97f4a7c15ull + (h << 6) + (h >> 2);
            h *= 0xbf58476d1ce4e5b9ull;
        }
        return static_cast<size_t>(h ^ (h >> 31));
    }
    const Range* Find(const Cell& c) const {
        for (size_t slot = Hash(c) & (slots_.size() - 1);; slot = (slot + 1) & (slots_.size() - 1)) {
            const int r = slots_[slot];
            if (r < 0) return nullptr;
            if (SameCell(ranges_[r].cell, c)) return &ranges_[r];
        }
    }

    Vec3 width_{0, 0, 0}, origin_;
    std::vector<int> members_;  // term indices, grouped by cell
    std::vector<Range> ranges_;
    std::vector<int> slots_;  // indices into ranges_, −1 empty; at most half full
};

namespace {

// Symmetric pairs as a sorted list of (low, high), for binary search.
std::vector<std::pair<int, int>> SortedPairs(const std::vector<std::pair<int, int>>& pairs) {
    std::vector<std::pair<int, int>> sorted;
    sorted.reserve(pairs.size());
    for (auto [a, b] : pairs) sorted.emplace_back(std::min(a, b), std::max(a, b));
    std::sort(sorted.begin(), sorted.end());
    return sorted;
}

// Term i's patch members: i, then every candidate (each visited by forEachCandidate, in any
// order, repeats allowed) whose support box overlaps i's and that is not paired with i in
// `separate` (sorted), in increasing term order (the order of the patch field's sum), once.
template <class ForEachCandidate>
std::vector<int> CollectMembers(const Field& object, int i,
                                const std::vector<std::pair<int, int>>& separate,
                                ForEachCandidate&& forEachCandidate) {
    thread_local std::vector<int> near;  // reused: one allocation per list, its own
    near.clear();
    const Bounds3& own = object.TermSupport(i);
    forEachCandidate([&](int j) {
        if (j != i && BoxesOverlap(own, object.TermSupport(j)) &&
            !std::binary_search(separate.begin(), separate.end(),
                                std::pair<int, int>(std::min(i, j), std::max(i, j)))) {
            near.push_back(j);
        }
    });
    std::sort(near.begin(), near.end());
    near.erase(std::unique(near.begin(), near.end()), near.end());
    std::vector<int> members;
    members.reserve(near.size() + 1);
    members.push_back(i);
    members.insert(members.end(), near.begin(), near.end());
    return members;
}

}  // namespace

AutomaticNeighbours::AutomaticNeighbours(const Field& object)
    : object_(object), grid_(std::make_unique<const Grid>(object)) {}

AutomaticNeighbours::~AutomaticNeighbours() = default;

std::vector<int> AutomaticNeighbours::Members(
    int i, const std::vector<std::pair<int, int>>& separate) const {
    return CollectMembers(object_, i, separate, [&](auto&& visit) {
        const Bounds3& own = object_.TermSupport(i);
        if (!own.IsEmpty()) grid_->ForEachNear(own.lo, visit);
    });
}

std::vector<Patch> BuildPatches(const Field& object, BlendMode mode,
                                const std::vector<std::pair<int, int>>& blendPairs,
                                const std::vector<std::pair<int, int>>& separatePairs) {
    const std::vector<FieldTerm>& terms = object.Terms();
    const int n = static_cast<int>(terms.size());
    const std::vector<std::pair<int, int>> separate = SortedPairs(separatePairs);
    std::vector<Patch> patches;
    if (mode == BlendMode::Automatic) {
        const AutomaticNeighbours neighbours(object);
        for (int i = 0; i < n; ++i) {
            if (terms[i].weight > 0) patches.emplace_back(object, neighbours.Members(i, separate));
        }
        return patches;
    }
    // Explicit mode: the declared partners of each term.
    std::vector<std::vector<int>> declared(n);
    for (auto [a, b] : blendPairs) {
        if (a < 0 || b < 0 || a >= n || b >= n || a == b) continue;
        declared[a].push_back(b);
        declared[b].push_back(a);
    }
    for (int i = 0; i < n; ++i) {
        if (!(terms[i].weight > 0)) continue;
        patches.emplace_back(object, CollectMembers(object, i, separate, [&](auto&& visit) {
                                 for (int j : declared[i]) visit(j);
                             }));
    }
    return patches;
}

}  // namespace rs
