// The original's generic "mtv" image format: "width height\n", then RGB bytes, top row first.
#include <sys/stat.h>

#include <cctype>

#include "libimage/codec.h"

namespace rs {

namespace {

// Longest header line accepted, '\n' excluded: two 9-digit numbers and generous spacing.
constexpr int kMaxHeaderLength = 64;
// Up to 9 digits per number keeps the parse inside int; anything wider exceeds
// kMaxImagePixels anyway.
constexpr int kMaxDigits = 9;

// Parses "[blanks] digits blanks digits [blanks]" (blanks: spaces or tabs) into two numbers.
bool ParseHeader(const std::string& line, int64_t& width, int64_t& height) {
    size_t i = 0;
    auto skipBlanks = [&]() {
        size_t start = i;
        while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
        return i > start;
    };
    auto readNumber = [&](int64_t& value) {
        size_t start = i;
        value = 0;
        while (i < line.size() && std::isdigit(static_cast<unsigned char>(line[i]))) {
            value = value * 10 + (line[i] - '0');
            ++i;
        }
        return i > start && i - start <= static_cast<size_t>(kMaxDigits);
    };
    skipBlanks();
    if (!readNumber(width) || !skipBlanks() || !readNumber(height)) return false;
    skipBlanks();
    return i == line.size();
}

// `text` with every byte outside printable ASCII shown as '?', for error messages.
std::string Printable(std::string text) {
    for (char& c : text) {
        if (!std::isprint(static_cast<unsigned char>(c))) c = '?';
    }
    return text;
}

}  // namespace

std::optional<Image> DecodeMtv(std::FILE* file, const std::string& path, std::string& error) {
    std::string line;
    for (;;) {
        const int c = std::fgetc(file);
        if (c == '\n') break;
        if (c == EOF || static_cast<int>(line.size()) == kMaxHeaderLength) {
            error = path + ": neither a PNG nor an mtv image (no \"width height\" header line)";
            return std::nullopt;
        }
        line.push_back(static_cast<char>(c));
    }
    int64_t width = 0, height = 0;
    if (!ParseHeader(line, width, height)) {
        error = path + ": neither a PNG nor an mtv image (bad header \"" + Printable(line) +
                "\")";
        return std::nullopt;
    }
    if (width < 1 || height < 1 || width * height > kMaxImagePixels) {
        error = path + ": mtv header gives an absurd size " + std::to_string(width) + " x " +
                std::to_string(height) + " (at least 1 x 1, at most 2^28 pixels)";
        return std::nullopt;
    }
    const size_t bytes = static_cast<size_t>(width * height * 3);
    auto truncated = [&](size_t available) {
        error = path + ": truncated mtv image: " + std::to_string(width) + " x " +
                std::to_string(height) + " needs " + std::to_string(bytes) +
                " bytes of pixels, found " + std::to_string(available);
        return std::nullopt;
    };
    // For a regular file, check the length before allocating for a possibly corrupt header.
    struct stat info;
    const long offset = std::ftell(file);
    if (fstat(fileno(file), &info) == 0 && S_ISREG(info.st_mode) && offset >= 0 &&
        static_cast<uint64_t>(info.st_size - offset) < bytes) {
        return truncated(static_cast<size_t>(info.st_size - offset));
    }
    Image image;
    image.width = static_cast<int>(width);
    image.height = static_cast<int>(height);
    image.channels = 3;
    image.pixels.resize(bytes);
    const size_t got = std::fread(image.pixels.data(), 1, bytes, file);
    if (got != bytes) {
        if (std::ferror(file)) {
            error = path + ": read error in mtv pixel data";
            return std::nullopt;
        }
        return truncated(got);
    }
    return image;
}

// mtv holds RGB only: grey (and grey+alpha) images are written with the grey value in all
// three channels, and alpha is dropped.
std::vector<uint8_t> EncodeMtv(const Image& image) {
    const std::string header =
        std::to_string(image.width) + " " + std::to_string(image.height) + "\n";
    std::vector<uint8_t> bytes(header.begin(), header.end());
    const size_t pixelCount = static_cast<size_t>(image.width) * image.height;
    bytes.reserve(header.size() + pixelCount * 3);
    const bool grey = image.channels < 3;
    for (size_t p = 0; p < pixelCount; ++p) {
        const uint8_t* px = image.pixels.data() + p * image.channels;
        for (int c = 0; c < 3; ++c) bytes.push_back(grey ? px[0] : px[c]);
    }
    return bytes;
}

}  // namespace rs
