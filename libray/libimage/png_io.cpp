// PNG through libpng's classic interface. libpng reports errors by calling our error function,
// which must not return: it longjmps back to the setjmp in ReadPngInto/WritePngFrom. Those two
// functions own no objects with destructors, so the jump skips no C++ cleanup; the libpng
// structures are released by a guard in the calling frame whichever way the call ends.
#include <png.h>
#include <zlib.h>

#include <algorithm>
#include <atomic>
#include <csetjmp>
#include <thread>
#include <utility>
#include <vector>

#include "libcommon/large_buffer.h"
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

// Bytes whose fresh memory is touched only where written: a piece's output buffer is sized
// for the worst case but filled to a fraction of it.
using Bytes = std::vector<uint8_t, LargeBufferAllocator<uint8_t>>;

// The PNG image data (zlib stream) of `image`, as the runs of bytes that make it up when
// concatenated (the zlib header, the pieces, the checksum): every row preceded by filter
// type 1 ("sub": each byte minus the byte one pixel to its left), deflated at level 2 in
// pieces of kRowsPerPiece rows, shared out among `threads` threads. The pieces depend only
// on the image, so the file is the same whatever the number of threads. Each piece is raw
// deflate ending on a byte boundary (a sync flush; the last piece finishes the stream), so
// the pieces concatenate into one stream, and their Adler-32 checksums combine. Level 2
// rather than zlib's default 6: encoding is serial work at the end of every frame; on the
// shared scenes' 1024x1024 images level 2 took 9-18 ms against 11-23 ms at level 3 and
// 50-60 ms at level 6, for files 3-6% larger than level 3's. The sub filter alone rather
// than libpng's per-row choice among all five halved the time for files within a few
// percent of the size. Each thread deflates all its pieces with one zlib stream (reset
// between pieces), whose quarter megabyte of state would otherwise be fresh memory, and
// page faults, for every piece. Returns false when zlib fails (out of memory).
bool DeflateImageData(const Image& image, int threads, std::vector<Bytes>& stream) {
    constexpr int kLevel = 2;
    constexpr int kRowsPerPiece = 128;
    const size_t rowBytes = static_cast<size_t>(image.width) * image.channels;
    const int bpp = image.channels;
    const int pieces = (image.height + kRowsPerPiece - 1) / kRowsPerPiece;
    struct Piece {
        Bytes out;
        uLong adler = adler32(0, nullptr, 0);
        uLong length = 0;
        bool ok = false;
    };
    std::vector<Piece> parts(static_cast<size_t>(pieces));
    auto deflatePiece = [&](z_stream& z, int k) {
        Piece& part = parts[static_cast<size_t>(k)];
        const int y0 = k * kRowsPerPiece;
        const int y1 = std::min(image.height, y0 + kRowsPerPiece);
        if (deflateReset(&z) != Z_OK) return;
        const uLong raw = static_cast<uLong>((rowBytes + 1) * static_cast<size_t>(y1 - y0));
        part.out.resize(deflateBound(&z, raw) + 16);
        z.next_out = part.out.data();
        z.avail_out = static_cast<uInt>(part.out.size());
        std::vector<uint8_t> filtered(rowBytes + 1);
        bool ok = true;
        for (int y = y0; y < y1 && ok; ++y) {
            const uint8_t* row = image.Row(y);
            filtered[0] = 1;
            for (size_t i = 0; i < rowBytes; ++i)
                filtered[i + 1] = static_cast<uint8_t>(row[i] - (i >= static_cast<size_t>(bpp) ? row[i - bpp] : 0));
            part.adler = adler32(part.adler, filtered.data(), static_cast<uInt>(filtered.size()));
            z.next_in = filtered.data();
            z.avail_in = static_cast<uInt>(filtered.size());
            const int flush = y + 1 < y1 ? Z_NO_FLUSH : (k + 1 < pieces ? Z_SYNC_FLUSH : Z_FINISH);
            const int rc = deflate(&z, flush);
            ok = z.avail_in == 0 && (rc == Z_OK || rc == Z_STREAM_END || rc == Z_BUF_ERROR);
        }
        part.length = raw;
        part.out.resize(part.out.size() - z.avail_out);
        part.ok = ok;
    };
    std::atomic<int> next{0};
    auto worker = [&] {
        z_stream z{};
        if (deflateInit2(&z, kLevel, Z_DEFLATED, -15, 8, Z_DEFAULT_STRATEGY) != Z_OK) return;
        for (int k; (k = next.fetch_add(1)) < pieces;) deflatePiece(z, k);
        deflateEnd(&z);  // Z_DATA_ERROR for a piece left open after its sync flush: expected
    };
    std::vector<std::thread> helpers;
    for (int t = 1; t < std::min(threads, pieces); ++t) helpers.emplace_back(worker);
    worker();
    for (std::thread& t : helpers) t.join();

    // zlib header: deflate with a 32 KiB window (0x78), "fast" compression level (FLEVEL 1),
    // check bits making the 16-bit header a multiple of 31.
    stream.clear();
    stream.push_back({0x78, 0x5e});
    uLong adler = adler32(0, nullptr, 0);
    for (Piece& part : parts) {
        if (!part.ok) return false;
        adler = adler32_combine(adler, part.adler, static_cast<z_off_t>(part.length));
        stream.push_back(std::move(part.out));
    }
    Bytes check;
    for (int shift = 24; shift >= 0; shift -= 8) check.push_back(static_cast<uint8_t>(adler >> shift));
    stream.push_back(std::move(check));
    return true;
}

// libpng writes the signature, the header and the end; the image data is ours, compressed
// on `threads` threads, and written as one IDAT chunk run by run.
bool WritePngFrom(PngContext& context, std::FILE* file, const Image& image, int threads) {
    if (setjmp(png_jmpbuf(context.png))) return false;
    std::vector<Bytes> data;
    if (!DeflateImageData(image, threads, data)) {
        std::snprintf(context.message, sizeof context.message, "%s", "compression failed (out of memory)");
        return false;
    }
    size_t length = 0;
    for (const Bytes& run : data) length += run.size();
    png_init_io(context.png, file);
    png_set_IHDR(context.png, context.info, static_cast<png_uint_32>(image.width),
                 static_cast<png_uint_32>(image.height), 8, ColorType(image.channels),
                 PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_write_info(context.png, context.info);
    png_write_chunk_start(context.png, reinterpret_cast<png_const_bytep>("IDAT"),
                          static_cast<png_uint_32>(length));
    for (const Bytes& run : data) png_write_chunk_data(context.png, run.data(), run.size());
    png_write_chunk_end(context.png);
    png_write_chunk(context.png, reinterpret_cast<png_const_bytep>("IEND"), nullptr, 0);
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

bool EncodePng(std::FILE* file, const Image& image, const std::string& path, std::string& error,
               int threads) {
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
    if (!WritePngFrom(context, file, image, threads)) {
        error = path + ": cannot write PNG: " + context.message;
        return false;
    }
    return true;
}

}  // namespace rs
