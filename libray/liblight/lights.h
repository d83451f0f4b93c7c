// Factories for the light types of `light Intensity Type ...` (spec §3.7), read through
// the ArgReader after the type keyword. Each returns the light(s) it creates (an area
// light is nu·nv independent sub-lights); the parser then applies `noshadow` to all.
#pragma once

#include <memory>
#include <vector>

#include "libcommon/arg_reader.h"
#include "liblight/light.h"

namespace rs {

using LightList = std::vector<std::shared_ptr<Light>>;

LightList CreatePointLight(ArgReader& args, const Color& intensity);        // point P
LightList CreateDirectionalLight(ArgReader& args, const Color& intensity);  // directional V
LightList CreateExtendedLight(ArgReader& args, const Color& intensity);     // extended r P
LightList CreateSpotLight(ArgReader& args, const Color& intensity);  // spot P Q c [θi θo]
LightList CreateAreaLight(ArgReader& args, const Color& intensity);  // area P1 P2 nu P3 nv

}  // namespace rs
