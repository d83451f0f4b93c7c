// One row per `texture` keyword: the parser looks the keyword up here and calls `create`
// with the reader positioned after the keyword (spec §2 `textype`). The parser then sets
// Texture::transform from the transforms that follow.
#pragma once

#include <memory>
#include <vector>

#include "libcommon/arg_reader.h"
#include "libtext/texture.h"

namespace rs {

struct TextureEntry {
    const char* keyword;
    std::shared_ptr<Texture> (*create)(ArgReader&);
    const char* usage;  // the argument syntax, for error messages
};

// All texture kinds, in the order of the spec's catalogue.
const std::vector<TextureEntry>& TextureRegistry();

}  // namespace rs
