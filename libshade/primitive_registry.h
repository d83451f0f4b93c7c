// The explicit table of primitive keywords (architecture note §2.4): a new primitive costs
// one .h/.cpp pair in libray/libobj/, one row in primitive_registry.cpp and one CMake line.
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "libcommon/arg_reader.h"
#include "libobj/primitive.h"

namespace rs {

struct PrimitiveEntry {
    const char* keyword;  // canonical keyword (synonyms are folded by the lexer)
    // Reads the arguments after the keyword (and the optional surface, which the parser
    // handles). Returns nullptr for degenerate input after warning through the reader.
    std::shared_ptr<Primitive> (*create)(ArgReader&);
    const char* usage;  // the argument syntax, for error messages
    // For primitives whose own arguments may begin with a NAME (a sub-keyword): whether a
    // NAME right after the keyword starts the arguments rather than naming a surface.
    bool (*startsArguments)(const std::string& word) = nullptr;
    // Whether `create` may run on several threads at once (the parser's parallel runs of
    // primitive statements, parser.cpp): it reads only its arguments and changes no state
    // shared between objects (no numbering by creation order, no file or cache).
    bool createsConcurrently = false;
};

const std::vector<PrimitiveEntry>& PrimitiveRegistry();

// The row for `keyword`, or null.
const PrimitiveEntry* FindPrimitive(std::string_view keyword);

// Whether `keyword` starts a primitive (spec §2 `primitive`): it has a row in the table.
bool IsPrimitiveKeyword(std::string_view keyword);

}  // namespace rs
