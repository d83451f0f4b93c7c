#include "thresholds.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>

namespace rs {

std::optional<double> ParseNonNegative(const std::string& text) {
    if (text.empty()) return std::nullopt;
    char* end = nullptr;
    errno = 0;
    const double value = std::strtod(text.c_str(), &end);
    if (errno != 0 || end != text.c_str() + text.size() || !std::isfinite(value) || value < 0) {
        return std::nullopt;
    }
    return value;
}

std::optional<std::vector<ThresholdRow>> ParseThresholdTable(const std::string& text,
                                                             const std::string& name,
                                                             std::string& error) {
    std::vector<ThresholdRow> rows;
    std::istringstream lines(text);
    std::string line;
    for (int lineNumber = 1; std::getline(lines, line); ++lineNumber) {
        std::istringstream fields(line);
        std::vector<std::string> f;
        for (std::string field; fields >> field;) f.push_back(field);
        if (f.empty() || f[0][0] == '#') continue;
        const std::string where = name + ":" + std::to_string(lineNumber) + ": ";
        if (f.size() != 6) {
            error = where + "expected 6 fields (scene resolution mean max frac bright), found " +
                    std::to_string(f.size());
            return std::nullopt;
        }
        double values[4];
        for (int i = 0; i < 4; ++i) {
            const std::optional<double> v = ParseNonNegative(f[2 + i]);
            if (!v) {
                error = where + "\"" + f[2 + i] + "\" is not a number >= 0";
                return std::nullopt;
            }
            values[i] = *v;
        }
        rows.push_back({f[0], f[1], {values[0], values[1], values[2], values[3]}});
    }
    return rows;
}

std::optional<Thresholds> LookupThresholds(const std::vector<ThresholdRow>& rows,
                                           const std::string& scene,
                                           const std::string& resolution, std::string& error) {
    const std::pair<std::string, std::string> keys[] = {
        {scene, resolution}, {scene, "any"}, {"default", resolution}, {"default", "any"}};
    for (const auto& [s, r] : keys) {
        for (const ThresholdRow& row : rows) {
            if (row.scene == s && row.resolution == r) return row.thresholds;
        }
    }
    error = "no thresholds for scene \"" + scene + "\" at resolution \"" + resolution +
            "\" and no \"default any\" row";
    return std::nullopt;
}

std::optional<Thresholds> LoadThresholds(const std::string& path, const std::string& scene,
                                         const std::string& resolution, std::string& error) {
    std::ifstream in(path);
    if (!in) {
        error = path + ": cannot open: " + std::strerror(errno);
        return std::nullopt;
    }
    std::ostringstream text;
    text << in.rdbuf();
    if (in.bad()) {
        error = path + ": read error";
        return std::nullopt;
    }
    const auto rows = ParseThresholdTable(text.str(), path, error);
    if (!rows) return std::nullopt;
    const auto found = LookupThresholds(*rows, scene, resolution, error);
    if (!found) error = path + ": " + error;
    return found;
}

}  // namespace rs
