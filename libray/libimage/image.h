// In-memory images and their files: PNG (through libpng) and the original's generic "mtv"
// format (an ASCII "width height\n" header, then width×height RGB byte triples, top row
// first).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "libcommon/large_buffer.h"

namespace rs {

// 8-bit image, rows stored top row first, `channels` interleaved (1 grey, 2 grey+alpha,
// 3 RGB, 4 RGBA).
struct Image {
    int width = 0, height = 0, channels = 3;
    std::vector<uint8_t, LargeBufferAllocator<uint8_t>> pixels;

    uint8_t* Row(int y) { return pixels.data() + static_cast<size_t>(y) * width * channels; }
    const uint8_t* Row(int y) const {
        return pixels.data() + static_cast<size_t>(y) * width * channels;
    }
};

// Reads a PNG or mtv file (chosen by content: the PNG signature, else an mtv header).
// On failure returns nothing and sets `error` to a message naming the file.
std::optional<Image> ReadImage(const std::string& path, std::string& error);

// Writes `image` to `path`: mtv when the name ends in ".mtv", else PNG. The data goes to
// a temporary file beside `path` that is renamed over it only when complete, so an
// interrupted write never leaves a truncated image under the final name. PNG data is
// compressed on up to `threads` threads; the file does not depend on their number.
bool WriteImage(const std::string& path, const Image& image, std::string& error, int threads = 1);

// The mtv bytes of an image (RGB only), for the concatenated stream on stdout.
std::vector<uint8_t> EncodeMtv(const Image& image);

}  // namespace rs
