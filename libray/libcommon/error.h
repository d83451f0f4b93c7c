// Error reporting for library code. The library never prints and never exits: it calls
// Report(), which hands the message to the sink the application installed. Rayshade's four
// severities are kept: Advise and Warn return to the caller; Abort and Panic throw
// FatalError after the sink has run, and main() turns that into the exit status
// (1 for Abort, 2 for Panic).
#pragma once

#include <cstdarg>
#include <functional>
#include <stdexcept>
#include <string>

namespace rs {

enum class Severity { Advise, Warn, Abort, Panic };

// Where in the scene text a message points; an empty file means "no location".
struct SourceLocation {
    std::string file;
    int line = 0;
    bool IsKnown() const { return line > 0; }
};

struct Diagnostic {
    Severity severity;
    SourceLocation location;
    std::string message;
};

class FatalError : public std::runtime_error {
  public:
    FatalError(Severity s, const std::string& what) : std::runtime_error(what), severity(s) {}
    Severity severity;
    int ExitStatus() const { return severity == Severity::Panic ? 2 : 1; }
};

using ErrorSink = std::function<void(const Diagnostic&)>;

// Installs the sink for the whole process and returns the previous one. With no sink
// installed, diagnostics are dropped (fatal ones still throw).
ErrorSink SetErrorSink(ErrorSink sink);

// Formats printf-style and reports. Throws FatalError for Abort and Panic.
void Report(Severity severity, const SourceLocation& where, const char* format, ...)
    __attribute__((format(printf, 3, 4)));
void ReportV(Severity severity, const SourceLocation& where, const char* format, va_list args);

// printf-style formatting into a std::string.
std::string StringPrintf(const char* format, ...) __attribute__((format(printf, 1, 2)));

}  // namespace rs
