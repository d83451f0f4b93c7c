// The scene-file parser (spec §2, §3): a hand-written recursive-descent parser that builds
// an rs::Scene — camera, options, lights, atmosphere and the World's node graph.
#pragma once

#include <string>
#include <vector>

#include "libshade/scene.h"

namespace rs {

struct ParseInput {
    std::string path;  // empty: standard input
    bool useCpp = true;
    std::string cppArgs;                    // the -P argument: extra words for cpp
    std::vector<std::string> extraDefines;  // NAME or NAME=VALUE, passed to cpp as -D...
};

// Model nesting limit of the original (spec §3.10): aggregates nested in aggregates, through
// named objects included.
inline constexpr int kMaxModelDepth = 32;

// Parses a scene. `options` arrives with the command line's settings (and Set flags);
// throws rs::FatalError (through rs::Report) on errors, with file:line.
Scene ParseScene(const ParseInput& input, const RenderOptions& options);

// The same for text that is already preprocessed (or is not to be); `fileName` names it in
// messages until a line marker says otherwise.
Scene ParseSceneText(std::string text, const std::string& fileName,
                     const RenderOptions& options);

}  // namespace rs
