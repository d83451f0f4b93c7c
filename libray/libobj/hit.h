// The record of the nearest hit found so far along a ray, with the path of scene nodes from
// the hit primitive up to the top, so surfaces, textures and transforms can be looked up
// for the winner only.
#pragma once

#include <algorithm>

#include "libobj/primitive.h"

namespace rs {

class Object;

struct HitRecord {
    // Instancing depth is bounded (libshade enforces kMaxModelDepth); the path holds the
    // primitive's node at [0] and its ancestors after it.
    static constexpr int kMaxPath = 64;

    PrimitiveHit prim;
    const Primitive* primitive = nullptr;
    const Object* path[kMaxPath];  // entries [0, pathLength) are valid
    int pathLength = 0;
    // CSG overrides the enter/leave classification of the hit: -1 none, 0 leave, 1 enter.
    int enterOverride = -1;

    HitRecord() = default;
    // Copies only the valid part of the path: records are copied per CSG step and the
    // full array is ten times larger than what a typical path uses.
    HitRecord(const HitRecord& other) { *this = other; }
    HitRecord& operator=(const HitRecord& other) {
        prim = other.prim;
        primitive = other.primitive;
        pathLength = other.pathLength;
        enterOverride = other.enterOverride;
        std::copy(other.path, other.path + other.pathLength, path);
        return *this;
    }

    double t() const { return prim.t; }
};

}  // namespace rs
