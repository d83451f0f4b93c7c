#include "libshade/primitive_registry.h"

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

const PrimitiveEntry* FindPrimitive(const std::string& keyword) {
    // Called for every object of a scene: the keywords' lengths are compared before their
    // characters, and the table is looked up once.
    static const std::vector<PrimitiveEntry>& rows = PrimitiveRegistry();
    static const std::vector<std::string_view> keywords = [] {
        std::vector<std::string_view> k;
        for (const PrimitiveEntry& row : rows) k.emplace_back(row.keyword);
        return k;
    }();
    const std::string_view word = keyword;
    for (size_t i = 0; i < keywords.size(); ++i)
        if (word == keywords[i]) return &rows[i];
    return nullptr;
}

bool IsPrimitiveKeyword(const std::string& keyword) {
    return FindPrimitive(keyword) != nullptr;
}

}  // namespace rs
