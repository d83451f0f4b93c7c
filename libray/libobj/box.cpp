#include "libobj/box.h"

#include <cmath>
#include <limits>
#include <utility>

#include "libcommon/constants.h"

namespace rs {

Box::Box(const Vec3& cornerA, const Vec3& cornerB) : bounds_(cornerA, cornerB) {}

std::shared_ptr<Primitive> Box::Create(ArgReader& args) {
    const Vec3 a = args.ReadVector();
    const Vec3 b = args.ReadVector();
    const Vec3 size = a - b;
    if (!(std::fabs(size.x) >= kEpsilon && std::fabs(size.y) >= kEpsilon &&
          std::fabs(size.z) >= kEpsilon)) {
        args.Warn("Degenerate box (an extent below epsilon), discarded.");
        return nullptr;
    }
    return std::make_shared<Box>(a, b);
}

const IntersectionCounters& Box::Counters() const {
    static const IntersectionCounters counters("Box");
    return counters;
}

bool Box::Intersect(const Ray& ray, double tMin, double tMax, PrimitiveHit& hit) const {
    // Slab test over the whole line: [tNear, tFar] is where the line is inside the box.
    const double o[3] = {ray.origin.x, ray.origin.y, ray.origin.z};
    const double d[3] = {ray.dir.x, ray.dir.y, ray.dir.z};
    const double lo[3] = {bounds_.lo.x, bounds_.lo.y, bounds_.lo.z};
    const double hi[3] = {bounds_.hi.x, bounds_.hi.y, bounds_.hi.z};
    constexpr double kInf = std::numeric_limits<double>::infinity();
    double tNear = -kInf, tFar = kInf;
    for (int axis = 0; axis < 3; ++axis) {
        if (d[axis] == 0) {
            // Parallel to this slab: inside it everywhere or nowhere.
            if (o[axis] < lo[axis] || o[axis] > hi[axis]) return false;
            continue;
        }
        const double inv = 1 / d[axis];
        double t0 = (lo[axis] - o[axis]) * inv, t1 = (hi[axis] - o[axis]) * inv;
        if (t0 > t1) std::swap(t0, t1);
        if (t0 > tNear) tNear = t0;
        if (t1 < tFar) tFar = t1;
    }
    if (tNear > tFar) return false;
    return AcceptNearerCrossing(tNear, tFar, tMin, tMax, hit);
}

SurfaceNormals Box::Normal(const Vec3& p, const PrimitiveHit&) const {
    // Faces in the original's test order: +x, −x, +y, −y, +z, −z.
    const double distance[6] = {std::fabs(p.x - bounds_.hi.x), std::fabs(p.x - bounds_.lo.x),
                                std::fabs(p.y - bounds_.hi.y), std::fabs(p.y - bounds_.lo.y),
                                std::fabs(p.z - bounds_.hi.z), std::fabs(p.z - bounds_.lo.z)};
    int face = 0;
    for (int i = 0; i < 6; ++i) {
        if (distance[i] < kEpsilon) {
            face = i;
            break;
        }
        if (distance[i] < distance[face]) face = i;
    }
    Vec3 n;
    n[face / 2] = (face % 2 == 0) ? 1.0 : -1.0;
    return {n, n, false};
}

bool Box::Enters(const Ray&, const PrimitiveHit& hit, const SurfaceNormals&) const {
    return hit.part == 0;
}

}  // namespace rs
