// libFuzzer target for the whole front end: scene text (already preprocessed, or raw; the
// lexer accepts cpp line markers) → lexer → parser → scene setup → World::PrepareFrame.
// rs::FatalError is a clean rejection (the library reports, then throws it); any other
// exception, crash, leak or sanitizer report is a finding.
#include <cstddef>
#include <cstdint>
#include <string>

#include "libcommon/error.h"
#include "libshade/parser.h"
#include "libshade/scene.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    try {
        rs::Scene scene = rs::ParseSceneText(text, "fuzz.ray", rs::RenderOptions{});
        if (scene.world) scene.world->PrepareFrame(scene.options.startTime, scene.options.shutter);
    } catch (const rs::FatalError&) {
        return 0;
    }
    return 0;
}
