#include "metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rs {

UnitImage ToUnit(const Image& image, int colourChannels, bool alpha) {
    UnitImage out;
    out.width = image.width;
    out.height = image.height;
    out.channels = colourChannels + (alpha ? 1 : 0);
    const size_t pixelCount = static_cast<size_t>(image.width) * image.height;
    out.values.resize(pixelCount * out.channels);
    const bool sourceColour = image.channels >= 3;
    const bool sourceAlpha = image.channels == 2 || image.channels == 4;
    for (size_t p = 0; p < pixelCount; ++p) {
        const uint8_t* in = image.pixels.data() + p * image.channels;
        double* o = out.values.data() + p * out.channels;
        for (int c = 0; c < colourChannels; ++c) o[c] = in[sourceColour ? c : 0] / 255.0;
        if (alpha) o[colourChannels] = sourceAlpha ? in[image.channels - 1] / 255.0 : 1.0;
    }
    return out;
}

UnitImage BoxDownsample(const UnitImage& image, int factor) {
    UnitImage out;
    out.width = (image.width + factor - 1) / factor;
    out.height = (image.height + factor - 1) / factor;
    out.channels = image.channels;
    out.values.assign(static_cast<size_t>(out.width) * out.height * out.channels, 0.0);
    for (int by = 0; by < out.height; ++by) {
        const int y1 = std::min(image.height, (by + 1) * factor);
        for (int bx = 0; bx < out.width; ++bx) {
            const int x1 = std::min(image.width, (bx + 1) * factor);
            double* o = out.values.data() +
                        (static_cast<size_t>(by) * out.width + bx) * out.channels;
            for (int y = by * factor; y < y1; ++y) {
                for (int x = bx * factor; x < x1; ++x) {
                    for (int c = 0; c < out.channels; ++c) o[c] += image.At(x, y, c);
                }
            }
            const double count = static_cast<double>(y1 - by * factor) * (x1 - bx * factor);
            for (int c = 0; c < out.channels; ++c) o[c] /= count;
        }
    }
    return out;
}

DiffMetrics Measure(const UnitImage& ours, const UnitImage& ref, int colourChannels) {
    DiffMetrics m;
    const size_t pixelCount = static_cast<size_t>(ours.width) * ours.height;
    if (pixelCount == 0) return m;
    double sumDiff = 0, sumOurs = 0, sumRef = 0;
    size_t differing = 0;
    for (size_t p = 0; p < pixelCount; ++p) {
        const double* a = ours.values.data() + p * ours.channels;
        const double* b = ref.values.data() + p * ref.channels;
        double largest = 0;
        for (int c = 0; c < ours.channels; ++c) {
            const double d = std::abs(a[c] - b[c]);
            sumDiff += d;
            largest = std::max(largest, d);
            if (c < colourChannels) {
                sumOurs += a[c];
                sumRef += b[c];
            }
        }
        m.max = std::max(m.max, largest);
        if (largest > kPixelTolerance) ++differing;
    }
    m.mean = sumDiff / (static_cast<double>(pixelCount) * ours.channels);
    m.frac = static_cast<double>(differing) / static_cast<double>(pixelCount);
    // The sums share the count of colour values, so the ratio of means is the ratio of sums.
    if (sumRef > 0) {
        m.bright = std::abs(sumOurs - sumRef) / sumRef;
    } else {
        m.bright = sumOurs > 0 ? std::numeric_limits<double>::infinity() : 0.0;
    }
    return m;
}

namespace {

struct SharedLayout {
    int colourChannels;
    bool alpha;
};

SharedLayout LayoutOf(const Image& a, const Image& b) {
    const bool colour = a.channels >= 3 || b.channels >= 3;
    auto hasAlpha = [](const Image& i) { return i.channels == 2 || i.channels == 4; };
    return {colour ? 3 : 1, hasAlpha(a) && hasAlpha(b)};
}

bool SameSize(const Image& ours, const Image& ref, std::string& error) {
    if (ours.width == ref.width && ours.height == ref.height) return true;
    error = "size mismatch: ours is " + std::to_string(ours.width) + " x " +
            std::to_string(ours.height) + ", the reference " + std::to_string(ref.width) +
            " x " + std::to_string(ref.height);
    return false;
}

}  // namespace

std::optional<DiffMetrics> CompareImages(const Image& ours, const Image& ref, std::string& error) {
    if (!SameSize(ours, ref, error)) return std::nullopt;
    const SharedLayout layout = LayoutOf(ours, ref);
    const UnitImage a =
        BoxDownsample(ToUnit(ours, layout.colourChannels, layout.alpha), kDownsampleFactor);
    const UnitImage b =
        BoxDownsample(ToUnit(ref, layout.colourChannels, layout.alpha), kDownsampleFactor);
    return Measure(a, b, layout.colourChannels);
}

std::optional<double> FractionBeyond(const Image& ours, const Image& ref, int steps,
                                     std::string& error) {
    if (!SameSize(ours, ref, error)) return std::nullopt;
    const SharedLayout layout = LayoutOf(ours, ref);
    const UnitImage a = ToUnit(ours, layout.colourChannels, layout.alpha);
    const UnitImage b = ToUnit(ref, layout.colourChannels, layout.alpha);
    const size_t pixelCount = static_cast<size_t>(a.width) * a.height;
    if (pixelCount == 0) return 0.0;
    // Differences are multiples of 1/255; half a step of margin keeps rounding out of it.
    const double limit = (steps + 0.5) / 255.0;
    size_t beyond = 0;
    for (size_t p = 0; p < pixelCount; ++p) {
        for (int c = 0; c < a.channels; ++c) {
            const size_t i = p * a.channels + c;
            if (std::abs(a.values[i] - b.values[i]) > limit) {
                ++beyond;
                break;
            }
        }
    }
    return static_cast<double>(beyond) / static_cast<double>(pixelCount);
}

bool WithinThresholds(const DiffMetrics& metrics, const Thresholds& thresholds) {
    return metrics.mean < thresholds.mean && metrics.max < thresholds.max &&
           metrics.frac <= thresholds.frac && metrics.bright < thresholds.bright;
}

void HeatColour(double d, double rgb[3]) {
    struct Stop {
        double d, r, g, b;
    };
    static constexpr Stop kStops[] = {{0.0, 0, 0, 0},
                                      {kPixelTolerance, 0, 0, 1},
                                      {kHeatFullScale, 1, 0, 0},
                                      {2 * kHeatFullScale, 1, 1, 0}};
    const Stop& last = kStops[std::size(kStops) - 1];
    rgb[0] = last.r;
    rgb[1] = last.g;
    rgb[2] = last.b;
    for (size_t i = 1; i < std::size(kStops); ++i) {
        if (d <= kStops[i].d) {
            const Stop& lo = kStops[i - 1];
            const Stop& hi = kStops[i];
            const double t = std::max(0.0, (d - lo.d) / (hi.d - lo.d));
            rgb[0] = lo.r + t * (hi.r - lo.r);
            rgb[1] = lo.g + t * (hi.g - lo.g);
            rgb[2] = lo.b + t * (hi.b - lo.b);
            return;
        }
    }
}

Image HeatMap(const Image& ours, const Image& ref) {
    const SharedLayout layout = LayoutOf(ours, ref);
    const UnitImage a =
        BoxDownsample(ToUnit(ours, layout.colourChannels, layout.alpha), kDownsampleFactor);
    const UnitImage b =
        BoxDownsample(ToUnit(ref, layout.colourChannels, layout.alpha), kDownsampleFactor);
    Image heat;
    heat.width = ours.width;
    heat.height = ours.height;
    heat.channels = 3;
    heat.pixels.resize(static_cast<size_t>(heat.width) * heat.height * 3);
    for (int y = 0; y < heat.height; ++y) {
        uint8_t* row = heat.Row(y);
        for (int x = 0; x < heat.width; ++x) {
            const int bx = x / kDownsampleFactor, by = y / kDownsampleFactor;
            double largest = 0;
            for (int c = 0; c < a.channels; ++c) {
                largest = std::max(largest, std::abs(a.At(bx, by, c) - b.At(bx, by, c)));
            }
            double rgb[3];
            HeatColour(largest, rgb);
            // Round to the nearest byte: rgb is in [0,1].
            for (int c = 0; c < 3; ++c) {
                row[x * 3 + c] = static_cast<uint8_t>(std::lround(rgb[c] * 255.0));
            }
        }
    }
    return heat;
}

}  // namespace rs
