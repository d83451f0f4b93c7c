#include "libtext/colormap.h"

#include <cerrno>
#include <cstdlib>
#include <fstream>

namespace rs {
namespace {

bool IsBlank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }

// Parses exactly three integers in [0, 255] separated by blanks.
bool ParseLine(const std::string& line, int rgb[3]) {
    const char* s = line.c_str();
    for (int k = 0; k < 3; ++k) {
        while (IsBlank(*s)) ++s;
        char* end = nullptr;
        errno = 0;
        long value = std::strtol(s, &end, 10);
        if (end == s || errno != 0 || value < 0 || value > 255) return false;
        if (*end != '\0' && !IsBlank(*end)) return false;
        rgb[k] = static_cast<int>(value);
        s = end;
    }
    while (IsBlank(*s)) ++s;
    return *s == '\0';
}

}  // namespace

std::optional<ColorMap> ParseColorMap(std::istream& in, const std::string& name,
                                      std::string& error) {
    ColorMap map{};
    std::string line;
    for (int i = 0; i < 256 && std::getline(in, line); ++i) {
        int rgb[3];
        if (!ParseLine(line, rgb)) {
            error = name + ": line " + std::to_string(i + 1) +
                    ": bad colour specification (expected three integers 0-255): \"" + line +
                    "\"";
            return std::nullopt;
        }
        map[i] = Color(rgb[0], rgb[1], rgb[2]) * (1.0 / 255.0);
    }
    return map;
}

std::optional<ColorMap> ReadColorMap(const std::string& path, std::string& error) {
    std::ifstream in(path);
    if (!in) {
        error = "cannot open colormap file \"" + path + "\"";
        return std::nullopt;
    }
    return ParseColorMap(in, path, error);
}

std::shared_ptr<const ColorMap> ReadColorMapArgument(ArgReader& args) {
    std::string path = args.ReadDataFilename();
    std::string error;
    std::optional<ColorMap> map = ReadColorMap(path, error);
    if (!map) args.Fail(error);
    return std::make_shared<const ColorMap>(*map);
}

}  // namespace rs
