// The ray-query tool's library: one world-space ray per text line in, the first hit (or a
// miss) per ray out, with the implicit module's evaluation count. The format is specified
// in README.md of this folder.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "libcommon/ray.h"
#include "libobj/implicit/implicit_surface.h"
#include "libobj/object.h"

namespace rs {

// The search interval of a query ray when the line gives none: (0, 1e14), open at both
// ends, in units of the given direction.
inline constexpr double kQueryDefaultTMin = 0;
inline constexpr double kQueryDefaultTMax = 1e14;

struct QueryRay {
    Ray ray;  // world space; dir need not be unit length
    double tMin = kQueryDefaultTMin, tMax = kQueryDefaultTMax;
    std::optional<double> time;  // the ray time, when the line gives one
};

// Parses `ox oy oz dx dy dz [tmin [tmax [time]]]` (whitespace separated, finite numbers,
// non-zero direction, tmin < tmax). Returns false with a message (without the line number) on
// malformed input. Blank lines and lines whose first non-blank character is '#' are for
// the caller to skip (IsQueryComment).
bool ParseQueryLine(const std::string& line, QueryRay& query, std::string& error);
bool IsQueryComment(const std::string& line);

struct QueryResult {
    bool hit = false;
    double t = 0;
    Vec3 point;   // world space, ray.At(t)
    Vec3 normal;  // world space, unit geometric normal, not flipped toward the ray
    std::string object = "-";  // name of the nearest named node on the hit's path, or "-"
    std::string patch = "-";   // the implicit patch's skeleton name, or "-"
    uint64_t evals = 0;  // implicit field + gradient + bound evaluations of the search
};

// Nearest hit in (tMin, tMax) of the prepared world. EVALS counts this thread's implicit
// evaluations during the search (not those of the normal computation).
QueryResult RunQuery(const Object& world, const QueryRay& query);

// `hit T PX PY PZ NX NY NZ OBJECT PATCH EVALS` or `miss EVALS`, numbers with 17
// significant digits, no trailing newline.
std::string FormatQueryResult(const QueryResult& result);

}  // namespace rs
