#include "rayquery/query.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <utility>
#include <vector>

#include "libcommon/error.h"
#include "libcommon/stats.h"
#include "libobj/hit.h"

namespace rs {

bool IsQueryComment(const std::string& line) {
    size_t first = line.find_first_not_of(" \t\r");
    return first == std::string::npos || line[first] == '#';
}

bool ParseQueryLine(const std::string& line, QueryRay& query, std::string& error) {
    std::istringstream in(line);
    std::vector<double> numbers;
    std::string word;
    while (in >> word) {
        const char* begin = word.c_str();
        char* end = nullptr;
        errno = 0;
        double v = std::strtod(begin, &end);
        if (end == begin || *end != '\0') {
            error = StringPrintf("'%s' is not a number", word.c_str());
            return false;
        }
        if (!std::isfinite(v) || errno == ERANGE) {
            error = StringPrintf("'%s' is not a finite number", word.c_str());
            return false;
        }
        numbers.push_back(v);
    }
    if (numbers.size() < 6 || numbers.size() > 9) {
        error = StringPrintf(
            "expected 'ox oy oz dx dy dz [tmin [tmax [time]]]' (6 to 9 numbers), got %zu",
            numbers.size());
        return false;
    }
    query = QueryRay();
    query.ray.origin = {numbers[0], numbers[1], numbers[2]};
    query.ray.dir = {numbers[3], numbers[4], numbers[5]};
    if (numbers.size() > 6) query.tMin = numbers[6];
    if (numbers.size() > 7) query.tMax = numbers[7];
    if (numbers.size() > 8) query.time = numbers[8];
    if (LengthSquared(query.ray.dir) == 0) {
        error = "the direction is zero";
        return false;
    }
    if (!(query.tMin < query.tMax)) {
        error = StringPrintf("tmin %g is not below tmax %g", query.tMin, query.tMax);
        return false;
    }
    return true;
}

QueryResult RunQuery(const Object& world, const QueryRay& query) {
    const FieldCounters& ids = FieldCounterIds();
    auto evaluations = [&ids] {
        // Less the evaluations of octrees built lazily by this query (not the ray's cost).
        return ThreadCount(ids.values) + ThreadCount(ids.gradients) + ThreadCount(ids.bounds) -
               ImplicitBuildEvaluations();
    };
    QueryResult result;
    HitRecord hit;
    double tMax = query.tMax;
    const uint64_t before = evaluations();
    result.hit = world.Intersect(query.ray, query.tMin, tMax, hit);
    result.evals = evaluations() - before;
    if (!result.hit) return result;

    // The primitive's normal, carried up the path as the renderer does (tracer.cpp).
    Transform worldFromPrimitive;
    for (int i = 0; i < hit.pathLength; ++i) {
        const TransformList& list = hit.path[i]->parentFromObject;
        if (list.IsIdentity()) continue;
        worldFromPrimitive = worldFromPrimitive.Then(
            list.IsAnimated() ? list.At(query.ray.time) : list.Static());
    }
    const Ray rayPrimitive = worldFromPrimitive.InverseRay(query.ray);
    const SurfaceNormals normals = hit.primitive->Normal(rayPrimitive.At(hit.t()), hit.prim);
    result.t = hit.t();
    result.point = query.ray.At(hit.t());
    result.normal = Normalize(worldFromPrimitive.ApplyNormal(normals.geometric));
    for (int i = 0; i < hit.pathLength; ++i) {
        if (!hit.path[i]->name.empty()) {
            result.object = hit.path[i]->name;
            break;
        }
    }
    if (const auto* implicit = dynamic_cast<const ImplicitSurface*>(hit.primitive)) {
        std::string patch = implicit->PatchName(hit.prim);
        if (!patch.empty()) result.patch = std::move(patch);
    }
    return result;
}

std::string FormatQueryResult(const QueryResult& r) {
    if (!r.hit) return StringPrintf("miss %llu", static_cast<unsigned long long>(r.evals));
    return StringPrintf("hit %.17g %.17g %.17g %.17g %.17g %.17g %.17g %s %s %llu", r.t,
                        r.point.x, r.point.y, r.point.z, r.normal.x, r.normal.y, r.normal.z,
                        r.object.c_str(), r.patch.c_str(),
                        static_cast<unsigned long long>(r.evals));
}

}  // namespace rs
