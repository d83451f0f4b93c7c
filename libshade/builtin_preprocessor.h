// A built-in C preprocessor for the subset of cpp that scene files use, so that most
// renders need not start the system cpp (whose start-up, with its compiler proper, costs
// 20–30 ms of CPU and more of wall time before any rendering can begin).
//
// Contract: when PreprocessBuiltin returns text, the lexer reads from it exactly the tokens,
// line numbers and file names it would read from GNU cpp's output for the same input. When
// the input needs anything outside the subset, or anything that could make cpp's output
// differ, warn or fail, it returns nothing and the caller runs the system cpp. Being
// conservative is the design: every doubtful construct falls back.
//
// The subset:
// - `/* */` comments (replaced by a blank; the newlines inside them are kept);
// - `#define NAME body` and `#define NAME(a, b) body` without `#`, `##` or `...`;
//   `#undef`; `#ifdef`, `#ifndef`, `#else`, `#endif`; `#include "file"` found beside the
//   including file; the null directive `#`;
// - macros given as `-DNAME` or `-DNAME=body`;
// - expansion with rescanning, function-like invocations across lines, arguments expanded
//   before substitution.
// Falls back on: other directives (`#if`, `#elif`, `#line`, `#pragma`, ...), quotes and
// backslashes outside an include line, `//`, control characters, identifiers cpp
// predefines (those starting with '_', and kCppPredefinedNames), a macro name or
// parameter whose neighbours are not blanks, parentheses or commas (cpp's spacing of the
// result could then join or split the scene language's tokens, whose names may contain
// `-`, `.` and `/`), a macro left unexpanded, a redefinition, unbalanced conditionals, a
// missing include, and wrong argument counts.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace rs {

// The predefined macros of GNU cpp outside the reserved namespace (names not beginning
// with '_') on the targets it supports in its default GNU mode, e.g. `linux` and `unix`.
inline constexpr std::string_view kCppPredefinedNames[] = {"linux", "unix", "i386", "sun",
                                                           "sparc", "mips", "vax"};

// A command-line definition: `-DNAME` is {"NAME", "1"}, `-DNAME=body` is {"NAME", "body"},
// `-D'F(x)=body'` is {"F(x)", "body"}.
struct CommandLineMacro {
    std::string name;
    std::string body;
};

// Preprocesses `text`, the contents of the file `fileName` (which locates its includes),
// with the command-line macros `predefined`; nothing when the system cpp must do it.
std::optional<std::string> PreprocessBuiltin(std::string text, const std::string& fileName,
                                             const std::vector<CommandLineMacro>& predefined);

}  // namespace rs
