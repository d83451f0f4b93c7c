// Where a data file named in a scene (height field, image texture, colormap) is read from.
// The original opened the name as written, relative to the working directory; that stays
// the first choice. A relative name not found there is looked up next to the scene file
// that names it, so `rayshade examples/heightfield.ray` finds examples/terrain.hf from any
// directory (docs/options.md, "Data files"). Output names (-O, outfile, report) are not
// resolved this way.
#pragma once

#include <string>

namespace rs {

// Returns `name` when it is absolute, exists relative to the working directory, or no
// other candidate exists; otherwise the path of `name` in the directory of `sceneFile`
// (the file whose text names it; empty or without a directory part: nothing to try).
std::string ResolveDataFile(const std::string& name, const std::string& sceneFile);

}  // namespace rs
