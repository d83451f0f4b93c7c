// The image comparison behind imgdiff: a 4×4 box downsample of both images, then four
// statistics bounded by thresholds (see shared/reference/thresholds.tsv).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "libimage/image.h"

namespace rs {

// Side of the square blocks averaged before comparing: jitter noise averages out, while
// structure larger than a few pixels survives.
inline constexpr int kDownsampleFactor = 4;
// A downsampled pixel "differs" when its largest channel difference exceeds this.
inline constexpr double kPixelTolerance = 0.03;

// Channel values in [0,1], rows top first, channels interleaved.
struct UnitImage {
    int width = 0, height = 0, channels = 0;
    std::vector<double> values;

    double At(int x, int y, int c) const {
        return values[(static_cast<size_t>(y) * width + x) * channels + c];
    }
};

// Converts bytes to [0,1] (v/255) with `colourChannels` colour channels (1 grey or 3 RGB;
// grey sources are replicated into RGB) followed by an alpha channel when `alpha` is true
// (sources without alpha get 1). Source alpha is dropped when `alpha` is false.
UnitImage ToUnit(const Image& image, int colourChannels, bool alpha);

// Averages `factor`×`factor` blocks: the result is ceil(w/factor) × ceil(h/factor), and a
// partial block at the right or bottom edge averages only the pixels that exist.
UnitImage BoxDownsample(const UnitImage& image, int factor);

struct DiffMetrics {
    double mean = 0;    // mean |ours − ref| over every channel of every downsampled pixel
    double max = 0;     // largest |ours − ref| in any channel
    double frac = 0;    // fraction of downsampled pixels whose largest channel difference
                        // exceeds kPixelTolerance
    double bright = 0;  // |mean(ours) − mean(ref)| / mean(ref) over the colour channels;
                        // 0 when both means are 0, +infinity when only mean(ref) is 0
};

// Metrics of two downsampled images of equal size and layout; `colourChannels` leading
// channels count for brightness (the rest is alpha).
DiffMetrics Measure(const UnitImage& ours, const UnitImage& ref, int colourChannels);

// Compares two 8-bit images: both are converted to the channels they share (RGB if either is
// in colour, else grey; alpha only if both have it), downsampled by kDownsampleFactor and
// measured. Fails, with a message, when the sizes differ.
std::optional<DiffMetrics> CompareImages(const Image& ours, const Image& ref, std::string& error);

// Fraction of full-resolution pixels (no downsampling) whose largest channel difference
// exceeds `steps` 8-bit steps (steps/255), on the channels the images share as in
// CompareImages: the self-regression criterion "at most 1/255 difference on 99.9% of pixels"
// is FractionBeyond(ours, ref, 1) <= 0.001. Fails, with a message, when the sizes differ.
std::optional<double> FractionBeyond(const Image& ours, const Image& ref, int steps,
                                     std::string& error);

struct Thresholds {
    double mean = 0.005, max = 0.15, frac = 0.05, bright = 0.01;
};

// True when mean < t.mean, max < t.max, frac ≤ t.frac and bright < t.bright.
bool WithinThresholds(const DiffMetrics& metrics, const Thresholds& thresholds);

// Difference at which the heat map saturates (the default `max` threshold).
inline constexpr double kHeatFullScale = 0.15;

// RGB heat map at the images' full size (which must match): every pixel shows the largest
// channel difference d of its downsampled block, so the picture shows what the metrics saw.
// Colours run black (d = 0) → blue (d = kPixelTolerance) → red (d = kHeatFullScale) →
// yellow (d ≥ 2·kHeatFullScale), linearly between those stops.
Image HeatMap(const Image& ours, const Image& ref);

// The heat-map colour of a difference d ≥ 0, per channel in [0,1].
void HeatColour(double d, double rgb[3]);

}  // namespace rs
