// Doubles rounded to single precision in a chosen direction, for single-precision tests
// that must stay conservative (the hierarchy's wide boxes and segments, octree bounds).
#pragma once

#include <bit>
#include <cstdint>
#include <limits>

namespace rs {

// The largest float <= x (-inf below float's range; NaN stays NaN).
inline float FloatAtOrBelow(double x) {
    const float f = static_cast<float>(x);
    if (!(static_cast<double>(f) > x)) return f;
    // f > x: f is neither NaN nor -inf, and not +0 (the cast keeps x's sign, and -0 > x
    // for a tiny negative x). The next float down is one step of the magnitude bits: down
    // for a positive f (from +inf, the largest finite float), up for a negative one (from
    // -0, the negative smallest subnormal).
    const uint32_t bits = std::bit_cast<uint32_t>(f);
    return std::bit_cast<float>(f > 0 ? bits - 1 : bits + 1);
}

// The smallest float >= x (+inf above float's range; NaN stays NaN).
inline float FloatAtOrAbove(double x) {
    const float f = static_cast<float>(x);
    if (!(static_cast<double>(f) < x)) return f;
    const uint32_t bits = std::bit_cast<uint32_t>(f);  // the mirror image of FloatAtOrBelow
    return std::bit_cast<float>(f < 0 ? bits - 1 : bits + 1);
}

}  // namespace rs
