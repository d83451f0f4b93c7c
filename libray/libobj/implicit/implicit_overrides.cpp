#include "libobj/implicit/implicit_overrides.h"

#include <cmath>
#include <cstdlib>

#include "libcommon/error.h"

namespace rs {

namespace {

struct SwitchEntry {
    const char* name;
    bool OctreeHeuristics::*flag;
};

constexpr SwitchEntry kSwitches[] = {
    {"range", &OctreeHeuristics::useValueRange},
    {"patch", &OctreeHeuristics::usePredominancePruning},
    {"1", &OctreeHeuristics::useHeuristic1},
    {"1bis", &OctreeHeuristics::useHeuristic1bis},
    {"3", &OctreeHeuristics::useHeuristic3},
    {"3bis", &OctreeHeuristics::useHeuristic3bis},
    {"4", &OctreeHeuristics::useHeuristic4},
    {"5", &OctreeHeuristics::useHeuristic5},
    {"0bis", &OctreeHeuristics::useTest0bis},
    {"t1", &OctreeHeuristics::useTest1},
    {"2bis", &OctreeHeuristics::useTest2bis},
    {"t3", &OctreeHeuristics::useTest3},
};

}  // namespace

const std::vector<std::string>& OctreeSwitchNames() {
    static const std::vector<std::string> names = [] {
        std::vector<std::string> n;
        for (const SwitchEntry& e : kSwitches) n.push_back(e.name);
        return n;
    }();
    return names;
}

bool* OctreeSwitch(OctreeHeuristics& heuristics, const std::string& name) {
    for (const SwitchEntry& e : kSwitches) {
        if (name == e.name) return &(heuristics.*e.flag);
    }
    return nullptr;
}

bool ParseOctreeSwitch(const std::string& assignment, ImplicitOverrides& overrides,
                       std::string& error) {
    const size_t eq = assignment.find('=');
    const std::string name = assignment.substr(0, eq);
    const std::string value = eq == std::string::npos ? "" : assignment.substr(eq + 1);
    OctreeHeuristics probe;
    if (!OctreeSwitch(probe, name)) {
        std::string names;
        for (const std::string& n : OctreeSwitchNames()) names += (names.empty() ? "" : ", ") + n;
        error = StringPrintf("unknown octree switch '%s' (expected NAME=on|off, NAME one of %s)",
                             name.c_str(), names.c_str());
        return false;
    }
    if (value != "on" && value != "off") {
        error = StringPrintf("octree switch '%s' needs =on or =off", name.c_str());
        return false;
    }
    overrides.switches.emplace_back(name, value == "on");
    return true;
}

namespace {

// The value as a finite number; false with a message otherwise.
bool ParseFinite(const std::string& value, double& number, std::string& error) {
    char* end = nullptr;
    number = std::strtod(value.c_str(), &end);
    if (value.empty() || *end != '\0' || !std::isfinite(number)) {
        error = "'" + value + "' is not a finite number";
        return false;
    }
    return true;
}

}  // namespace

bool ParseImplicitOverride(ImplicitOverrideKind kind, const std::string& value,
                           ImplicitOverrides& overrides, std::string& error) {
    if (kind == ImplicitOverrideKind::Switch) return ParseOctreeSwitch(value, overrides, error);
    if (kind == ImplicitOverrideKind::Method) {
        ImplicitMethod method;
        if (!ParseImplicitMethod(value, method)) {
            error = "unknown method '" + value + "' (expected " + ImplicitMethodNames() + ")";
            return false;
        }
        overrides.method = method;
        return true;
    }
    double number = 0;
    if (!ParseFinite(value, number, error)) return false;
    const bool positive = number > 0;
    switch (kind) {
        case ImplicitOverrideKind::Tolerance:
            if (!positive) error = "the tolerance must be > 0";
            if (positive) overrides.tolerance = number;
            break;
        case ImplicitOverrideKind::Depth: {
            const bool depth = number == std::floor(number) && number >= 0 && number <= 16;
            if (!depth) error = "the octree depth must be an integer in [0, 16]";
            if (depth) overrides.maxDepth = static_cast<int>(number);
            break;
        }
        case ImplicitOverrideKind::DRatio:
            overrides.dRatio = number;
            break;
        default:  // Step
            if (!positive) error = "the march step must be > 0";
            if (positive) overrides.step = number;
            break;
    }
    return error.empty();
}

}  // namespace rs
