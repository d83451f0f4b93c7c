// Pixel sampling tables of spec §3.3: the dither permutation that maps a sub-pixel cell to
// its sample number, filter weights, and the square "lens" sample for a sample number.
#pragma once

#include <vector>

#include "libcommon/random.h"
#include "libshade/scene.h"

namespace rs {

class SamplingPattern {
  public:
    // `n` samples per side (n ≥ 1); `width` the filter footprint in pixels.
    SamplingPattern(int n, FilterKind filter, double width);

    int PerSide() const { return n_; }
    int Cells() const { return n_ * n_; }
    double Width() const { return width_; }
    // Sample number of cell s = l·n + k (k column, l row).
    int SampleNumber(int cell) const { return dither_[cell]; }
    double Weight(int cell) const { return weights_[cell]; }
    // Offset of cell s's low corner from the pixel centre, and the cell size, in pixels.
    double CellOffsetX(int cell) const { return -width_ / 2 + (cell % n_) * cellSize_; }
    double CellOffsetY(int cell) const { return -width_ / 2 + (cell / n_) * cellSize_; }
    double CellSize() const { return cellSize_; }

  private:
    int n_;
    double width_, cellSize_;
    std::vector<int> dither_;
    std::vector<double> weights_;
};

// The lens / gloss sample of sample number m on the n×n grid: a point of [−1,1]², jittered
// inside cell m (always random, even without jitter); a plain uniform point when m < 0.
void SquareSample(int m, int n, Rng& rng, double& px, double& py);

// The ray time of sample number m (0 ≤ m < n²) in a frame whose shutter opens at
// `frameTime` (spec §3.3): `frameTime` when shutter ≤ 0, else
// frameTime + (shutter/n²)·(m + xi) with xi ∈ [0, 1) (0 without jitter), so sample m lies in
// stratum m of [frameTime, frameTime + shutter).
double ShutterTime(double frameTime, double shutter, int n, int m, double xi);

}  // namespace rs
