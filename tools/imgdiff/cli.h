// The imgdiff command line, as a function so tests can run it in-process.
#pragma once

#include <ostream>
#include <string>
#include <vector>

namespace rs {

inline constexpr int kImgdiffPass = 0;   // every metric within its threshold
inline constexpr int kImgdiffFail = 1;   // compared, and some metric is out of bounds
inline constexpr int kImgdiffError = 2;  // bad usage, unreadable image, size mismatch, ...

// Runs `imgdiff args...` (args exclude the program name): prints the one-line metrics report
// to `out`, errors and usage to `err`, writes the heat map on failure, and returns the exit
// status above.
int RunImgdiff(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);

}  // namespace rs
