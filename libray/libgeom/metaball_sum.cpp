#include "libgeom/metaball_sum.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include "libgeom/polynomial.h"

namespace rs {

namespace {

// Up to this many balls a plain loop finds the ones a ray meets faster than a structure.
constexpr size_t kLinearSearchMax = 8;

// The grid has about kCellsPerBall cells per ball, at most kMaxGridCells, and is given up
// for the hierarchy when its non-empty cells list more than kMaxMeanCellBalls balls on
// average (the balls crowd into a small part of their box, so the cells a ray crosses
// there would each cost that many tests; a few crowded cells, as where a chain coils up,
// do not count much).
constexpr double kCellsPerBall = 2;
constexpr double kMaxGridCells = 1 << 22;
constexpr double kMaxMeanCellBalls = 16;

// Boxes are registered in the cells they overlap after padding by this fraction of the
// grid's largest extent, so the cell the walk is in when the ray enters a ball always lists
// it: the walk's cell boundaries and first point are rounded by a few ulp of the ray
// origin's distance, below the padding for origins within 10⁹ grid extents (farther, the
// quartics have lost their accuracy anyway: kFieldBoundMargin).
constexpr double kGridPadding = 1e-6;

// Relative margin of the field-bound rejections in FirstRoot. An interval's quartic is
// formed from terms of size at most 81·|s| per active ball (|q_i| ≤ 1 and each of q_i's
// three terms at most 4 in size on the ball's chord), so its computed values differ from
// the true field minus T by a few hundred ulp of T + Σ|s| at most; a field bound below T by
// 10⁻⁷ of that is far outside this error and outside the solver's zero tolerance, so every
// value the solver would compute there is negative and it would report no root. The rounding
// of the interval's start point (about u·|o + t·d|, moving the field by up to 4|s|/r times
// that) stays below the margin for rays starting within some 10⁷ ball radii of the balls.
constexpr double kFieldBoundMargin = 1e-7;

// Where the ray is inside a ball's support, on one piece of it: ρ²(t) = dist2 +
// curvature·(t − tClosest)² there, about the ball's centre (piece kSphereAtCentre), its
// segment's far end (kSphereAtEnd) or its axis line (kAxis); enter and exit bound the part
// of (tMin, tMax) on the piece with ρ < r.
enum Piece { kSphereAtCentre, kAxis, kSphereAtEnd };
struct Span {
    int ball;
    Piece piece;
    double tClosest, dist2, curvature;
    double enter, exit;
};

struct Event {
    double t;
    int span;
    bool entering;
};

// Per-thread scratch of FirstRoot, sized for every span the largest sum seen can give (a
// ray takes each ball at most once: the loop and the grid walk by construction, the
// hierarchy because Traverse visits each item once, also in its fallback for rays beyond
// single precision; and a ball gives one span, a capsule up to three), so rays neither allocate nor check
// capacities. The arrays
// are left uninitialised: only their used prefixes are read, and untouched pages cost
// nothing.
struct Scratch {
    std::unique_ptr<Span[]> spans;
    std::unique_ptr<Event[]> events;  // not swept yet (in the grid walk, a min-heap on t)
    std::unique_ptr<int[]> active;    // indices into spans, in increasing ball index
    size_t capacity = 0;              // spans

    void Reserve(size_t count) {
        if (count <= capacity) return;
        spans.reset(new Span[count]);
        events.reset(new Event[2 * count]);
        active.reset(new int[count]);
        capacity = count;
    }
};

// The largest value of s·q² over [ta, tb] for a span, q = 1 − ρ²/r² ∈ [0, 1] being largest at
// the interval's point nearest to the closest approach; at most 0 for a negative strength.
double TermPeak(double strength, double radius2, const Span& span, double ta, double tb) {
    if (strength < 0) return 0;
    const double gap = span.tClosest - std::clamp(span.tClosest, ta, tb);
    const double q = 1 - (span.dist2 + span.curvature * gap * gap) / radius2;
    return strength * q * q;
}

// The component of v across the unit vector n.
Vec3 Across(const Vec3& v, const Vec3& n) { return v - n * Dot(v, n); }

// The box of a ball's sphere of influence (of both end spheres for a capsule).
Bounds3 BoxOf(const Metaball& b) {
    const Vec3 r{b.radius, b.radius, b.radius};
    Bounds3 box(b.centre - r, b.centre + r);
    box.Extend(Bounds3(b.centre + b.axis - r, b.centre + b.axis + r));
    return box;
}

}  // namespace

MetaballSum::MetaballSum(double threshold, std::span<const Metaball> balls)
    : MetaballSum(threshold, balls.size(), [balls](size_t i) { return balls[i]; }) {}

MetaballSum::MetaballSum(double threshold, size_t count,
                         const std::function<Metaball(size_t)>& ball)
    : threshold_(threshold) {
    balls_.reserve(count);
    for (size_t i = 0; i < count; ++i) {
        const Metaball b = ball(i);
        const double r2 = b.radius * b.radius, length2 = LengthSquared(b.axis);
        const Vec3 unit = length2 > 0 ? b.axis / std::sqrt(length2) : Vec3{0, 0, 0};
        balls_.push_back({b.centre, r2, 1 / r2, b.strength, b.axis, length2, unit});
        bounds_.Extend(BoxOf(b));
        maxSpans_ += length2 > 0 ? 3 : 1;
    }
    if (count <= kLinearSearchMax) return;
    const auto box = [&ball](size_t i) { return BoxOf(ball(i)); };
    BuildGrid(count, box);
    if (!grid_.IsEmpty()) return;
    std::vector<Bounds3> boxes;
    boxes.reserve(count);
    for (size_t i = 0; i < count; ++i) boxes.push_back(box(i));
    hierarchy_.Build(boxes);
}

int MetaballSum::Grid::CellOf(double x, int axis) const {
    const double f = std::floor((x - lo[axis]) / cellSize[axis]);
    if (!(f >= 0)) return 0;  // also NaN
    return static_cast<int>(std::min(f, static_cast<double>(n[axis] - 1)));
}

void MetaballSum::BuildGrid(size_t count, const std::function<Bounds3(size_t)>& box) {
    Grid grid;
    const Vec3 extent = bounds_.Extent();
    const double largest = std::max({extent.x, extent.y, extent.z});
    // Cells as near cubes: flat directions get one cell.
    const double cells = std::min(kCellsPerBall * static_cast<double>(count), kMaxGridCells);
    double volume = 1;
    int axes = 0;
    for (int a = 0; a < 3; ++a) {
        if (extent[a] > 1e-6 * largest) {
            volume *= extent[a];
            ++axes;
        }
    }
    const double edge = std::pow(volume / cells, 1.0 / axes);
    if (!std::isfinite(largest) || !(edge > 0) || !std::isfinite(edge)) return;  // hierarchy
    for (int a = 0; a < 3; ++a) {
        grid.n[a] = extent[a] > 1e-6 * largest
                        ? static_cast<int>(std::clamp(extent[a] / edge, 1.0, 1024.0))
                        : 1;
        grid.cellSize[a] = std::max(extent[a], 1e-300) / grid.n[a];
    }
    grid.lo = bounds_.lo;
    const double pad = kGridPadding * largest;
    // Count, then fill (compressed rows, balls in increasing index per cell).
    const size_t cellCount = static_cast<size_t>(grid.n[0]) * grid.n[1] * grid.n[2];
    grid.cellStart.assign(cellCount + 1, 0);
    const auto forCells = [&](const Bounds3& b, auto&& visit) {
        int lo[3], hi[3];
        for (int a = 0; a < 3; ++a) {
            lo[a] = grid.CellOf(b.lo[a] - pad, a);
            hi[a] = grid.CellOf(b.hi[a] + pad, a);
        }
        for (int z = lo[2]; z <= hi[2]; ++z)
            for (int y = lo[1]; y <= hi[1]; ++y)
                for (int x = lo[0]; x <= hi[0]; ++x) visit(grid.Index(x, y, z));
    };
    for (size_t i = 0; i < count; ++i) forCells(box(i), [&](int c) { ++grid.cellStart[c + 1]; });
    size_t nonEmpty = 0;
    for (size_t c = 0; c < cellCount; ++c) {
        nonEmpty += grid.cellStart[c + 1] > 0;
        grid.cellStart[c + 1] += grid.cellStart[c];
    }
    if (grid.cellStart[cellCount] > kMaxMeanCellBalls * static_cast<double>(nonEmpty)) {
        return;  // crowded: the hierarchy instead
    }
    grid.cellBalls.resize(grid.cellStart[cellCount]);
    std::vector<uint32_t, LargeBufferAllocator<uint32_t>> fill(grid.cellStart.begin(),
                                                               grid.cellStart.end() - 1);
    for (size_t i = 0; i < count; ++i) {
        forCells(box(i),
                 [&](int c) { grid.cellBalls[fill[c]++] = static_cast<uint32_t>(i); });
    }
    grid_ = std::move(grid);
}

template <class Visit>
void MetaballSum::ForBallsAt(const Vec3& p, Visit&& visit) const {
    if (!grid_.IsEmpty()) {
        if (!bounds_.Contains(p)) return;
        const int c = grid_.Index(grid_.CellOf(p.x, 0), grid_.CellOf(p.y, 1), grid_.CellOf(p.z, 2));
        for (uint32_t k = grid_.cellStart[c]; k < grid_.cellStart[c + 1]; ++k) {
            visit(static_cast<int>(grid_.cellBalls[k]));
        }
        return;
    }
    if (hierarchy_.IsEmpty()) {
        for (size_t i = 0; i < balls_.size(); ++i) visit(static_cast<int>(i));
        return;
    }
    thread_local std::vector<int> near;
    near.clear();
    hierarchy_.VisitContaining(p, [&](int i) { near.push_back(i); });
    std::sort(near.begin(), near.end());
    for (int i : near) visit(i);
}

std::optional<double> MetaballSum::FirstRoot(const Ray& ray, double tMin, double tMax,
                                             int* quarticsSolved) const {
    constexpr double kInfinity = std::numeric_limits<double>::infinity();
    if (quarticsSolved) *quarticsSolved = 0;
    const double dd = LengthSquared(ray.dir);
    if (!(dd > 0)) return std::nullopt;
    thread_local Scratch scratch;
    scratch.Reserve(maxSpans_);
    Span* const spans = scratch.spans.get();
    Event* const pending = scratch.events.get();
    int* const active = scratch.active.get();
    int spanCount = 0, pendingCount = 0, activeCount = 0;
    const auto later = [](const Event& a, const Event& b) { return a.t > b.t; };
    double peakSum = 0, strengthSum = 0;  // over the balls met

    // Calls emit(span) for each piece of (tMin, tMax) inside ball i's support.
    const auto spansOf = [&](int i, auto&& emit) {
        const Ball& b = balls_[i];
        // The span about a centre c on [lo, hi]: |o + t d − c|² = r² solved around the
        // closest approach for stability.
        const auto sphere = [&](Piece piece, const Vec3& c, double lo, double hi) {
            const Vec3 oc = ray.origin - c;
            const double tClosest = -Dot(oc, ray.dir) / dd;
            const double dist2 = LengthSquared(oc + ray.dir * tClosest);
            const double h2 = (b.radius2 - dist2) / dd;
            if (h2 <= 0) return;
            const double h = std::sqrt(h2);
            const Span span{i, piece, tClosest, dist2, dd, std::max(tClosest - h, lo),
                            std::min(tClosest + h, hi)};
            if (span.enter < span.exit) emit(span);
        };
        if (b.axisLength2 == 0) {
            sphere(kSphereAtCentre, b.centre, tMin, tMax);
            return;
        }
        // The axis parameter of the ray's projection, u(t) = u0 + u1·t (0 at the centre, 1
        // at the far end), splits the ray into the pieces u < 0, 0 <= u <= 1, u > 1.
        const double u0 = Dot(ray.origin - b.centre, b.axis) / b.axisLength2;
        const double u1 = Dot(ray.dir, b.axis) / b.axisLength2;
        double atCentre = -kInfinity, atEnd = kInfinity;  // t where u = 0 and u = 1
        if (u1 != 0) {
            atCentre = -u0 / u1;
            atEnd = (1 - u0) / u1;
        } else if (u0 < 0 || u0 > 1) {
            sphere(u0 < 0 ? kSphereAtCentre : kSphereAtEnd,
                   u0 < 0 ? b.centre : b.centre + b.axis, tMin, tMax);
            return;
        }
        const double lo = std::max(std::min(atCentre, atEnd), tMin);
        const double hi = std::min(std::max(atCentre, atEnd), tMax);
        const bool forward = u1 >= 0;  // the ray meets the centre's cap first
        // Cap before the axis piece, axis piece, cap after.
        sphere(forward ? kSphereAtCentre : kSphereAtEnd,
               forward ? b.centre : b.centre + b.axis, tMin, std::min(lo, tMax));
        if (lo < hi) {
            // ρ² = |w⊥ + t·d⊥|², the parts of o − centre and d across the axis.
            const Vec3 w = Across(ray.origin - b.centre, b.axisUnit);
            const Vec3 across = Across(ray.dir, b.axisUnit);
            const double curvature = LengthSquared(across);
            const double tClosest = curvature > 0 ? -Dot(w, across) / curvature : 0;
            const double dist2 = LengthSquared(w + across * tClosest);
            if (dist2 < b.radius2) {
                const double h = curvature > 0 ? std::sqrt((b.radius2 - dist2) / curvature)
                                               : kInfinity;
                const Span span{i, kAxis, tClosest, dist2, curvature,
                                std::max(tClosest - h, lo), std::min(tClosest + h, hi)};
                if (span.enter < span.exit) emit(span);
            }
        }
        sphere(forward ? kSphereAtEnd : kSphereAtCentre,
               forward ? b.centre + b.axis : b.centre, std::max(hi, tMin), tMax);
    };
    const auto add = [&](const Span& span) {
        const int k = spanCount++;
        spans[k] = span;
        pending[pendingCount++] = {span.enter, k, true};
        pending[pendingCount++] = {span.exit, k, false};
        const Ball& b = balls_[span.ball];
        if (b.strength > 0) {
            const double q = 1 - span.dist2 / b.radius2;
            peakSum += b.strength * q * q;
        }
        strengthSum += std::abs(b.strength);
    };

    // The first root in (tMin, tMax) of F − T on [ta, tb], where the active balls are fixed.
    const auto solve = [&](double ta, double tb) -> std::optional<double> {
        double bound = 0, activeStrength = 0;
        for (int a = 0; a < activeCount; ++a) {
            const int k = active[a];
            const Ball& b = balls_[spans[k].ball];
            bound += TermPeak(b.strength, b.radius2, spans[k], ta, tb);
            activeStrength += std::abs(b.strength);
        }
        if (bound + kFieldBoundMargin * (threshold_ + activeStrength) < threshold_) {
            return std::nullopt;
        }
        // Quartic in u = t − ta: Σ s_i·q_i(u)² − T, with q_i = 1 − ρ_i²(u)/r_i² and
        // ρ_i² = |d|²u² + 2(o'−c)·d u + |o'−c|², o' = the point at ta (on an axis piece,
        // d and o' − c taken across the axis).
        const Vec3 start = ray.At(ta);
        double c[5] = {-threshold_, 0, 0, 0, 0};  // ascending powers
        for (int a = 0; a < activeCount; ++a) {
            const Span& span = spans[active[a]];
            const Ball& b = balls_[span.ball];
            Vec3 oc = start - b.centre, dir = ray.dir;
            if (span.piece == kSphereAtEnd) {
                oc = start - (b.centre + b.axis);
            } else if (span.piece == kAxis) {
                oc = Across(oc, b.axisUnit);
                dir = Across(dir, b.axisUnit);
            }
            const double a2 = -span.curvature * b.inverseRadius2,
                         a1 = -2 * Dot(oc, dir) * b.inverseRadius2,
                         a0 = 1 - LengthSquared(oc) * b.inverseRadius2;
            c[4] += b.strength * a2 * a2;
            c[3] += b.strength * 2 * a2 * a1;
            c[2] += b.strength * (a1 * a1 + 2 * a2 * a0);
            c[1] += b.strength * 2 * a1 * a0;
            c[0] += b.strength * a0 * a0;
        }
        if (quarticsSolved) ++*quarticsSolved;
        // Roots come nearest first and only as many as needed are computed.
        AscendingRoots roots(c, 4, 0, tb - ta);
        double u;
        while (roots.Next(u)) {
            const double t = ta + u;
            if (t > tMin && t < tMax) return t;
        }
        return std::nullopt;
    };

    // One step of the sweep along the ray: the event's interval [cursor, event.t], if some
    // ball is active there, is solved (the events are taken in increasing t, and every
    // event before event.t is known), then the event is applied. (A capsule's pieces do
    // not overlap: at most one of them is active at a time.)
    double cursor = 0;  // the last event swept; read only while some ball is active
    const auto sweep = [&](const Event& event) -> std::optional<double> {
        if (activeCount > 0 && event.t > cursor) {
            if (std::optional<double> root = solve(cursor, event.t)) return root;
        }
        // Active balls in increasing index, the order of the quartic's sums.
        const int ball = spans[event.span].ball;
        if (event.entering) {
            int i = activeCount++;
            for (; i > 0 && spans[active[i - 1]].ball > ball; --i) active[i] = active[i - 1];
            active[i] = event.span;
        } else {
            int i = 0;
            while (active[i] != event.span) ++i;
            for (--activeCount; i < activeCount; ++i) active[i] = active[i + 1];
        }
        cursor = event.t;
        return std::nullopt;
    };

    if (grid_.IsEmpty()) {
        // Every ball the ray meets, then one sweep.
        const auto visit = [&](int i) { spansOf(i, add); };
        if (hierarchy_.IsEmpty()) {
            for (size_t i = 0; i < balls_.size(); ++i) visit(static_cast<int>(i));
        } else {
            double segmentEnd = tMax;
            hierarchy_.Traverse(ray, tMin, segmentEnd, [&](int i) {
                visit(i);
                return false;  // collects every ball: the segment is not shortened
            });
        }
        if (spanCount == 0) return std::nullopt;
        // Even every ball at its peak stays below the threshold: no root anywhere.
        if (peakSum + kFieldBoundMargin * (threshold_ + strengthSum) < threshold_) {
            return std::nullopt;
        }
        std::sort(pending, pending + pendingCount,
                  [](const Event& a, const Event& b) { return a.t < b.t; });
        for (int e = 0; e < pendingCount; ++e) {
            if (std::optional<double> root = sweep(pending[e])) return root;
        }
        return std::nullopt;
    }

    // Grid walk, the pending events kept as a min-heap on t. Cell k covers the parameters [entry_k, exit_k) of the ray (the first from
    // −∞, the last to +∞, absorbing rounding at the grid's faces). A ball is added by the
    // cell whose range holds its entry parameter, which lists it (its box, padded, overlaps
    // the cell there): so once cell k is read, every ball entering before exit_k is known.
    double t0 = tMin, t1 = tMax;
    if (!bounds_.ClipRay(ray, t0, t1)) return std::nullopt;
    int cell[3], step[3];
    double next[3];  // the parameter of the next cell boundary along each axis
    const Vec3 p0 = ray.At(t0);
    for (int a = 0; a < 3; ++a) {
        cell[a] = grid_.CellOf(p0[a], a);
        step[a] = ray.dir[a] > 0 ? 1 : -1;
    }
    const auto boundary = [&](int a) {
        if (ray.dir[a] == 0) return kInfinity;
        const double plane = grid_.lo[a] + (cell[a] + (step[a] > 0)) * grid_.cellSize[a];
        return (plane - ray.origin[a]) / ray.dir[a];
    };
    for (int a = 0; a < 3; ++a) next[a] = boundary(a);
    double entry = -kInfinity;
    for (;;) {
        const int axis = next[0] <= next[1] ? (next[0] <= next[2] ? 0 : 2)
                                            : (next[1] <= next[2] ? 1 : 2);
        const bool last = next[axis] >= t1 || cell[axis] + step[axis] < 0 ||
                          cell[axis] + step[axis] >= grid_.n[axis];
        const double exit = last ? kInfinity : next[axis];
        const int c = grid_.Index(cell[0], cell[1], cell[2]);
        for (uint32_t k = grid_.cellStart[c]; k < grid_.cellStart[c + 1]; ++k) {
            spansOf(static_cast<int>(grid_.cellBalls[k]), [&](const Span& span) {
                if (span.enter < entry || span.enter >= exit) return;  // another cell's
                add(span);
                std::push_heap(pending, pending + pendingCount - 1, later);
                std::push_heap(pending, pending + pendingCount, later);
            });
        }
        // Every ball entering before `exit` is known: sweep the events up to it.
        while (pendingCount > 0 && pending[0].t <= exit) {
            std::pop_heap(pending, pending + pendingCount, later);
            const Event event = pending[--pendingCount];
            if (std::optional<double> root = sweep(event)) return root;
        }
        if (last) return std::nullopt;
        entry = exit;
        cell[axis] += step[axis];
        next[axis] = boundary(axis);
    }
}

Vec3 MetaballSum::NearestSkeletonPoint(const Ball& b, const Vec3& p) {
    if (b.axisLength2 == 0) return b.centre;
    const double u = Dot(p - b.centre, b.axis) / b.axisLength2;
    return b.centre + b.axis * std::clamp(u, 0.0, 1.0);
}

double MetaballSum::Value(const Vec3& p) const {
    double f = 0;
    ForBallsAt(p, [&](int i) {
        const Ball& b = balls_[i];
        const double q = 1 - LengthSquared(p - NearestSkeletonPoint(b, p)) / b.radius2;
        if (q > 0) f += b.strength * q * q;
    });
    return f;
}

Vec3 MetaballSum::Gradient(const Vec3& p) const {
    // ∇[s(1 − ρ²/r²)²] = −(4s/r²)(1 − ρ²/r²)(X − c) = (4·c4·ρ² + 2·c2)(X − c) with c4 = s/r⁴,
    // c2 = −2s/r², inside the ball, c the nearest skeleton point (∇ρ = (X − c)/ρ).
    Vec3 g;
    ForBallsAt(p, [&](int i) {
        const Ball& b = balls_[i];
        const Vec3 d = p - NearestSkeletonPoint(b, p);
        const double rho2 = LengthSquared(d);
        if (rho2 >= b.radius2) return;
        const double c4 = b.strength / (b.radius2 * b.radius2), c2 = -2 * b.strength / b.radius2;
        g += d * (4 * c4 * rho2 + 2 * c2);
    });
    return g;
}

int MetaballSum::Predominant(const Vec3& p) const {
    int best = -1;
    double bestValue = 0;
    ForBallsAt(p, [&](int i) {  // increasing index: a later ball must be strictly larger
        const Ball& b = balls_[i];
        const double q = 1 - LengthSquared(p - NearestSkeletonPoint(b, p)) / b.radius2;
        if (q <= 0) return;
        const double value = b.strength * q * q;
        if (best < 0 || value > bestValue) {
            best = i;
            bestValue = value;
        }
    });
    return best;
}

}  // namespace rs
