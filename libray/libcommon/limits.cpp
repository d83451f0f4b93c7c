#include "libcommon/limits.h"

#include <cerrno>
#include <cstdlib>

namespace rs {

namespace {

ResourceLimits& MutableLimits() {
    static ResourceLimits limits;
    return limits;
}

struct NamedLimit {
    const char* name;
    long ResourceLimits::*field;
};

constexpr NamedLimit kNamed[] = {
    {"resolutionSide", &ResourceLimits::resolutionSide},
    {"resolutionPixels", &ResourceLimits::resolutionPixels},
    {"samplesPerSide", &ResourceLimits::samplesPerSide},
    {"rayDepth", &ResourceLimits::rayDepth},
    {"sceneBytes", &ResourceLimits::sceneBytes},
    {"gridVoxels", &ResourceLimits::gridVoxels},
    {"gridEntries", &ResourceLimits::gridEntries},
    {"polylinePoints", &ResourceLimits::polylinePoints},
    {"octreeBytes", &ResourceLimits::octreeBytes},
};

}  // namespace

const ResourceLimits& Limits() { return MutableLimits(); }

bool SetLimit(const std::string& assignment, std::string& error) {
    std::string::size_type eq = assignment.find('=');
    if (eq == std::string::npos) {
        error = "-L expects name=value, got '" + assignment + "'";
        return false;
    }
    std::string name = assignment.substr(0, eq), value = assignment.substr(eq + 1);
    for (const NamedLimit& n : kNamed) {
        if (name != n.name) continue;
        char* end = nullptr;
        errno = 0;
        long v = std::strtol(value.c_str(), &end, 10);
        if (value.empty() || *end != '\0' || errno == ERANGE || v < 1) {
            error = "-L " + name + ": '" + value + "' is not a positive integer";
            return false;
        }
        MutableLimits().*n.field = v;
        return true;
    }
    error = "-L: unknown limit '" + name + "' (known: " + LimitNames() + ")";
    return false;
}

std::string LimitNames() {
    std::string s;
    for (const NamedLimit& n : kNamed) {
        if (!s.empty()) s += ' ';
        s += n.name;
    }
    return s;
}

}  // namespace rs
