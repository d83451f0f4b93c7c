// The file codecs behind ReadImage/WriteImage (internal to libimage). Each takes an open stdio
// stream and the file's name, which every error message starts with.
#pragma once

#include <cstdint>
#include <cstdio>
#include <optional>
#include <string>

#include "libimage/image.h"

namespace rs {

// Largest image accepted, in pixels: 2^28 (16384 × 16384). Larger headers are taken as corrupt
// rather than allocating gigabytes; 2^28 × 4 channels still fits comfortably in size_t.
inline constexpr int64_t kMaxImagePixels = int64_t{1} << 28;

// Decodes the PNG stream `file`, positioned at its start. Every PNG variant libpng reads comes
// back as 8 bits per channel: palettes expand to RGB, grey below 8 bits to 8 bits,
// transparency chunks to an alpha channel, and 16-bit samples scale to round(v·255/65535).
// No gamma correction is applied (the stored values are returned).
std::optional<Image> DecodePng(std::FILE* file, const std::string& path, std::string& error);

// Writes `image` (already validated: 1–4 channels, consistent sizes) as an 8-bit,
// non-interlaced PNG of the matching colour type (grey, grey+alpha, RGB, RGBA), compressing
// on up to `threads` threads.
bool EncodePng(std::FILE* file, const Image& image, const std::string& path, std::string& error,
               int threads);

// Decodes an mtv stream: an ASCII header "width height" (decimal, separated by spaces or tabs)
// ended by exactly one '\n', then width×height RGB triples, top row first. Bytes after the
// first image are ignored (a stream may concatenate frames).
std::optional<Image> DecodeMtv(std::FILE* file, const std::string& path, std::string& error);

}  // namespace rs
