#include "libcommon/error.h"

#include <cstdio>
#include <mutex>
#include <vector>

namespace rs {

namespace {

std::mutex& SinkMutex() {
    static std::mutex m;
    return m;
}

ErrorSink& CurrentSink() {
    static ErrorSink sink;
    return sink;
}

std::string FormatV(const char* format, va_list args) {
    va_list copy;
    va_copy(copy, args);
    int n = std::vsnprintf(nullptr, 0, format, copy);
    va_end(copy);
    if (n < 0) return format;
    std::vector<char> buf(static_cast<size_t>(n) + 1);
    std::vsnprintf(buf.data(), buf.size(), format, args);
    return std::string(buf.data(), static_cast<size_t>(n));
}

// The innermost HeldReports of this thread, or null.
thread_local HeldReports* tHeld = nullptr;

}  // namespace

HeldReports::HeldReports() : previous_(tHeld) { tHeld = this; }

HeldReports::~HeldReports() { tHeld = previous_; }

ErrorSink SetErrorSink(ErrorSink sink) {
    std::lock_guard<std::mutex> lock(SinkMutex());
    ErrorSink previous = std::move(CurrentSink());
    CurrentSink() = std::move(sink);
    return previous;
}

void ReportV(Severity severity, const SourceLocation& where, const char* format, va_list args) {
    const bool fatal = severity == Severity::Abort || severity == Severity::Panic;
    if (tHeld) {
        ++tHeld->count_;
        if (fatal) throw FatalError(severity, "held report");
        return;
    }
    Diagnostic d{severity, where, FormatV(format, args)};
    {
        std::lock_guard<std::mutex> lock(SinkMutex());
        if (CurrentSink()) CurrentSink()(d);
    }
    if (fatal) {
        std::string what = where.IsKnown()
                               ? where.file + ":" + std::to_string(where.line) + ": " + d.message
                               : d.message;
        throw FatalError(severity, what);
    }
}

void Report(Severity severity, const SourceLocation& where, const char* format, ...) {
    va_list args;
    va_start(args, format);
    try {
        ReportV(severity, where, format, args);
    } catch (...) {
        va_end(args);
        throw;
    }
    va_end(args);
}

std::string StringPrintf(const char* format, ...) {
    va_list args;
    va_start(args, format);
    std::string s = FormatV(format, args);
    va_end(args);
    return s;
}

}  // namespace rs
