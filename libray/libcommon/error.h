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

// While one lives, reports made on its thread reach no sink: it counts them instead (fatal
// ones still throw FatalError). For speculative work that is redone in the usual way
// wherever it reported anything (the parser's parallel runs of primitives). Scopes nest;
// the innermost counts.
class HeldReports {
  public:
    HeldReports();
    ~HeldReports();
    HeldReports(const HeldReports&) = delete;
    HeldReports& operator=(const HeldReports&) = delete;
    int Count() const { return count_; }

  private:
    friend void ReportV(Severity, const SourceLocation&, const char*, va_list);
    HeldReports* previous_;
    int count_ = 0;
};

// Formats printf-style and reports. Throws FatalError for Abort and Panic.
void Report(Severity severity, const SourceLocation& where, const char* format, ...)
    __attribute__((format(printf, 3, 4)));
void ReportV(Severity severity, const SourceLocation& where, const char* format, va_list args);

// printf-style formatting into a std::string.
std::string StringPrintf(const char* format, ...) __attribute__((format(printf, 1, 2)));

}  // namespace rs
