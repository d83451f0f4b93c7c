#include "libshade/primitive_registry.h"

#include <string_view>
#include <unordered_map>

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
        {"sphere", Sphere::Create, "sphere [surface] radius cx cy cz"},
        {"box", Box::Create, "box [surface] x1 y1 z1 x2 y2 z2"},
        {"plane", Plane::Create, "plane [surface] px py pz nx ny nz"},
        {"disc", Disc::Create, "disc [surface] radius cx cy cz nx ny nz"},
        {"cylinder", Cylinder::Create, "cylinder [surface] radius bx by bz tx ty tz"},
        {"cone", Cone::Create, "cone [surface] r1 x1 y1 z1 r2 x2 y2 z2"},
        {"torus", Torus::Create, "torus [surface] rswept rtube cx cy cz nx ny nz"},
        {"triangle", Triangle::Create,
         "triangle [surface] p1 p2 p3  or  triangle [surface] p1 n1 p2 n2 p3 n3"},
        {"triangleuv", Triangle::CreateUV,
         "triangleuv [surface] p1 n1 u1 v1 p2 n2 u2 v2 p3 n3 u3 v3"},
        {"poly", Polygon::Create, "poly [surface] x1 y1 z1 x2 y2 z2 x3 y3 z3 ..."},
        {"blob", Blob::Create, "blob [surface] threshold strength radius cx cy cz [strength radius cx cy cz ...]"},
        {"heightfield", HeightField::Create, "heightfield [surface] file"},
        {"implicit", ImplicitSurface::Create, kImplicitUsage,
         ImplicitSurface::IsBlockWord},
    };
    return rows;
}

const PrimitiveEntry* FindPrimitive(std::string_view keyword) {
    // Called for every object of a scene: one hash lookup in a table built once.
    static const std::unordered_map<std::string_view, const PrimitiveEntry*> rows = [] {
        std::unordered_map<std::string_view, const PrimitiveEntry*> byKeyword;
        for (const PrimitiveEntry& row : PrimitiveRegistry()) byKeyword.emplace(row.keyword, &row);
        return byKeyword;
    }();
    const auto it = rows.find(keyword);
    return it == rows.end() ? nullptr : it->second;
}

bool IsPrimitiveKeyword(std::string_view keyword) {
    return FindPrimitive(keyword) != nullptr;
}

}  // namespace rs
