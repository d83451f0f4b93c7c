// A sum of metaballs F(X) = Σ s_i (1 − ρ_i(X)²/r_i²)² (each term 0 beyond its radius r_i),
// ρ_i the distance to ball i's skeleton, a point or a segment (a capsule), and the exact
// first crossing of F = T along a ray, by one quartic per interval: the method of Rayshade
// 4.0's blob (spec §3.9), shared by the `blob` primitive and the implicit primitive's
// `method polynomial`.
//
// Along a ray o + t·d, ρ² is a quadratic in t: for a point c, |o + t·d − c|²; for a segment
// [a, b], the same about a or b where the ray's projection on the axis falls before a or
// after b, and the squared distance to the axis line between (three pieces of the ray,
// split where the projection crosses a and b). So each term is a quartic in t on each piece
// inside its support; between two consecutive entry/exit/piece events the active pieces
// are fixed and F − T is one quartic.
// Each interval's quartic is formed in u = t − t_start with the ray's origin moved to the
// interval's start (no O(t⁴) cancellation for distant cameras, research note §8), and its
// roots in [0, t_end − t_start] come in ascending order; the first one in (tMin, tMax) is
// the crossing, whichever interval it is in (so a ray starting just outside the surface
// still finds it). Intervals where a bound of F stays below T by a safe margin are skipped
// without forming their quartic (kFieldBoundMargin in the .cpp derives it).
//
// Cost: the balls a ray may meet are found through a uniform grid over their boxes, walked
// front to back (3-D DDA): an interval is solved as soon as every cell the ray crossed
// before its end has been read, and the walk stops at the first root, so a ray costs about
// the cells it crosses up to its first root plus O(k log k) for the k balls met there, not
// O(N). Where the balls crowd into a few cells (the cells would hold many balls each on
// average), a bounding volume hierarchy over the boxes is used instead, collecting every
// ball along the ray; a few balls are simply looped over. The quartics sum their
// active balls in increasing ball index, so results do not depend on the structure.
//
// Strengths may be negative (carving); the threshold T must be > 0.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <vector>

#include "libcommon/bounds.h"
#include "libcommon/large_buffer.h"
#include "libcommon/ray.h"
#include "libgeom/bvh.h"

namespace rs {

struct Metaball {
    Vec3 centre;
    double radius;    // > 0
    double strength;  // s, non-zero
    // A capsule's segment runs from centre to centre + axis; zero for a ball.
    Vec3 axis{0, 0, 0};
};

class MetaballSum {
  public:
    MetaballSum(double threshold, std::span<const Metaball> balls);
    // The balls ball(0) ... ball(count − 1), without a copy of them all: `ball` is called a
    // few times per ball and must give the same ball each time.
    MetaballSum(double threshold, size_t count, const std::function<Metaball(size_t)>& ball);

    // The smallest t in (tMin, tMax) where F − T has a root of an interval's quartic (to
    // the polynomial solver's accuracy; a tangency within its rounding counts), or nothing.
    // `quarticsSolved`, when given, receives the number of quartics formed.
    std::optional<double> FirstRoot(const Ray& ray, double tMin, double tMax,
                                    int* quarticsSolved = nullptr) const;
    double Value(const Vec3& p) const;
    // ∇F at p (the outward normal is −∇F, normalised).
    Vec3 Gradient(const Vec3& p) const;
    // The ball whose term s(1 − ρ²/r²)² is largest at p (ties to the lowest index), or −1
    // where no ball's sphere of influence holds p.
    int Predominant(const Vec3& p) const;
    // The box of the spheres of influence: F = 0 outside it.
    const Bounds3& Bounds() const { return bounds_; }
    // How the balls along a ray are found (see above).
    enum class Search { Loop, Grid, Hierarchy };
    Search SearchStructure() const {
        return !grid_.IsEmpty() ? Search::Grid
                                : (hierarchy_.IsEmpty() ? Search::Loop : Search::Hierarchy);
    }

  private:
    // Ball data in the form the intersection uses.
    struct Ball {
        Vec3 centre;
        double radius2;         // r²
        double inverseRadius2;  // 1/r²
        double strength;
        Vec3 axis;              // zero for a point
        double axisLength2;     // |axis|²
        Vec3 axisUnit;          // axis / |axis| (zero for a point)
    };
    // The point of ball i's skeleton nearest to p.
    static Vec3 NearestSkeletonPoint(const Ball& b, const Vec3& p);
    // A uniform grid over bounds_: cell c lists, in increasing index, every ball whose box
    // (padded by kGridPadding of the grid's extent) overlaps it, in
    // cellBalls[cellStart[c] .. cellStart[c + 1]).
    struct Grid {
        int n[3] = {0, 0, 0};
        Vec3 lo, cellSize;
        std::vector<uint32_t, LargeBufferAllocator<uint32_t>> cellStart, cellBalls;
        bool IsEmpty() const { return cellStart.empty(); }
        // The cell index along `axis` holding coordinate x, clamped to the grid.
        int CellOf(double x, int axis) const;
        int Index(int ix, int iy, int iz) const { return (iz * n[1] + iy) * n[0] + ix; }
    };
    // Builds grid_ over the boxes box(0) ... box(count − 1) of the balls; leaves it empty
    // when the balls crowd into too few cells (the caller then builds hierarchy_).
    void BuildGrid(size_t count, const std::function<Bounds3(size_t)>& box);
    // Calls visit(i) for every ball whose box may contain p (at least those that do), in
    // increasing index.
    template <class Visit>
    void ForBallsAt(const Vec3& p, Visit&& visit) const;

    double threshold_;
    std::vector<Ball, LargeBufferAllocator<Ball>> balls_;
    size_t maxSpans_ = 0;  // the most spans a ray can give: 1 per ball, 3 per capsule
    Bounds3 bounds_;
    // At most one of the two is built: none for a few balls (a plain loop).
    Grid grid_;
    BoundingVolumeHierarchy hierarchy_;
};

}  // namespace rs
