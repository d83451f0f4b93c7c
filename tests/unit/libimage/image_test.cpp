#include "libimage/image.h"

#include <png.h>
#include <zlib.h>

#include <unistd.h>

#include <algorithm>
#include <csetjmp>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>

#include <gtest/gtest.h>

namespace rs {
namespace {

namespace fs = std::filesystem;

// A fresh empty directory per test, removed afterwards.
class ImageFiles : public ::testing::Test {
  protected:
    void SetUp() override {
        const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        dir = fs::temp_directory_path() /
              (std::string("libimage_test_") + info->name() + "_" + std::to_string(getpid()));
        fs::remove_all(dir);
        fs::create_directories(dir);
    }
    void TearDown() override { fs::remove_all(dir); }

    std::string PathOf(const std::string& name) const { return (dir / name).string(); }

    std::vector<std::string> Listing() const {
        std::vector<std::string> names;
        for (const auto& entry : fs::directory_iterator(dir)) {
            names.push_back(entry.path().filename().string());
        }
        std::sort(names.begin(), names.end());
        return names;
    }

    void WriteBytes(const std::string& name, const std::vector<uint8_t>& bytes) const {
        std::ofstream out(PathOf(name), std::ios::binary);
        out.write(reinterpret_cast<const char*>(bytes.data()),
                  static_cast<std::streamsize>(bytes.size()));
    }

    std::vector<uint8_t> ReadBytes(const std::string& name) const {
        std::ifstream in(PathOf(name), std::ios::binary);
        return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    }

    fs::path dir;
};

// An image whose every byte differs from its neighbours: value = (7·index + 3) mod 256.
Image Pattern(int width, int height, int channels) {
    Image image;
    image.width = width;
    image.height = height;
    image.channels = channels;
    image.pixels.resize(static_cast<size_t>(width) * height * channels);
    for (size_t i = 0; i < image.pixels.size(); ++i) {
        image.pixels[i] = static_cast<uint8_t>((7 * i + 3) % 256);
    }
    return image;
}

struct RawPng {
    int width = 0, height = 0, bitDepth = 8, colorType = PNG_COLOR_TYPE_RGB;
    int interlace = PNG_INTERLACE_NONE;
    std::vector<std::vector<uint8_t>> rows;  // packed, as stored in the file
    std::vector<png_color> palette;
    std::vector<uint8_t> paletteAlpha;  // tRNS for palette images
    int transparentGrey = -1;           // tRNS for grey images
};

bool WriteRawPngBody(png_structp png, png_infop info, std::FILE* file, const RawPng& spec) {
    if (setjmp(png_jmpbuf(png))) return false;
    png_init_io(png, file);
    png_set_IHDR(png, info, spec.width, spec.height, spec.bitDepth, spec.colorType,
                 spec.interlace, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    if (!spec.palette.empty()) {
        png_set_PLTE(png, info, spec.palette.data(), static_cast<int>(spec.palette.size()));
    }
    if (!spec.paletteAlpha.empty()) {
        png_set_tRNS(png, info, spec.paletteAlpha.data(),
                     static_cast<int>(spec.paletteAlpha.size()), nullptr);
    }
    png_color_16 grey{};
    if (spec.transparentGrey >= 0) {
        grey.gray = static_cast<png_uint_16>(spec.transparentGrey);
        png_set_tRNS(png, info, nullptr, 0, &grey);
    }
    png_write_info(png, info);
    const int passes = png_set_interlace_handling(png);
    for (int pass = 0; pass < passes; ++pass) {
        for (const auto& row : spec.rows) png_write_row(png, row.data());
    }
    png_write_end(png, info);
    return true;
}

// Writes a PNG of any layout with libpng directly, independently of the code under test.
void WriteRawPng(const std::string& path, const RawPng& spec) {
    std::FILE* file = std::fopen(path.c_str(), "wb");
    ASSERT_NE(file, nullptr);
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
    png_infop info = png_create_info_struct(png);
    const bool ok = WriteRawPngBody(png, info, file, spec);
    png_destroy_write_struct(&png, &info);
    std::fclose(file);
    ASSERT_TRUE(ok);
}

void ExpectSameImage(const Image& a, const Image& b) {
    EXPECT_EQ(a.width, b.width);
    EXPECT_EQ(a.height, b.height);
    EXPECT_EQ(a.channels, b.channels);
    EXPECT_TRUE(a.pixels == b.pixels);
}

TEST_F(ImageFiles, PngRoundTripsEveryChannelCount) {
    for (int channels = 1; channels <= 4; ++channels) {
        SCOPED_TRACE(channels);
        const Image image = Pattern(13, 7, channels);
        const std::string path = PathOf("round.png");
        std::string error;
        ASSERT_TRUE(WriteImage(path, image, error)) << error;
        auto back = ReadImage(path, error);
        ASSERT_TRUE(back) << error;
        ExpectSameImage(*back, image);
    }
}

TEST_F(ImageFiles, PngCompressedInPiecesRoundTripsAndIsTheSameForAnyThreadCount) {
    // 300 rows make three pieces, deflated on up to as many threads and joined into one
    // zlib stream (libpng's reader checks its Adler-32); the bytes must not depend on the
    // number of threads.
    for (int channels : {1, 3, 4}) {
        std::vector<uint8_t> firstFile;
        for (int threads : {1, 2, 3, 8}) {
            SCOPED_TRACE(std::to_string(channels) + " channels, " + std::to_string(threads) + " threads");
            const Image image = Pattern(131, 300, channels);
            std::string error;
            ASSERT_TRUE(WriteImage(PathOf("pieces.png"), image, error, threads)) << error;
            auto back = ReadImage(PathOf("pieces.png"), error);
            ASSERT_TRUE(back) << error;
            ExpectSameImage(*back, image);
            const std::vector<uint8_t> file = ReadBytes("pieces.png");
            if (firstFile.empty()) firstFile = file;
            EXPECT_TRUE(file == firstFile);
        }
    }
}

TEST_F(ImageFiles, MtvRoundTripsRgbAndHasTheOriginalsLayout) {
    const Image image = Pattern(5, 3, 3);
    const std::string path = PathOf("round.mtv");
    std::string error;
    ASSERT_TRUE(WriteImage(path, image, error)) << error;
    std::vector<uint8_t> expected = {'5', ' ', '3', '\n'};
    expected.insert(expected.end(), image.pixels.begin(), image.pixels.end());
    EXPECT_TRUE(ReadBytes("round.mtv") == expected);
    EXPECT_TRUE(EncodeMtv(image) == expected);
    auto back = ReadImage(path, error);
    ASSERT_TRUE(back) << error;
    ExpectSameImage(*back, image);
}

TEST_F(ImageFiles, MtvStoresGreyAsEqualChannelsAndDropsAlpha) {
    Image grey;
    grey.width = 2;
    grey.height = 1;
    grey.channels = 2;
    grey.pixels = {10, 200, 30, 40};  // grey 10 alpha 200, grey 30 alpha 40
    const std::vector<uint8_t> expected = {'2', ' ', '1', '\n', 10, 10, 10, 30, 30, 30};
    EXPECT_TRUE(EncodeMtv(grey) == expected);

    Image rgba = Pattern(2, 2, 4);
    const std::string path = PathOf("rgba.mtv");
    std::string error;
    ASSERT_TRUE(WriteImage(path, rgba, error)) << error;
    auto back = ReadImage(path, error);
    ASSERT_TRUE(back) << error;
    ASSERT_EQ(back->channels, 3);
    for (int p = 0; p < 4; ++p) {
        for (int c = 0; c < 3; ++c) EXPECT_EQ(back->pixels[p * 3 + c], rgba.pixels[p * 4 + c]);
    }
}

TEST_F(ImageFiles, MtvHeaderMayUseTabsAndExtraBlanksButPixelsStartAfterOneNewline) {
    // The first pixel byte is '\n' itself: the header ends at the first newline only.
    WriteBytes("tabs.mtv", {' ', '1', '\t', ' ', '1', ' ', '\n', '\n', 'A', 'B'});
    std::string error;
    auto image = ReadImage(PathOf("tabs.mtv"), error);
    ASSERT_TRUE(image) << error;
    EXPECT_EQ(image->width, 1);
    EXPECT_EQ(image->height, 1);
    EXPECT_TRUE(image->pixels == (decltype(image->pixels){'\n', 'A', 'B'}));
}

TEST_F(ImageFiles, ReadsPalettePngAsRgbAndPaletteWithTransparencyAsRgba) {
    RawPng spec;
    spec.width = 3;
    spec.height = 1;
    spec.bitDepth = 8;
    spec.colorType = PNG_COLOR_TYPE_PALETTE;
    spec.palette = {{255, 0, 0}, {0, 128, 0}, {1, 2, 3}};
    spec.rows = {{2, 0, 1}};
    WriteRawPng(PathOf("pal.png"), spec);
    std::string error;
    auto image = ReadImage(PathOf("pal.png"), error);
    ASSERT_TRUE(image) << error;
    EXPECT_EQ(image->channels, 3);
    EXPECT_TRUE(image->pixels == (decltype(image->pixels){1, 2, 3, 255, 0, 0, 0, 128, 0}));

    spec.paletteAlpha = {0, 100};  // entry 2 has no tRNS entry: opaque
    WriteRawPng(PathOf("palt.png"), spec);
    image = ReadImage(PathOf("palt.png"), error);
    ASSERT_TRUE(image) << error;
    EXPECT_EQ(image->channels, 4);
    EXPECT_TRUE(image->pixels ==
                (decltype(image->pixels){1, 2, 3, 255, 255, 0, 0, 0, 0, 128, 0, 100}));
}

TEST_F(ImageFiles, ReadsLowBitDepthGreyScaledToEightBits) {
    // 2-bit grey 0,1,2,3 packed into one byte 0b00011011; expands to v·255/3.
    RawPng spec;
    spec.width = 4;
    spec.height = 1;
    spec.bitDepth = 2;
    spec.colorType = PNG_COLOR_TYPE_GRAY;
    spec.rows = {{0x1B}};
    WriteRawPng(PathOf("grey2.png"), spec);
    std::string error;
    auto image = ReadImage(PathOf("grey2.png"), error);
    ASSERT_TRUE(image) << error;
    EXPECT_EQ(image->channels, 1);
    EXPECT_TRUE(image->pixels == (decltype(image->pixels){0, 85, 170, 255}));
}

TEST_F(ImageFiles, ReadsGreyWithTransparentValueAsGreyAlpha) {
    RawPng spec;
    spec.width = 2;
    spec.height = 1;
    spec.colorType = PNG_COLOR_TYPE_GRAY;
    spec.transparentGrey = 5;
    spec.rows = {{5, 9}};
    WriteRawPng(PathOf("greyt.png"), spec);
    std::string error;
    auto image = ReadImage(PathOf("greyt.png"), error);
    ASSERT_TRUE(image) << error;
    EXPECT_EQ(image->channels, 2);
    EXPECT_TRUE(image->pixels == (decltype(image->pixels){5, 0, 9, 255}));
}

TEST_F(ImageFiles, ReadsSixteenBitSamplesScaledWithRounding) {
    // Big-endian 16-bit RGB samples: 257·v is exactly v; 0x8000 = 32768 maps to
    // 32768·255/65535 = 127.502 → 128; 0x0080 = 128 maps to 0.498 → 0.
    RawPng spec;
    spec.width = 1;
    spec.height = 2;
    spec.bitDepth = 16;
    spec.colorType = PNG_COLOR_TYPE_RGB;
    spec.rows = {{0x0C, 0x0C, 0xFF, 0xFF, 0x00, 0x00}, {0x80, 0x00, 0x00, 0x80, 0x01, 0x01}};
    WriteRawPng(PathOf("rgb16.png"), spec);
    std::string error;
    auto image = ReadImage(PathOf("rgb16.png"), error);
    ASSERT_TRUE(image) << error;
    EXPECT_EQ(image->channels, 3);
    EXPECT_TRUE(image->pixels == (decltype(image->pixels){12, 255, 0, 128, 0, 1}));
}

TEST_F(ImageFiles, ReadsInterlacedPng) {
    const Image image = Pattern(11, 9, 3);
    RawPng spec;
    spec.width = image.width;
    spec.height = image.height;
    spec.interlace = PNG_INTERLACE_ADAM7;
    for (int y = 0; y < image.height; ++y) {
        spec.rows.emplace_back(image.Row(y), image.Row(y) + image.width * 3);
    }
    WriteRawPng(PathOf("adam7.png"), spec);
    std::string error;
    auto back = ReadImage(PathOf("adam7.png"), error);
    ASSERT_TRUE(back) << error;
    ExpectSameImage(*back, image);
}

TEST_F(ImageFiles, EveryTruncationOfAPngIsAnErrorNamingTheFile) {
    std::string error;
    ASSERT_TRUE(WriteImage(PathOf("full.png"), Pattern(16, 16, 3), error)) << error;
    const std::vector<uint8_t> full = ReadBytes("full.png");
    for (size_t length = 0; length < full.size(); ++length) {
        SCOPED_TRACE(length);
        WriteBytes("cut.png", std::vector<uint8_t>(full.begin(), full.begin() + length));
        error.clear();
        EXPECT_FALSE(ReadImage(PathOf("cut.png"), error));
        EXPECT_NE(error.find(PathOf("cut.png")), std::string::npos) << error;
    }
}

TEST_F(ImageFiles, CorruptedPngBytesGiveErrorsNotCrashes) {
    std::string error;
    ASSERT_TRUE(WriteImage(PathOf("full.png"), Pattern(16, 16, 3), error)) << error;
    const std::vector<uint8_t> full = ReadBytes("full.png");
    const unsigned seed = 20261122;
    std::mt19937 random(seed);
    // Flip one byte after the signature; CRCs catch nearly all such damage, and whatever
    // slips through must still decode to a well-formed image.
    for (int trial = 0; trial < 200; ++trial) {
        std::vector<uint8_t> bytes = full;
        const size_t at = 8 + random() % (bytes.size() - 8);
        bytes[at] ^= static_cast<uint8_t>(1 + random() % 255);
        WriteBytes("bad.png", bytes);
        error.clear();
        auto image = ReadImage(PathOf("bad.png"), error);
        if (image) {
            EXPECT_EQ(image->pixels.size(),
                      static_cast<size_t>(image->width) * image->height * image->channels)
                << "seed " << seed;
        } else {
            EXPECT_NE(error.find("bad.png"), std::string::npos) << "seed " << seed;
        }
    }
}

TEST_F(ImageFiles, GarbageIsNeitherPngNorMtv) {
    const unsigned seed = 7;
    std::mt19937 random(seed);
    std::vector<uint8_t> bytes(1000);
    for (auto& b : bytes) b = static_cast<uint8_t>('a' + random() % 26);
    WriteBytes("garbage.bin", bytes);
    std::string error;
    EXPECT_FALSE(ReadImage(PathOf("garbage.bin"), error)) << "seed " << seed;
    EXPECT_NE(error.find("garbage.bin"), std::string::npos) << error;
    EXPECT_NE(error.find("header"), std::string::npos) << error;
}

TEST_F(ImageFiles, MtvErrorsForBadHeadersTruncationAndAbsurdSizes) {
    struct Case {
        std::string bytes;
        std::string expected;
    };
    const std::vector<Case> cases = {
        {"", "empty"},
        {"3 2", "header"},               // no newline
        {"3\n", "header"},               // one number
        {"3 x\n", "header"},             // not a number
        {"-3 2\n", "header"},            // sign
        {"3 2 1\n", "header"},           // three numbers
        {"0 5\n", "absurd"},             // empty image
        {"16385 16384\n", "absurd"},     // 2^28 + 16384 pixels
        {"1234567890 1\n", "header"},    // too many digits
        {"2 2\nabcdefghijk", "truncated"},  // 11 of 12 bytes
        {"\x89PNG", "truncated PNG"},       // half a PNG signature
        {"\x01\x02 3\n", "\"?? 3\""},       // binary shown as '?'
    };
    for (const auto& c : cases) {
        SCOPED_TRACE(c.bytes);
        WriteBytes("case.mtv", std::vector<uint8_t>(c.bytes.begin(), c.bytes.end()));
        std::string error;
        EXPECT_FALSE(ReadImage(PathOf("case.mtv"), error));
        EXPECT_NE(error.find("case.mtv"), std::string::npos) << error;
        EXPECT_NE(error.find(c.expected), std::string::npos) << error;
    }
}

void AppendChunk(std::vector<uint8_t>& out, const char* type, const std::vector<uint8_t>& data) {
    auto put32 = [&](uint32_t v) {
        for (int shift = 24; shift >= 0; shift -= 8) out.push_back(uint8_t(v >> shift));
    };
    put32(static_cast<uint32_t>(data.size()));
    const size_t start = out.size();
    out.insert(out.end(), type, type + 4);
    out.insert(out.end(), data.begin(), data.end());
    const auto length = static_cast<uInt>(out.size() - start);
    put32(static_cast<uint32_t>(crc32(0, out.data() + start, length)));
}

TEST_F(ImageFiles, PngLargerThanTwoToThe28PixelsIsRefused) {
    // 20000 × 20000 = 4·10^8 > 2^28 ≈ 2.68·10^8, yet within libpng's own 10^6 per-side limit.
    std::vector<uint8_t> bytes = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
    const uint32_t side = 20000;
    std::vector<uint8_t> ihdr;
    for (int i = 0; i < 2; ++i) {
        for (int shift = 24; shift >= 0; shift -= 8) ihdr.push_back(uint8_t(side >> shift));
    }
    ihdr.insert(ihdr.end(), {8, 2, 0, 0, 0});  // 8-bit RGB, deflate, adaptive, no interlace
    AppendChunk(bytes, "IHDR", ihdr);
    AppendChunk(bytes, "IDAT", {});
    AppendChunk(bytes, "IEND", {});
    WriteBytes("huge.png", bytes);
    std::string error;
    EXPECT_FALSE(ReadImage(PathOf("huge.png"), error));
    EXPECT_NE(error.find("huge.png"), std::string::npos) << error;
    EXPECT_NE(error.find("2^28"), std::string::npos) << error;
}

TEST_F(ImageFiles, MissingFileIsAnErrorNamingIt) {
    std::string error;
    EXPECT_FALSE(ReadImage(PathOf("absent.png"), error));
    EXPECT_NE(error.find("absent.png"), std::string::npos) << error;
    EXPECT_FALSE(ReadImage(dir.string(), error));  // a directory
    EXPECT_NE(error.find(dir.string()), std::string::npos) << error;
}

TEST_F(ImageFiles, WriteReplacesAnExistingFileAndLeavesNoTemporaries) {
    std::string error;
    ASSERT_TRUE(WriteImage(PathOf("out.png"), Pattern(4, 4, 3), error)) << error;
    const Image second = Pattern(2, 3, 1);
    ASSERT_TRUE(WriteImage(PathOf("out.png"), second, error)) << error;
    ASSERT_TRUE(WriteImage(PathOf("out.mtv"), second, error)) << error;
    EXPECT_EQ(Listing(), (std::vector<std::string>{"out.mtv", "out.png"}));
    auto back = ReadImage(PathOf("out.png"), error);
    ASSERT_TRUE(back) << error;
    ExpectSameImage(*back, second);
}

TEST_F(ImageFiles, FailedWritesLeaveNothingBehind) {
    std::string error;
    const std::string missing = PathOf("no/such/dir/out.png");
    EXPECT_FALSE(WriteImage(missing, Pattern(4, 4, 3), error));
    EXPECT_NE(error.find(missing), std::string::npos) << error;
    EXPECT_FALSE(fs::exists(missing));

    // The final name is a directory: the temporary is written, the rename fails, and the
    // temporary must be removed.
    fs::create_directory(dir / "taken.png");
    EXPECT_FALSE(WriteImage(PathOf("taken.png"), Pattern(4, 4, 3), error));
    EXPECT_NE(error.find("taken.png"), std::string::npos) << error;
    EXPECT_TRUE(fs::is_directory(dir / "taken.png"));

    Image inconsistent = Pattern(4, 4, 3);
    inconsistent.pixels.pop_back();
    EXPECT_FALSE(WriteImage(PathOf("bad.png"), inconsistent, error));
    EXPECT_NE(error.find("bad.png"), std::string::npos) << error;
    Image noChannels = Pattern(4, 4, 3);
    noChannels.channels = 5;
    EXPECT_FALSE(WriteImage(PathOf("bad.mtv"), noChannels, error));

    EXPECT_EQ(Listing(), (std::vector<std::string>{"taken.png"}));
}

TEST(TestTexture, MtvAndPngCopiesHaveIdenticalPixels) {
    const std::string scenes = RAYSHADE_SCENES_DIR;
    std::string error;
    auto mtv = ReadImage(scenes + "/testtex.img", error);
    ASSERT_TRUE(mtv) << error;
    auto png = ReadImage(scenes + "/testtex.png", error);
    ASSERT_TRUE(png) << error;
    EXPECT_EQ(mtv->width, 256);
    EXPECT_EQ(mtv->height, 256);
    ExpectSameImage(*mtv, *png);
}

}  // namespace
}  // namespace rs
