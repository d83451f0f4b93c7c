// Per-scene comparison thresholds, read from a table in the format of
// shared/reference/thresholds.tsv: '#' comment lines and blank lines are skipped; every
// other line has six whitespace-separated fields
//     scene  resolution  mean  max  frac  bright
// where scene is a scene name or "default" (any scene) and resolution is a number (the
// -R size the image was rendered at), "default" (the scene's own resolution) or "any".
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "metrics.h"

namespace rs {

struct ThresholdRow {
    std::string scene, resolution;
    Thresholds thresholds;
};

// Parses the table text; `name` (the file name) starts every error message, with the line.
std::optional<std::vector<ThresholdRow>> ParseThresholdTable(const std::string& text,
                                                             const std::string& name,
                                                             std::string& error);

// The thresholds for `scene` rendered at `resolution` (a number or "default"): the first row
// matching (scene, resolution), (scene, any), (default, resolution), (default, any), in that
// order. Fails when none matches.
std::optional<Thresholds> LookupThresholds(const std::vector<ThresholdRow>& rows,
                                           const std::string& scene,
                                           const std::string& resolution, std::string& error);

// Reads and parses the file `path`, then looks up as above.
std::optional<Thresholds> LoadThresholds(const std::string& path, const std::string& scene,
                                         const std::string& resolution, std::string& error);

// Parses a whole string as a finite number ≥ 0.
std::optional<double> ParseNonNegative(const std::string& text);

}  // namespace rs
