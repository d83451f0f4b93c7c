// Reading the scene text, through the external C preprocessor by default (spec §1.1).
#pragma once

#include <string>
#include <string_view>
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
// A file that cpp would pass through unchanged apart from its comments (which the lexer
// skips itself) is read directly, without starting cpp: see CppWouldOnlyStripComments.
// Starting cpp and its compiler proper costs 20–30 ms of CPU, a tenth of a small render.
SourceText ReadSceneSource(const std::string& path, bool useCpp, const std::string& cppArgs,
                           const std::vector<std::string>& defines);

// True when GNU cpp, run without arguments, would turn `text` into the same token sequence
// with the same line numbers, only removing /* */ comments. (The end of input of a file
// without a final newline is then reported on its last line; cpp adds a newline, so
// through cpp it is the line after.) Conservative: false as soon as
// the text (outside comments) has anything cpp could act on or warn about: a line whose
// first non-blank character is '#', a backslash, "//", a quote, a control character other
// than tab, CR and newline, or a C identifier that cpp predefines as a macro (those
// beginning with '_', and the traditional system names in kCppPredefinedNames).
bool CppWouldOnlyStripComments(std::string_view text);

// The predefined macros of GNU cpp outside the reserved namespace (names not beginning
// with '_') on the targets it supports in its default GNU mode, e.g. `linux` and `unix`.
inline constexpr std::string_view kCppPredefinedNames[] = {"linux", "unix", "i386", "sun",
                                                           "sparc", "mips", "vax"};

}  // namespace rs
