// Global numeric constants of the Rayshade model (spec, "Global numeric constants").
#pragma once

namespace rs {

// Generic tolerance and the minimum hit distance of eye, reflected and refracted rays.
inline constexpr double kEpsilon = 1e-5;
// Minimum hit distance of shadow rays: a little larger than kEpsilon so a surface does not
// shadow itself through round-off in the hit point.
inline constexpr double kShadowEpsilon = 4e-5;
// "Infinite" distance: the maximum distance of eye rays and the distance of a miss.
inline constexpr double kFar = 1e14;
inline constexpr double kPi = 3.14159265358979323846;

}  // namespace rs
