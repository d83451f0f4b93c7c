// libFuzzer target for the whole front end: scene text (already preprocessed, or raw; the
// lexer accepts cpp line markers) → lexer → parser → scene setup → World::PrepareFrame, and
// the same for the built-in preprocessor's output when it takes the text (it leaves
// anything outside its subset to the system cpp, which the fuzzer does not run).
// rs::FatalError is a clean rejection (the library reports, then throws it); any other
// exception, crash, leak or sanitizer report is a finding. Run it with standard input
// closed or empty: an input may `#include "/dev/stdin"`.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

#include "libcommon/error.h"
#include "libcommon/limits.h"
#include "libshade/builtin_preprocessor.h"
#include "libshade/parser.h"
#include "libshade/scene.h"

namespace {

void ParseAndPrepare(std::string text) {
    try {
        rs::Scene scene = rs::ParseSceneText(std::move(text), "fuzz.ray", rs::RenderOptions{});
        if (scene.world) scene.world->PrepareFrame(scene.options.startTime, scene.options.shutter);
    } catch (const rs::FatalError&) {
    }
}

}  // namespace

// Included files are read up to the scene text limit: 1 MB here keeps an endless device
// (`#include "/dev/zero"`) from costing a gigabyte per input.
extern "C" int LLVMFuzzerInitialize(int*, char***) {
    std::string error;
    rs::SetLimit("sceneBytes=1000000", error);
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    std::optional<std::string> preprocessed;
    try {
        preprocessed = rs::PreprocessBuiltin(text, "fuzz.ray", {});
    } catch (const rs::FatalError&) {
    }
    ParseAndPrepare(text);
    if (preprocessed) ParseAndPrepare(std::move(*preprocessed));
    return 0;
}
