// ReadImage/WriteImage: format selection, validation, and the write-to-temporary-then-rename
// protocol.
#include "libimage/image.h"

#include <fcntl.h>
#include <unistd.h>
#include <png.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <memory>

#include "libimage/codec.h"

namespace rs {

namespace {

struct FileCloser {
    void operator()(std::FILE* file) const { std::fclose(file); }
};
using FilePtr = std::unique_ptr<std::FILE, FileCloser>;

constexpr size_t kPngSignatureSize = 8;

bool EndsWith(const std::string& s, const std::string& suffix) {
    return s.size() >= suffix.size() &&
           s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// A new file beside the destination, removed on destruction unless Commit() renamed it over
// the destination.
class TempFile {
  public:
    ~TempFile() {
        if (file_) std::fclose(file_);
        if (!name_.empty()) unlink(name_.c_str());
    }

    // Creates "<path>.tmp-<pid>-<n>" exclusively (never reusing an existing file), with the
    // usual 0666-minus-umask permissions a plain fopen would give.
    bool Open(const std::string& path, std::string& error) {
        static std::atomic<unsigned> counter{0};
        constexpr int kAttempts = 100;
        for (int attempt = 0; attempt < kAttempts; ++attempt) {
            std::string name = path + ".tmp-" + std::to_string(getpid()) + "-" +
                               std::to_string(counter.fetch_add(1));
            const int fd = open(name.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
            if (fd < 0) {
                if (errno == EEXIST) continue;
                error = path + ": cannot create a temporary file beside it: " +
                        std::strerror(errno);
                return false;
            }
            name_ = std::move(name);
            file_ = fdopen(fd, "wb");
            if (!file_) {
                error = path + ": cannot open a temporary file: " + std::strerror(errno);
                close(fd);
                return false;
            }
            return true;
        }
        error = path + ": cannot find an unused temporary file name beside it";
        return false;
    }

    std::FILE* File() const { return file_; }

    // Closes the file (reporting buffered write errors) and renames it to `path`.
    bool Commit(const std::string& path, std::string& error) {
        const bool writeFailed = std::ferror(file_) != 0;
        const int closeStatus = std::fclose(file_);
        const int closeErrno = errno;
        file_ = nullptr;
        if (writeFailed || closeStatus != 0) {
            error = path + ": write error: " + std::strerror(closeStatus != 0 ? closeErrno : EIO);
            return false;
        }
        if (std::rename(name_.c_str(), path.c_str()) != 0) {
            error = path + ": cannot rename the temporary file over it: " + std::strerror(errno);
            return false;
        }
        name_.clear();
        return true;
    }

  private:
    std::string name_;
    std::FILE* file_ = nullptr;
};

}  // namespace

std::optional<Image> ReadImage(const std::string& path, std::string& error) {
    FilePtr file(std::fopen(path.c_str(), "rb"));
    if (!file) {
        error = path + ": cannot open: " + std::strerror(errno);
        return std::nullopt;
    }
    unsigned char signature[kPngSignatureSize];
    const size_t got = std::fread(signature, 1, sizeof signature, file.get());
    if (got == 0) {
        error = std::ferror(file.get()) ? path + ": cannot read: " + std::strerror(errno)
                                        : path + ": empty file";
        return std::nullopt;
    }
    if (std::fseek(file.get(), 0, SEEK_SET) != 0) {
        error = path + ": cannot seek: " + std::strerror(errno);
        return std::nullopt;
    }
    if (png_sig_cmp(signature, 0, got) == 0) {
        if (got < kPngSignatureSize) {
            error = path + ": truncated PNG (the file ends inside the signature)";
            return std::nullopt;
        }
        return DecodePng(file.get(), path, error);
    }
    return DecodeMtv(file.get(), path, error);
}

bool WriteImage(const std::string& path, const Image& image, std::string& error, int threads) {
    const int64_t pixelCount = int64_t{image.width} * image.height;
    if (image.width < 1 || image.height < 1 || image.channels < 1 || image.channels > 4 ||
        pixelCount > kMaxImagePixels ||
        image.pixels.size() != static_cast<size_t>(pixelCount) * image.channels) {
        error = path + ": refusing to write an inconsistent image (" +
                std::to_string(image.width) + " x " + std::to_string(image.height) + " x " +
                std::to_string(image.channels) + " channels, " +
                std::to_string(image.pixels.size()) + " bytes)";
        return false;
    }
    TempFile temp;
    if (!temp.Open(path, error)) return false;
    if (EndsWith(path, ".mtv")) {
        const std::vector<uint8_t> bytes = EncodeMtv(image);
        if (std::fwrite(bytes.data(), 1, bytes.size(), temp.File()) != bytes.size()) {
            error = path + ": write error: " + std::strerror(errno);
            return false;
        }
    } else if (!EncodePng(temp.File(), image, path, error, threads)) {
        return false;
    }
    return temp.Commit(path, error);
}

}  // namespace rs
