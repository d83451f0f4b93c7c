// Reading the scene text, through the external C preprocessor by default (spec §1.1).
#pragma once

#include <string>
#include <vector>

namespace rs {

struct SourceText {
    std::string text;
    std::string fileName;  // for locations until the first line marker: the path or "stdin"
};


// Reads the scene from `path` (empty: standard input). With `useCpp`, runs
//     cpp [words of cppArgs] [-D<define>...] [path]
// (cpp reads standard input when no path is given) without a shell, and returns its
// output, line markers included. Fails through rs::Report (Abort, throws FatalError) when
// the file cannot be read, cpp cannot be started or exits unsuccessfully (the message
// carries cpp's standard error); cpp's warnings on success are reported as warnings.
//
// Files that need no more than the built-in preprocessor's subset (builtin_preprocessor.h)
// and whose cpp arguments are only -D definitions are preprocessed without starting cpp.
SourceText ReadSceneSource(const std::string& path, bool useCpp, const std::string& cppArgs,
                           const std::vector<std::string>& defines);

}  // namespace rs
