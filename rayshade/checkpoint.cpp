#include "rayshade/checkpoint.h"

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <type_traits>

#include "rayshade/cli.h"

namespace rs {

namespace {

constexpr char kMagic[] = "RAYSHADE-PARTIAL 2\n";
// Sizes beyond these cannot come from a render we would start (see main.cpp's limits).
constexpr uint64_t kMaxPixels = (1ULL << 28) + (1ULL << 16);
constexpr uint64_t kMaxFingerprint = 1 << 20;

class Writer {
  public:
    explicit Writer(std::ofstream& out) : out_(out) {}
    template <class T>
    void Put(const T& v) {
        static_assert(std::is_trivially_copyable_v<T>);
        out_.write(reinterpret_cast<const char*>(&v), sizeof v);
    }
    void PutBytes(const std::string& s) {
        Put<uint64_t>(s.size());
        out_.write(s.data(), static_cast<std::streamsize>(s.size()));
    }

  private:
    std::ofstream& out_;
};

class Reader {
  public:
    explicit Reader(std::ifstream& in) : in_(in) {}
    template <class T>
    bool Get(T& v) {
        static_assert(std::is_trivially_copyable_v<T>);
        return static_cast<bool>(in_.read(reinterpret_cast<char*>(&v), sizeof v));
    }
    bool GetBytes(std::string& s, uint64_t limit) {
        uint64_t n = 0;
        if (!Get(n) || n > limit) return false;
        s.resize(n);
        return static_cast<bool>(in_.read(s.data(), static_cast<std::streamsize>(n)));
    }

  private:
    std::ifstream& in_;
};

}  // namespace

std::string RenderFingerprint(const std::vector<std::string>& args, const std::string& inputFile) {
    std::string f;
    for (size_t i = 0; i < args.size(); ++i) {
        const std::string& a = args[i];
        const int count = a.size() == 2 && a[0] == '-' ? OptionArgumentCount(a[1]) : -1;
        if (count < 0) {
            f += "file " + a + '\n';
            continue;
        }
        std::string line = a;
        for (int k = 0; k < count && i + 1 < args.size(); ++k) line += ' ' + args[++i];
        if (a != "-c" && a != "-q" && a != "-v" && a != "-t" && a != "-V" && a != "-F") f += line + '\n';
    }
    // FNV-1a over the scene file taken 8 bytes at a time (large scenes: one step per byte
    // cost 3% of their setup), the tail byte by byte; every byte changes the result.
    uint64_t hash = 1469598103934665603ULL;
    if (std::FILE* in = inputFile.empty() ? nullptr : std::fopen(inputFile.c_str(), "rb")) {
        unsigned char block[65536];
        for (size_t n; (n = std::fread(block, 1, sizeof block, in)) > 0;) {
            size_t i = 0;
            for (; i + 8 <= n; i += 8) {
                uint64_t word;
                std::memcpy(&word, block + i, sizeof word);
                hash = (hash ^ word) * 1099511628211ULL;
            }
            for (; i < n; ++i) hash = (hash ^ block[i]) * 1099511628211ULL;
        }
        std::fclose(in);
    }
    return f + "scene " + std::to_string(hash);
}

SceneFileStamp StampSceneFile(const std::string& path) {
    struct stat info;
    if (path.empty() || stat(path.c_str(), &info) != 0) return {};
    const auto ns = [](const timespec& t) { return static_cast<long long>(t.tv_sec) * 1000000000LL + t.tv_nsec; };
    return {static_cast<long long>(info.st_dev), static_cast<long long>(info.st_ino),
            static_cast<long long>(info.st_size), ns(info.st_mtim), ns(info.st_ctim)};
}

LazyRenderFingerprint::LazyRenderFingerprint(std::vector<std::string> args, std::string inputFile)
    : args_(std::move(args)), inputFile_(std::move(inputFile)), readStamp_(StampSceneFile(inputFile_)) {}

const std::string& LazyRenderFingerprint::Get() {
    if (fingerprint_.empty()) {
        fingerprint_ = RenderFingerprint(args_, inputFile_);
        if (StampSceneFile(inputFile_) != readStamp_) fingerprint_ += "\nscene changed while rendering";
    }
    return fingerprint_;
}

std::string DescribeFingerprintDifference(const std::string& saved, const std::string& current) {
    auto lines = [](const std::string& text) {
        std::vector<std::string> out;
        for (size_t start = 0; start < text.size();) {
            size_t end = text.find('\n', start);
            if (end == std::string::npos) end = text.size();
            out.push_back(text.substr(start, end - start));
            start = end + 1;
        }
        return out;
    };
    const std::vector<std::string> was = lines(saved), now = lines(current);
    auto only = [](const std::vector<std::string>& a, const std::vector<std::string>& b) {
        std::vector<std::string> rest = b;  // the lines of a not matched in b (a multiset)
        for (const std::string& line : a) {
            auto it = std::find(rest.begin(), rest.end(), line);
            if (it == rest.end()) return line;
            rest.erase(it);
        }
        return std::string();
    };
    auto option = [](const std::string& line) { return line.substr(0, line.find(' ')); };
    const std::string lost = only(was, now), added = only(now, was);
    if (lost.empty() && added.empty()) return {};
    // Another hash, or the line of a scene that changed while a render read it (on either
    // side: the saved render's, or this one's when it changed during parsing).
    const bool lostScene = option(lost) == "scene", addedScene = option(added) == "scene";
    if ((lostScene && (added.empty() || addedScene)) || (addedScene && lost.empty()))
        return "the scene file has changed since";
    if (!lost.empty() && !added.empty() && option(lost) == option(added))
        return "it was saved with " + lost + ", not " + added;
    if (!lost.empty() && option(lost) != "scene") return "it was saved with " + lost + ", which this command lacks";
    return "it was saved without " + added + ", which this command gives";
}

std::string PartialStatePath(const std::string& outFile) { return outFile + ".partial"; }

bool SaveFrameState(const std::string& path, const std::string& fingerprint,
                    const FrameState& state, std::string& error) {
    const std::string temp = path + ".tmp-" + std::to_string(getpid());
    {
        std::ofstream out(temp, std::ios::binary | std::ios::trunc);
        if (!out) {
            error = "cannot write partial state '" + temp + "': " + std::strerror(errno);
            return false;
        }
        Writer w(out);
        out.write(kMagic, sizeof kMagic - 1);
        w.PutBytes(fingerprint);
        w.Put<int32_t>(state.frame);
        w.Put<int32_t>(state.width);
        w.Put<int32_t>(state.rows);
        w.Put<int32_t>(static_cast<int32_t>(state.phase));
        w.Put<int32_t>(state.pass);
        w.Put<uint64_t>(state.todo.size());
        for (long t : state.todo) w.Put<int64_t>(t);
        w.Put<uint64_t>(state.pixels.size());
        for (const PixelState& p : state.pixels) {
            w.Put(p.r);
            w.Put(p.g);
            w.Put(p.b);
            w.Put(p.alpha);
            w.Put(p.singleCell);
            w.Put<uint8_t>(static_cast<uint8_t>((p.sampled ? 1 : 0) | (p.supersampled ? 2 : 0)));
        }
        out.flush();
        if (!out) {
            error = "cannot write partial state '" + temp + "' (disk full?)";
            out.close();
            std::remove(temp.c_str());
            return false;
        }
    }
    if (std::rename(temp.c_str(), path.c_str()) != 0) {
        error = "cannot rename '" + temp + "' to '" + path + "': " + std::strerror(errno);
        std::remove(temp.c_str());
        return false;
    }
    return true;
}

bool LoadFrameState(const std::string& path, const std::string& fingerprint, FrameState& state,
                    std::string& error) {
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        error = "nothing to continue: cannot open '" + path + "': " + std::strerror(errno);
        return false;
    }
    auto damaged = [&] {
        error = "partial state '" + path + "' is damaged or truncated";
        return false;
    };
    char magic[sizeof kMagic - 1];
    if (!in.read(magic, sizeof magic) || std::memcmp(magic, kMagic, sizeof magic) != 0) return damaged();
    Reader r(in);
    std::string saved;
    if (!r.GetBytes(saved, kMaxFingerprint)) return damaged();
    if (saved != fingerprint) {
        error = "partial state '" + path + "' belongs to another render: " +
                DescribeFingerprintDifference(saved, fingerprint) +
                " (-c needs the same command and scene file)";
        return false;
    }
    int32_t frame, width, rows, phase, pass;
    if (!r.Get(frame) || !r.Get(width) || !r.Get(rows) || !r.Get(phase) || !r.Get(pass))
        return damaged();
    if (width < 1 || rows < 2 || phase < 0 || phase > 3 || pass < 0 ||
        static_cast<uint64_t>(width) * static_cast<uint64_t>(rows) > kMaxPixels)
        return damaged();
    const uint64_t pixelCount = static_cast<uint64_t>(width) * static_cast<uint64_t>(rows);
    uint64_t todoCount = 0;
    if (!r.Get(todoCount) || todoCount > pixelCount) return damaged();
    state.todo.resize(todoCount);
    for (long& t : state.todo) {
        int64_t v;
        if (!r.Get(v) || v < 0 || static_cast<uint64_t>(v) >= pixelCount) return damaged();
        t = static_cast<long>(v);
    }
    // The renderer keeps the list in increasing order; earlier versions saved it in the
    // order the pixels were queued.
    std::sort(state.todo.begin(), state.todo.end());
    uint64_t count = 0;
    if (!r.Get(count) || count != pixelCount) return damaged();
    state.pixels.resize(count);
    for (PixelState& p : state.pixels) {
        p = PixelState{};
        uint8_t flags = 0;
        if (!r.Get(p.r) || !r.Get(p.g) || !r.Get(p.b) || !r.Get(p.alpha) ||
            !r.Get(p.singleCell) || !r.Get(flags))
            return damaged();
        p.sampled = flags & 1;
        p.supersampled = flags & 2;
    }
    state.frame = frame;
    state.width = width;
    state.rows = rows;
    state.phase = static_cast<FrameState::Phase>(phase);
    state.pass = pass;
    return true;
}

}  // namespace rs
