#include "libshade/preprocess.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <optional>
#include <sstream>

#include "libcommon/large_buffer.h"
#include "libcommon/limits.h"
#include "libcommon/error.h"
#include "libshade/builtin_preprocessor.h"

extern char** environ;

namespace rs {

namespace {

const SourceLocation kNoLocation{};

// Appends everything readable from `fd` to `out`; returns false at end of file.
bool Drain(int fd, std::string& out) {
    char buf[65536];
    while (true) {
        ssize_t n = read(fd, buf, sizeof buf);
        if (n > 0) {
            out.append(buf, static_cast<size_t>(n));
            return true;
        }
        if (n == 0) return false;
        if (errno == EINTR) continue;
        if (errno == EAGAIN) return true;
        return false;
    }
}

std::string ReadRaw(const std::string& path) {
    int fd = path.empty() ? STDIN_FILENO : open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0)
        Report(Severity::Abort, kNoLocation, "Cannot open %s: %s", path.c_str(), strerror(errno));
    std::string text;
    struct stat info;
    if (fstat(fd, &info) == 0 && S_ISREG(info.st_mode)) {
        // One allocation for the whole file (the limit is checked as it is read), on huge
        // pages: the text is written once here and kept through parsing.
        text.reserve(static_cast<size_t>(
            std::min<off_t>(info.st_size, static_cast<off_t>(Limits().sceneBytes)) + 1));
        AdviseHugePages(text.data(), text.capacity());
    }
    while (Drain(fd, text)) {
        if (text.size() > static_cast<size_t>(Limits().sceneBytes)) {
            if (!path.empty()) close(fd);
            Report(Severity::Abort, kNoLocation, "Scene input exceeds %zu bytes", static_cast<size_t>(Limits().sceneBytes));
        }
    }
    if (!path.empty()) close(fd);
    return text;
}

std::vector<std::string> SplitWords(const std::string& s) {
    std::vector<std::string> words;
    std::istringstream in(s);
    std::string w;
    while (in >> w) words.push_back(w);
    return words;
}

// cpp's diagnostics without the context it adds around them ("In file included from" chains,
// source excerpts with carets, "compilation terminated."): only the lines that carry
// "file:line:col: error|warning: ...". A self-including file thus gives one line instead of
// 200 include levels. Text without such lines is returned unchanged.
std::string CppDiagnostics(const std::string& err) {
    std::string kept;
    std::istringstream in(err);
    for (std::string line; std::getline(in, line);) {
        if (line.find(": error: ") == std::string::npos &&
            line.find(": fatal error: ") == std::string::npos &&
            line.find(": warning: ") == std::string::npos)
            continue;
        if (!kept.empty()) kept += '\n';
        kept += line;
    }
    return kept.empty() ? err : kept;
}

// Runs cpp with `args` (argv[0] included), returning its standard output.
std::string RunCpp(const std::vector<std::string>& args) {
    int outPipe[2], errPipe[2];
    if (pipe2(outPipe, O_CLOEXEC) != 0)
        Report(Severity::Abort, kNoLocation, "Cannot create a pipe: %s", strerror(errno));
    if (pipe2(errPipe, O_CLOEXEC) != 0) {
        close(outPipe[0]);
        close(outPipe[1]);
        Report(Severity::Abort, kNoLocation, "Cannot create a pipe: %s", strerror(errno));
    }
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_adddup2(&actions, outPipe[1], STDOUT_FILENO);
    posix_spawn_file_actions_adddup2(&actions, errPipe[1], STDERR_FILENO);

    std::vector<char*> argv;
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);

    pid_t pid = -1;
    int rc = posix_spawnp(&pid, argv[0], &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    close(outPipe[1]);
    close(errPipe[1]);
    if (rc != 0) {
        close(outPipe[0]);
        close(errPipe[0]);
        Report(Severity::Abort, kNoLocation, "Cannot run the C preprocessor '%s': %s", argv[0],
               strerror(rc));
    }

    // Read both pipes together so neither can fill up and stall cpp.
    std::string out, err;
    bool outOpen = true, errOpen = true, tooBig = false;
    while ((outOpen || errOpen) && !tooBig) {
        pollfd fds[2] = {{outOpen ? outPipe[0] : -1, POLLIN, 0},
                         {errOpen ? errPipe[0] : -1, POLLIN, 0}};
        if (poll(fds, 2, -1) < 0) {
            if (errno == EINTR) continue;
            break;
        }
        if (outOpen && (fds[0].revents & (POLLIN | POLLHUP | POLLERR)))
            outOpen = Drain(outPipe[0], out);
        if (errOpen && (fds[1].revents & (POLLIN | POLLHUP | POLLERR)))
            errOpen = Drain(errPipe[0], err);
        tooBig = out.size() > static_cast<size_t>(Limits().sceneBytes) || err.size() > static_cast<size_t>(Limits().sceneBytes);
    }
    close(outPipe[0]);
    close(errPipe[0]);
    if (tooBig) kill(pid, SIGTERM);
    int status = 0;
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    err = CppDiagnostics(err);
    while (!err.empty() && err.back() == '\n') err.pop_back();
    if (tooBig)
        Report(Severity::Abort, kNoLocation, "Scene input exceeds %zu bytes", static_cast<size_t>(Limits().sceneBytes));
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
        Report(Severity::Abort, kNoLocation, "The C preprocessor failed%s%s",
               err.empty() ? "" : ":\n", err.c_str());
    }
    if (!err.empty()) Report(Severity::Warn, kNoLocation, "cpp: %s", err.c_str());
    return out;
}

// The macros of cpp arguments and extra definitions when every one is a -D definition
// (`-DNAME`, `-DNAME=body`; `defines` hold them without the -D); nothing otherwise.
std::optional<std::vector<CommandLineMacro>> OnlyDefinitions(const std::vector<std::string>& cppWords,
                                                             const std::vector<std::string>& defines) {
    std::vector<CommandLineMacro> macros;
    auto add = [&](const std::string& definition) {
        if (definition.empty()) return false;
        const size_t equals = definition.find('=');
        if (equals == std::string::npos)
            macros.push_back({definition, "1"});
        else
            macros.push_back({definition.substr(0, equals), definition.substr(equals + 1)});
        return true;
    };
    for (const std::string& w : cppWords)
        if (w.rfind("-D", 0) != 0 || !add(w.substr(2))) return std::nullopt;
    for (const std::string& d : defines)
        if (!add(d)) return std::nullopt;
    return macros;
}

}  // namespace

SourceText ReadSceneSource(const std::string& path, bool useCpp, const std::string& cppArgs,
                           const std::vector<std::string>& defines) {
    SourceText src;
    src.fileName = path.empty() ? "stdin" : path;
    if (!useCpp) {
        src.text = ReadRaw(path);
        return src;
    }
    if (!path.empty()) {
        if (auto macros = OnlyDefinitions(SplitWords(cppArgs), defines)) {
            if (auto text = PreprocessBuiltin(ReadRaw(path), path, *macros)) {
                src.text = std::move(*text);
                return src;
            }
        }
    }
    std::vector<std::string> args{"cpp"};
    for (std::string& w : SplitWords(cppArgs)) args.push_back(std::move(w));
    for (const std::string& d : defines) args.push_back("-D" + d);
    if (!path.empty()) args.push_back(path);
    src.text = RunCpp(args);
    return src;
}

}  // namespace rs
