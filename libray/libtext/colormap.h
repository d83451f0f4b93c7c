// Colour maps for the marble, fbm and mount textures (spec §3.12.2).
//
// A file holds up to 256 lines "r g b" of integers in [0, 255]; entry i comes from line
// i + 1, scaled by 1/255. Missing entries are black; lines after the 256th are ignored. Any
// other line (including a blank one, as in the original) is an error naming the file and
// line.
#pragma once

#include <array>
#include <istream>
#include <memory>
#include <optional>
#include <string>

#include "libcommon/arg_reader.h"
#include "libcommon/vector.h"
#include "libsurf/surface.h"

namespace rs {

using ColorMap = std::array<Color, 256>;

// Parses colour-map text; `name` labels messages. On failure returns nothing and sets
// `error` to "<name>: line <n>: <problem>".
std::optional<ColorMap> ParseColorMap(std::istream& in, const std::string& name,
                                      std::string& error);

// Reads a colour-map file (messages name `path`).
std::optional<ColorMap> ReadColorMap(const std::string& path, std::string& error);

// Reads a FILE argument and loads it, failing through `args` on error.
std::shared_ptr<const ColorMap> ReadColorMapArgument(ArgReader& args);

// The entry for a value scaled to [0, 256) and clamped to the table.
inline const Color& ColorMapLookup(const ColorMap& map, double scaled) {
    int i = scaled >= 255 ? 255 : (scaled > 0 ? static_cast<int>(scaled) : 0);
    return map[i];
}

// What marble and fbm do with their value v ∈ [0, 1]: with a colour map, ambient and
// diffuse are multiplied by the entry ⌊255·v⌋; without one, by v itself.
inline void ModulateAmbientDiffuse(Surface& surface, const ColorMap* map, double v) {
    if (map) {
        const Color& c = ColorMapLookup(*map, 255 * v);
        surface.ambient *= c;
        surface.diffuse *= c;
    } else {
        surface.ambient *= v;
        surface.diffuse *= v;
    }
}

}  // namespace rs
