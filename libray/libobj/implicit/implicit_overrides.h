// Layer 8 of the implicit module: command-line overrides of every implicit object's
// intersection settings (rayquery -m/-e/-d/-r/-k/-H, rayshade -M/-I/-K/-J/-B/-H), applied
// through ImplicitSurface::ApplyOverrides (ApplyImplicitOverrides walks a scene).
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "libobj/implicit/lg_octree.h"
#include "libobj/implicit/method_registry.h"

namespace rs {

struct ImplicitOverrides {
    std::optional<ImplicitMethod> method;
    std::optional<double> tolerance;  // every method's root accuracy (object-space distance)
    std::optional<int> maxDepth;      // octree depth (patches, kb89)
    std::optional<double> dRatio;     // Gascuel's Dratio (patches)
    std::optional<double> step;       // march step (object-space distance)
    // OctreeHeuristics switches by name (OctreeSwitchNames), applied in order after the
    // method's defaults.
    std::vector<std::pair<std::string, bool>> switches;

    bool Empty() const {
        return !method && !tolerance && !maxDepth && !dRatio && !step && switches.empty();
    }
};

// The names of the octree switches, in the order of OctreeHeuristics:
//   range (useValueRange), patch (usePredominancePruning), 1, 1bis, 3, 3bis, 4, 5 (build
//   heuristics useHeuristic…), 0bis, t1, 2bis, t3 (search tests useTest0bis, useTest1,
//   useTest2bis, useTest3).
const std::vector<std::string>& OctreeSwitchNames();
// The flag named `name` in `settings`, or null for an unknown name.
bool* OctreeSwitch(OctreeHeuristics& heuristics, const std::string& name);

// Parses "NAME=on|off" (NAME from OctreeSwitchNames) and appends it to overrides.switches;
// false with a message otherwise.
bool ParseOctreeSwitch(const std::string& assignment, ImplicitOverrides& overrides,
                       std::string& error);

// The settings a command-line override may take, one option each in rayshade (-M, -I,
// -K, -J, -B, -H) and rayquery (-m, -e, -d, -r, -k, -H).
enum class ImplicitOverrideKind { Method, Tolerance, Depth, DRatio, Step, Switch };

// Parses the value of one override into `overrides`: a method name (Method), a finite
// number (Tolerance and Step > 0, Depth an integer in [0, 16], any DRatio), or NAME=on|off
// (Switch). False with a message without the option's name otherwise. Both programs parse
// their implicit options through this one function.
bool ParseImplicitOverride(ImplicitOverrideKind kind, const std::string& value,
                           ImplicitOverrides& overrides, std::string& error);

class Object;

// Applies the overrides to every implicit object below `root` (each shared node once) and
// rebuilds them. Returns the number of objects changed, or −1 with `error` set when one
// cannot take the method (e.g. polynomial on a non-blob object); objects met before it keep
// their new settings. Defined with the primitive (implicit_surface.cpp), which this header
// does not include.
int ApplyImplicitOverrides(Object& root, const ImplicitOverrides& overrides, std::string& error);

}  // namespace rs
