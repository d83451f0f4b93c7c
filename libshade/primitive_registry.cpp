#include "libshade/primitive_registry.h"

#include <array>
#include <string_view>

#include "libobj/blob.h"
#include "libobj/box.h"
#include "libobj/cone.h"
#include "libobj/cylinder.h"
#include "libobj/disc.h"
#include "libobj/heightfield.h"
#include "libobj/implicit/implicit_surface.h"
#include "libobj/implicit/implicit_syntax.h"
#include "libobj/plane.h"
#include "libobj/polygon.h"
#include "libobj/sphere.h"
#include "libobj/torus.h"
#include "libobj/triangle.h"

namespace rs {

const std::vector<PrimitiveEntry>& PrimitiveRegistry() {
    static const std::vector<PrimitiveEntry> rows = {
        {"sphere", Sphere::Create, "sphere [surface] radius cx cy cz", nullptr, true},
        {"box", Box::Create, "box [surface] x1 y1 z1 x2 y2 z2", nullptr, true},
        {"plane", Plane::Create, "plane [surface] px py pz nx ny nz", nullptr, true},
        {"disc", Disc::Create, "disc [surface] radius cx cy cz nx ny nz", nullptr, true},
        {"cylinder", Cylinder::Create, "cylinder [surface] radius bx by bz tx ty tz", nullptr, true},
        {"cone", Cone::Create, "cone [surface] r1 x1 y1 z1 r2 x2 y2 z2", nullptr, true},
        {"torus", Torus::Create, "torus [surface] rswept rtube cx cy cz nx ny nz", nullptr, true},
        {"triangle", Triangle::Create,
         "triangle [surface] p1 p2 p3  or  triangle [surface] p1 n1 p2 n2 p3 n3", nullptr, true},
        {"triangleuv", Triangle::CreateUV,
         "triangleuv [surface] p1 n1 u1 v1 p2 n2 u2 v2 p3 n3 u3 v3", nullptr, true},
        {"poly", Polygon::Create, "poly [surface] x1 y1 z1 x2 y2 z2 x3 y3 z3 ...", nullptr, true},
        {"blob", Blob::Create, "blob [surface] threshold strength radius cx cy cz [strength radius cx cy cz ...]", nullptr, true},
        {"heightfield", HeightField::Create, "heightfield [surface] file"},
        {"implicit", ImplicitSurface::Create, kImplicitUsage,
         ImplicitSurface::IsBlockWord},
    };
    return rows;
}

const PrimitiveEntry* FindPrimitive(std::string_view keyword) {
    // Called for every object of a scene: the rows are indexed by first letter and length
    // (one candidate, compared in full); a key two rows share sends the lookup to a scan.
    constexpr size_t kLetters = 26, kLengths = 16;
    constexpr int kNone = -1, kShared = -2;
    static const std::vector<PrimitiveEntry>& rows = PrimitiveRegistry();
    const auto key = [](std::string_view word) -> long {
        if (word.empty() || word.size() >= kLengths || word[0] < 'a' || word[0] > 'z') return -1;
        return static_cast<long>(static_cast<size_t>(word[0] - 'a') * kLengths + word.size());
    };
    static const std::array<int, kLetters * kLengths> index = [&] {
        std::array<int, kLetters * kLengths> byKey;
        byKey.fill(kNone);
        for (size_t i = 0; i < rows.size(); ++i) {
            const long k = key(rows[i].keyword);
            if (k < 0) continue;  // not indexed: found by the scan of shared keys only
            int& slot = byKey[static_cast<size_t>(k)];
            slot = slot == kNone ? static_cast<int>(i) : kShared;
        }
        return byKey;
    }();
    const long k = key(keyword);
    const int row = k < 0 ? kShared : index[static_cast<size_t>(k)];
    if (row >= 0) {
        const PrimitiveEntry& candidate = rows[static_cast<size_t>(row)];
        return keyword == candidate.keyword ? &candidate : nullptr;
    }
    if (row == kNone) return nullptr;
    for (const PrimitiveEntry& entry : rows)
        if (keyword == entry.keyword) return &entry;
    return nullptr;
}

bool IsPrimitiveKeyword(std::string_view keyword) {
    return FindPrimitive(keyword) != nullptr;
}

}  // namespace rs
