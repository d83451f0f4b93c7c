// Partial-render files for continued rendering (-c). While a frame renders, its state is
// saved now and then to "<output>.partial"; `rayshade -c` loads it and finishes the frame,
// producing the image an uninterrupted run would have produced.
#pragma once

#include <string>

#include "rayshade/renderer.h"

namespace rs {

// The partial file that belongs to output image `outFile`.
std::string PartialStatePath(const std::string& outFile);

// Writes `state` with `fingerprint` (what identifies the render: scene and options) to
// `path`, through a temporary file renamed over it, so the file on disk is always either
// the previous complete state or the new one.
bool SaveFrameState(const std::string& path, const std::string& fingerprint,
                    const FrameState& state, std::string& error);

// Reads a state saved by SaveFrameState. Fails with a message when the file is missing,
// damaged, or was saved for a different render (another fingerprint).
bool LoadFrameState(const std::string& path, const std::string& fingerprint, FrameState& state,
                    std::string& error);

}  // namespace rs
