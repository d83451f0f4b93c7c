#include "libshade/command.h"

#include <cstdio>
#include <new>

namespace rs {

void PrintDiagnostic(const char* program, const Diagnostic& d, bool quiet) {
    if (d.severity == Severity::Advise && quiet) return;
    const char* kind = d.severity == Severity::Advise || d.severity == Severity::Warn
                           ? "Warning"
                           : (d.severity == Severity::Abort ? "Error" : "Fatal error");
    if (d.location.IsKnown())
        std::fprintf(stderr, "%s: %s: %s:%d: %s\n", program, kind,
                     d.location.file.empty() ? "<stdin>" : d.location.file.c_str(), d.location.line,
                     d.message.c_str());
    else
        std::fprintf(stderr, "%s: %s: %s\n", program, kind, d.message.c_str());
}

int RunCommand(const char* program, const std::atomic<bool>& quiet, const std::function<int()>& run) {
    SetErrorSink([program, &quiet](const Diagnostic& d) { PrintDiagnostic(program, d, quiet.load()); });
    try {
        return run();
    } catch (const FatalError& e) {
        return e.ExitStatus();
    } catch (const std::bad_alloc&) {
        std::fprintf(stderr, "%s: Fatal error: out of memory\n", program);
        return 2;
    }
}

}  // namespace rs
