// Partial-render files for continued rendering (-c). While a frame renders, its state is
// saved now and then to "<output>.partial"; `rayshade -c` loads it and finishes the frame,
// producing the image an uninterrupted run would have produced.
#pragma once

#include <string>
#include <vector>

#include "rayshade/renderer.h"

namespace rs {

// What identifies a render for continuing it: one line per command-line option with its
// arguments ("-R 320 240"), in the order given, leaving out those that cannot change the
// image (-c, -q, -v, -t, -V, -F); a line "file NAME" for the scene file as named; and last
// a line "scene HASH" with a hash of the scene file's bytes. A partial state saved under
// another fingerprint is refused.
std::string RenderFingerprint(const std::vector<std::string>& args, const std::string& inputFile);

// The scene file's identity and version as the file system gives them (device, inode, size,
// modification and status-change times; all zero for standard input or a file that cannot
// be examined).
struct SceneFileStamp {
    long long device = 0, inode = 0, size = 0, modifiedNs = 0, changedNs = 0;
    bool operator==(const SceneFileStamp&) const = default;
};
SceneFileStamp StampSceneFile(const std::string& path);

// The fingerprint of a render, computed when first asked for. Hashing the scene file is a
// pass over all of it (on tetra, 25 MB, about 2% of the setup, on one thread), and only
// saving a partial state (every CheckpointSeconds of rendering, or on an interrupt) or
// loading one (-c) needs it. The file is stamped when this is constructed, before the
// scene is read; if the stamp taken after hashing differs, the hashed bytes may not be the
// rendered ones, and the fingerprint gets a last line "scene changed while rendering" that
// no later run's has, so that state is refused. Not thread-safe: ask from one thread.
class LazyRenderFingerprint {
  public:
    LazyRenderFingerprint(std::vector<std::string> args, std::string inputFile);
    const std::string& Get();

  private:
    std::vector<std::string> args_;
    std::string inputFile_;
    SceneFileStamp readStamp_;
    std::string fingerprint_;  // empty until Get
};

// What differs between two fingerprints, for the refusal message: the first option the
// saved render had and this one lacks (or has with other arguments), else the first one
// only this one has, else the scene file (e.g. "it was saved with -R 320 240, not -R 256
// 256"). Empty when they are equal.
std::string DescribeFingerprintDifference(const std::string& saved, const std::string& current);

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
