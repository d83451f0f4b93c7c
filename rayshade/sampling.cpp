#include "rayshade/sampling.h"

#include <cmath>
#include <numeric>

namespace rs {

namespace {

// The original's dither permutations for n = 1…5 (spec §3.3). For larger n its tables are
// off by one, so we build a well-spread permutation instead: cells in bit-reversed-like
// order of a 2-D stride, which keeps consecutive sample numbers far apart.
std::vector<int> DitherTable(int n) {
    static const std::vector<int> kTables[] = {
        {0},
        {0, 2, 3, 1},
        {0, 2, 7, 6, 5, 1, 3, 8, 4},
        {0, 8, 2, 10, 12, 4, 14, 6, 3, 11, 1, 9, 15, 7, 13, 5},
        {0, 8, 23, 17, 2, 19, 12, 4, 20, 15, 3, 21, 16, 9, 6, 14, 10, 24, 1, 13, 22, 7, 18, 11, 5},
    };
    if (n <= 5) return kTables[n - 1];
    int cells = n * n;
    // A multiplicative permutation: s ↦ (s·p) mod cells with p coprime to cells and near
    // cells·0.618 (golden-ratio stride) spreads sample numbers over the grid.
    int p = static_cast<int>(cells * 0.6180339887) | 1;
    while (std::gcd(p, cells) != 1) p += 2;
    std::vector<int> table(cells);
    for (int s = 0; s < cells; ++s) table[s] = static_cast<int>((static_cast<long>(s) * p) % cells);
    return table;
}

}  // namespace

SamplingPattern::SamplingPattern(int n, FilterKind filter, double width)
    : n_(n), width_(width), cellSize_(width / n), dither_(DitherTable(n)), weights_(n * n) {
    if (filter == FilterKind::Box) {
        for (double& w : weights_) w = 1.0 / (n * n);
        return;
    }
    // Gaussian with σ = 1 pixel over the cell centres, normalised to sum 1.
    double sum = 0;
    for (int l = 0; l < n; ++l) {
        for (int k = 0; k < n; ++k) {
            double uk = -width / 2 + width / (2 * n) + k * cellSize_;
            double ul = -width / 2 + width / (2 * n) + l * cellSize_;
            double w = std::exp(-(uk * uk + ul * ul) / 2);
            weights_[l * n + k] = w;
            sum += w;
        }
    }
    for (double& w : weights_) w /= sum;
}

void SquareSample(int m, int n, Rng& rng, double& px, double& py) {
    if (m < 0 || n < 1) {
        px = 2 * rng.Uniform() - 1;
        py = 2 * rng.Uniform() - 1;
        return;
    }
    double cell = 2.0 / n;
    px = -1 + (m % n) * cell + rng.Uniform() * cell;
    py = -1 + (m / n) * cell + rng.Uniform() * cell;
}

double ShutterTime(double frameTime, double shutter, int n, int m, double xi) {
    if (shutter <= 0) return frameTime;
    return frameTime + shutter / (n * n) * (m + xi);
}

}  // namespace rs
