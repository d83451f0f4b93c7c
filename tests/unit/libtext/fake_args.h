// A token-list ArgReader for factory tests: numbers are tokens that parse as doubles,
// surfaces are names looked up in `surfaces`, file names are tokens containing '.' or '/'
// that are not numbers. Fail throws FatalError carrying the message.
#pragma once

#include <cstdlib>
#include <map>
#include <string>
#include <vector>

#include "libcommon/arg_reader.h"
#include "libsurf/surface.h"

namespace rs::testing {

class FakeArgs : public ArgReader {
  public:
    explicit FakeArgs(std::vector<std::string> tokens) : tokens_(std::move(tokens)) {}

    std::map<std::string, Surface> surfaces;

    bool AtEnd() const { return next_ == tokens_.size(); }

    double ReadNumber() override {
        if (!PeekNumber()) Fail("expected a number");
        return std::strtod(tokens_[next_++].c_str(), nullptr);
    }
    int ReadInt() override { return static_cast<int>(ReadNumber()); }
    AnimatedValue ReadAnimatedNumber() override { return {ReadNumber(), {}, {}}; }
    bool PeekNumber() override {
        if (AtEnd()) return false;
        const std::string& t = tokens_[next_];
        char* end = nullptr;
        std::strtod(t.c_str(), &end);
        return !t.empty() && *end == '\0';
    }
    bool Accept(const char* word) override {
        if (!Peek(word)) return false;
        ++next_;
        return true;
    }
    bool Peek(const char* word) override { return !AtEnd() && tokens_[next_] == word; }
    std::string ReadName() override {
        if (AtEnd()) Fail("expected a name");
        return tokens_[next_++];
    }
    std::string ReadFilename() override {
        if (!PeekFilename()) Fail("expected a file name");
        return tokens_[next_++];
    }
    bool PeekFilename() override {
        return !AtEnd() && !PeekNumber() &&
               tokens_[next_].find_first_of("./") != std::string::npos;
    }
    Surface ReadSurface() override {
        std::string name = ReadName();
        auto found = surfaces.find(name);
        if (found == surfaces.end()) Fail("unknown surface " + name);
        return found->second;
    }
    bool FlipNormals() const override { return false; }
    SourceLocation Location() const override { return {"test.ray", 1}; }
    void Warn(const std::string& message) override { warnings.push_back(message); }
    void Advise(const std::string& message) override { warnings.push_back(message); }
    [[noreturn]] void Fail(const std::string& message) override {
        throw FatalError(Severity::Abort, message);
    }

    std::vector<std::string> warnings;

  private:
    std::vector<std::string> tokens_;
    size_t next_ = 0;
};

}  // namespace rs::testing
