// What the command-line programs (rayshade, rayquery) share: the error sink that prints
// diagnostics the way the original did, and the guard that turns fatal errors into exit
// statuses.
#pragma once

#include <atomic>
#include <functional>

#include "libcommon/error.h"

namespace rs {

// "<program>: <Warning|Error|Fatal error>: <file>:<line>: <message>" (without the location
// when there is none), one line on stderr. Advisories are dropped while `quiet` is true.
void PrintDiagnostic(const char* program, const Diagnostic& d, bool quiet);

// Installs PrintDiagnostic for `program` as the error sink (reading `quiet` at each
// message), runs `run`, and returns its status; a FatalError becomes its exit status (1 for
// errors, 2 for fatal errors) and running out of memory is reported with status 2.
int RunCommand(const char* program, const std::atomic<bool>& quiet, const std::function<int()>& run);

}  // namespace rs
