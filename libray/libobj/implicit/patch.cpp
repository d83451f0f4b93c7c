#include "libobj/implicit/patch.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace rs {

namespace {

bool BoxesOverlap(const Bounds3& a, const Bounds3& b) {
    return !Intersection(a, b).IsEmpty();
}

}  // namespace

Patch::Patch(const Field& object, std::vector<int> members)
    : field_(object.Subset(std::move(members))),
      box_(TermSupportBounds(object.Terms()[field_.Rows().front()])) {}

namespace {

// |w|·max|f'|: the term's Lipschitz constant in space.
double TermLipschitz(const FieldTerm& term) {
    const Kernel& k = term.kernel;
    return std::abs(term.weight) * k.Bounds(0, k.Radius()).maxSlope;
}

}  // namespace

bool Patch::PredominatesNear(const Vec3& p, double uncertainty) const {
    const std::vector<int>& members = field_.Rows();
    const int ownIndex = members.front();
    const double own = field_.TermValue(ownIndex, p);
    double ownLipschitz = -1;  // computed on first need: most points have no close rival
    for (size_t j = 1; j < members.size(); ++j) {
        const double other = field_.TermValue(members[j], p);
        if (other < own || (other == own && members[j] > ownIndex)) continue;
        // An exact tie keeps its rule (the lowest index wins), so a point computed on a
        // seam still belongs to one patch; only a strictly larger rival is weighed.
        if (other == own || !(uncertainty > 0)) return false;
        if (ownLipschitz < 0) ownLipschitz = TermLipschitz(field_.Terms()[ownIndex]);
        const double slack = (ownLipschitz + TermLipschitz(field_.Terms()[members[j]])) *
                                 uncertainty +
                             kValueRounding * (std::abs(other) + std::abs(own));
        if (other - own > slack) return false;
    }
    return true;
}

bool Patch::MayHoldRoot(const Ray& ray, double tMin, double tMax) const {
    const FieldTerm& own = field_.Terms()[Own()];
    const double a = LengthSquared(ray.dir);
    if (!(a > 0)) return true;
    const double reach = own.kernel.Radius() * (1 + kSupportMargin);
    // NaNs (overflow) fail every comparison below: true.
    if (const auto* point = std::get_if<PointSkeleton>(&own.skeleton)) {
        const Vec3 oc = ray.origin - point->center;
        const double radius = reach + kOriginMargin * Length(oc);
        // The closest approach to the centre, at parameter tc and squared distance d2; the
        // enlarged ball spans tc ± half.
        const double tc = -Dot(oc, ray.dir) / a;
        const double d2 = LengthSquared(ray.At(tc) - point->center);
        if (d2 > radius * radius) return false;
        const double half = std::sqrt((radius * radius - d2) / a);
        return !(tc + half < tMin || tc - half > tMax);
    }
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

std::vector<Patch> BuildPatches(const Field& object, BlendMode mode,
                                const std::vector<std::pair<int, int>>& blendPairs,
                                const std::vector<std::pair<int, int>>& separatePairs) {
    const std::vector<FieldTerm>& terms = object.Terms();
    const int n = static_cast<int>(terms.size());
    std::vector<Bounds3> support(n);
    for (int i = 0; i < n; ++i) support[i] = TermSupportBounds(terms[i]);
    // Candidate neighbours: in Explicit mode the declared partners, otherwise every term
    // whose support box overlaps (found through a uniform grid, below).
    std::vector<std::vector<int>> candidates(n);
    if (mode == BlendMode::Explicit) {
        for (auto [a, b] : blendPairs) {
            if (a < 0 || b < 0 || a >= n || b >= n || a == b) continue;
            candidates[a].push_back(b);
            candidates[b].push_back(a);
        }
    } else {
        // Grid of cell edge W per axis, W the largest support extent along that axis, each
        // box filed under the cell of its low corner. Two boxes overlap only if their low
        // corners differ by at most W per axis, i.e. their cells are equal or adjacent, so
        // the 27 cells around a box's own hold every box it may overlap. Cost O(n·k) for k
        // boxes per cell neighbourhood, instead of testing all n² pairs.
        const double inf = std::numeric_limits<double>::infinity();
        Vec3 width{0, 0, 0}, origin{inf, inf, inf};
        for (const Bounds3& b : support) {
            if (b.IsEmpty()) continue;
            width = Max(width, b.hi - b.lo);
            origin = Min(origin, b.lo);
        }
        // Cell coordinates are clamped to ±2^60, so that they and their neighbours' keys
        // stay integers for supports of absurd spread (coordinates of 1e64 and beyond):
        // clamping is monotone, so boxes in equal or adjacent cells stay so. An axis whose
        // widest support is not finite has one cell, as does one of zero width; a NaN
        // quotient (infinite supports) goes to cell 0.
        constexpr double kMaxCell = 0x1p60;
        auto cellOf = [&](const Vec3& p) {
            std::array<long long, 3> c{};
            for (int a = 0; a < 3; ++a) {
                if (!(width[a] > 0 && std::isfinite(width[a]))) continue;
                const double q = std::floor((p[a] - origin[a]) / width[a]);
                c[a] = std::isnan(q) ? 0
                                     : static_cast<long long>(std::clamp(q, -kMaxCell, kMaxCell));
            }
            return c;
        };
        std::vector<std::pair<std::array<long long, 3>, int>> cells;
        cells.reserve(n);
        for (int i = 0; i < n; ++i) {
            if (!support[i].IsEmpty()) cells.emplace_back(cellOf(support[i].lo), i);
        }
        std::sort(cells.begin(), cells.end());
        for (int i = 0; i < n; ++i) {
            if (!(terms[i].weight > 0) || support[i].IsEmpty()) continue;
            const std::array<long long, 3> c = cellOf(support[i].lo);
            for (long long dx = -1; dx <= 1; ++dx) {
                for (long long dy = -1; dy <= 1; ++dy) {
                    for (long long dz = -1; dz <= 1; ++dz) {
                        std::array<long long, 3> key{c[0] + dx, c[1] + dy, c[2] + dz};
                        auto lo = std::lower_bound(
                            cells.begin(), cells.end(), key,
                            [](const auto& e, const std::array<long long, 3>& k) {
                                return e.first < k;
                            });
                        for (auto it = lo; it != cells.end() && it->first == key; ++it) {
                            candidates[i].push_back(it->second);
                        }
                    }
                }
            }
        }
    }
    auto separate = [&separatePairs](int i, int j) {
        for (auto [a, b] : separatePairs) {
            if ((a == i && b == j) || (a == j && b == i)) return true;
        }
        return false;
    };
    std::vector<Patch> patches;
    for (int i = 0; i < n; ++i) {
        if (!(terms[i].weight > 0)) continue;
        // Neighbours in increasing term order (the order of the patch field's sum).
        std::vector<int>& c = candidates[i];
        std::sort(c.begin(), c.end());
        c.erase(std::unique(c.begin(), c.end()), c.end());
        std::vector<int> members{i};
        for (int j : c) {
            if (j == i || !BoxesOverlap(support[i], support[j]) || separate(i, j)) continue;
            members.push_back(j);
        }
        patches.emplace_back(object, std::move(members));
    }
    return patches;
}

}  // namespace rs
