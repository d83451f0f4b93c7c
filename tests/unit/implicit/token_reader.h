// An ArgReader over whitespace-separated tokens for the implicit module's tests (no
// locations: every message is located at line 0).
#pragma once

#include <cstdlib>
#include <string>
#include <utility>
#include <vector>

#include "libcommon/arg_reader.h"
#include "libsurf/surface.h"

namespace rs {

// An ArgReader over whitespace-separated tokens. The token TIME reads as the animated
// number equal to the frame time.
class TokenReader final : public ArgReader {
  public:
    explicit TokenReader(const std::string& text) {
        size_t i = 0;
        while (i < text.size()) {
            size_t j = text.find_first_of(" \n", i);
            if (j == std::string::npos) j = text.size();
            if (j > i) tokens_.push_back(text.substr(i, j - i));
            i = j + 1;
        }
    }
    double ReadNumber() override {
        if (!PeekNumber()) Fail("expected a number");
        return std::strtod(tokens_[pos_++].c_str(), nullptr);
    }
    int ReadInt() override { return static_cast<int>(ReadNumber()); }
    AnimatedValue ReadAnimatedNumber() override {
        AnimatedValue v;
        if (Accept("TIME")) {
            v.at = [](double t) { return t; };
            v.range = [](double t0, double t1) { return std::pair<double, double>(t0, t1); };
        } else {
            v.value = ReadNumber();
        }
        return v;
    }
    bool PeekNumber() override {
        if (pos_ >= tokens_.size()) return false;
        if (tokens_[pos_] == "TIME") return true;
        char* end = nullptr;
        std::strtod(tokens_[pos_].c_str(), &end);
        return *end == '\0';
    }
    bool Accept(const char* word) override {
        if (!Peek(word)) return false;
        ++pos_;
        return true;
    }
    bool Peek(const char* word) override { return pos_ < tokens_.size() && tokens_[pos_] == word; }
    std::string ReadName() override {
        if (pos_ >= tokens_.size() || PeekNumber()) Fail("expected a name");
        return tokens_[pos_++];
    }
    std::string ReadFilename() override { return ReadName(); }
    bool PeekFilename() override { return pos_ < tokens_.size() && !PeekNumber(); }
    Surface ReadSurface() override { return Surface{}; }
    bool FlipNormals() const override { return false; }
    SourceLocation Location() const override { return {}; }
    void Warn(const std::string& message) override { warnings.push_back(message); }
    void Advise(const std::string& message) override { warnings.push_back(message); }
    [[noreturn]] void Fail(const std::string& message) override {
        throw FatalError(Severity::Abort, message);
    }
    bool AtEnd() const { return pos_ == tokens_.size(); }

    std::vector<std::string> warnings;

  private:
    std::vector<std::string> tokens_;
    size_t pos_ = 0;
};

}  // namespace rs
