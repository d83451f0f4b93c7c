// PNG through libpng's classic interface. libpng reports errors by calling our error function,
// which must not return: it longjmps back to the setjmp in ReadPngInto/WritePngFrom. Those two
// functions own no objects with destructors, so the jump skips no C++ cleanup; the libpng
// structures are released by a guard in the calling frame whichever way the call ends.
#include <png.h>

#include <csetjmp>

#include "libimage/codec.h"

namespace rs {

namespace {

struct PngContext {
    png_structp png = nullptr;
    png_infop info = nullptr;
    char message[256] = {};
};

[[noreturn]] void OnPngError(png_structp png, png_const_charp message) {
    auto* context = static_cast<PngContext*>(png_get_error_ptr(png));
    std::snprintf(context->message, sizeof context->message, "%s", message);
    png_longjmp(png, 1);
}

// Library code never prints, and libpng's warnings (odd ancillary chunks, sRGB profile
// quirks) do not make an image unusable, so they are dropped.
void OnPngWarning(png_structp, png_const_charp) {}

// Frees the read structures of `context` when the decoding frame ends.
struct ReadGuard {
    PngContext& context;
    ~ReadGuard() {
        png_destroy_read_struct(&context.png, context.info ? &context.info : nullptr, nullptr);
    }
};

struct WriteGuard {
    PngContext& context;
    ~WriteGuard() {
        png_destroy_write_struct(&context.png, context.info ? &context.info : nullptr);
    }
};

// Returns false after a libpng error (message in context.message) or a refused size.
bool ReadPngInto(PngContext& context, std::FILE* file, Image& image) {
    if (setjmp(png_jmpbuf(context.png))) return false;
    png_init_io(context.png, file);
    png_read_info(context.png, context.info);
    const png_uint_32 width = png_get_image_width(context.png, context.info);
    const png_uint_32 height = png_get_image_height(context.png, context.info);
    if (static_cast<int64_t>(width) * height > kMaxImagePixels) {
        std::snprintf(context.message, sizeof context.message,
                      "%u x %u pixels is more than the limit of 2^28", width, height);
        return false;
    }
    png_set_expand(context.png);
    png_set_scale_16(context.png);
    const int passes = png_set_interlace_handling(context.png);
    png_read_update_info(context.png, context.info);
    image.width = static_cast<int>(width);
    image.height = static_cast<int>(height);
    image.channels = png_get_channels(context.png, context.info);
    image.pixels.assign(static_cast<size_t>(width) * height * image.channels, 0);
    // Interlaced images need every pass; each pass fills in more of the same rows.
    for (int pass = 0; pass < passes; ++pass) {
        for (int y = 0; y < image.height; ++y) png_read_row(context.png, image.Row(y), nullptr);
    }
    png_read_end(context.png, nullptr);
    return true;
}

int ColorType(int channels) {
    switch (channels) {
        case 1: return PNG_COLOR_TYPE_GRAY;
        case 2: return PNG_COLOR_TYPE_GRAY_ALPHA;
        case 3: return PNG_COLOR_TYPE_RGB;
        default: return PNG_COLOR_TYPE_RGB_ALPHA;
    }
}

bool WritePngFrom(PngContext& context, std::FILE* file, const Image& image) {
    if (setjmp(png_jmpbuf(context.png))) return false;
    png_init_io(context.png, file);
    // zlib level 2 instead of the default 6: encoding is serial work at the end of every
    // frame. On the shared scenes' 1024x1024 images (sub filter) level 2 took 9-18 ms
    // against 11-23 ms at level 3 and 50-60 ms at level 6, for files 3-6% larger than
    // level 3's.
    png_set_compression_level(context.png, 2);
    // The "sub" filter alone instead of libpng's per-row choice among all five: trying every
    // filter on every row doubled the encoding time of rendered 1024x1024 frames (about
    // 0.1 s -> 0.05 s), and the files stayed within a few percent of the size (smaller for
    // some).
    png_set_filter(context.png, PNG_FILTER_TYPE_BASE, PNG_FILTER_SUB);
    png_set_IHDR(context.png, context.info, static_cast<png_uint_32>(image.width),
                 static_cast<png_uint_32>(image.height), 8, ColorType(image.channels),
                 PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_write_info(context.png, context.info);
    for (int y = 0; y < image.height; ++y) png_write_row(context.png, image.Row(y));
    png_write_end(context.png, context.info);
    return true;
}

}  // namespace

std::optional<Image> DecodePng(std::FILE* file, const std::string& path, std::string& error) {
    PngContext context;
    context.png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &context, OnPngError, OnPngWarning);
    if (!context.png) {
        error = path + ": cannot start the PNG decoder (out of memory)";
        return std::nullopt;
    }
    ReadGuard guard{context};
    context.info = png_create_info_struct(context.png);
    if (!context.info) {
        error = path + ": cannot start the PNG decoder (out of memory)";
        return std::nullopt;
    }
    Image image;
    if (!ReadPngInto(context, file, image)) {
        error = path + (std::feof(file) ? ": truncated PNG (the file ends early): "
                                        : ": unreadable PNG: ") +
                context.message;
        return std::nullopt;
    }
    return image;
}

bool EncodePng(std::FILE* file, const Image& image, const std::string& path, std::string& error) {
    PngContext context;
    context.png =
        png_create_write_struct(PNG_LIBPNG_VER_STRING, &context, OnPngError, OnPngWarning);
    if (!context.png) {
        error = path + ": cannot start the PNG encoder (out of memory)";
        return false;
    }
    WriteGuard guard{context};
    context.info = png_create_info_struct(context.png);
    if (!context.info) {
        error = path + ": cannot start the PNG encoder (out of memory)";
        return false;
    }
    if (!WritePngFrom(context, file, image)) {
        error = path + ": cannot write PNG: " + context.message;
        return false;
    }
    return true;
}

}  // namespace rs
