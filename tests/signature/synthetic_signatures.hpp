#pragma once
// Synthetic signatures for scale (the hierarchy test and signature_bench): places on a square
// floor whose magnitudes vary smoothly with position, low components slowly and high ones
// faster, as the paper observes of real views (Menegatti et al. 2004, §2.3: "the low frequency
// components ... are more similar in a larger interval of distances"). Random signatures would have
// no neighbourhoods at all and make every pruning look bad; these have the structure the search
// relies on. Seeded.

#include <cmath>
#include <random>
#include <vector>

#include "omninav/signature/signature.hpp"

namespace omninav::signature::testing {

class SyntheticPlaces {
 public:
  // A floor `size_m` across, signatures of `rows` × `channels` lines and `components`.
  SyntheticPlaces(double size_m, int rows, int channels, int components, unsigned seed = 1)
      : rows_(rows), channels_(channels), components_(components) {
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const int values = rows * channels * components;
    waves_.resize(static_cast<std::size_t>(values) * kWaves);
    base_.resize(static_cast<std::size_t>(values));
    for (int v = 0; v < values; ++v) {
      const int k = v % components;
      // Magnitudes fall with k (Fig. 5); spatial frequency grows with k.
      const double amplitude = 40.0 / (1.0 + k);
      base_[v] = static_cast<float>(2.0 * amplitude + 20.0 * unit(random));
      const double cycles_per_m = (0.15 + 0.12 * k) * (0.7 + 0.6 * unit(random));
      for (int w = 0; w < kWaves; ++w) {
        const double direction = 2.0 * M_PI * unit(random);
        Wave& wave = waves_[static_cast<std::size_t>(v) * kWaves + w];
        wave.fx = 2.0 * M_PI * cycles_per_m * std::cos(direction);
        wave.fy = 2.0 * M_PI * cycles_per_m * std::sin(direction);
        wave.phase = 2.0 * M_PI * unit(random);
        wave.amplitude = amplitude * (0.5 + 0.5 * unit(random));
      }
    }
    (void)size_m;
  }

  // The signature seen at (x, y), with pixel-like noise of `noise` grey levels.
  Signature at(double x_m, double y_m, std::mt19937* noise_source = nullptr,
               double noise = 0.0) const {
    Signature s;
    s.rows = rows_;
    s.channels = channels_;
    s.components = components_;
    s.width_px = 360;
    s.magnitude.resize(base_.size());
    s.phase_rad.assign(base_.size(), 0.0f);
    std::normal_distribution<double> gaussian(0.0, noise);
    for (std::size_t v = 0; v < base_.size(); ++v) {
      double value = base_[v];
      for (int w = 0; w < kWaves; ++w) {
        const Wave& wave = waves_[v * kWaves + w];
        value += wave.amplitude * std::sin(wave.fx * x_m + wave.fy * y_m + wave.phase);
      }
      if (noise_source != nullptr && noise > 0.0) value += gaussian(*noise_source);
      s.magnitude[v] = static_cast<float>(std::max(0.0, value));
    }
    return s;
  }

 private:
  static constexpr int kWaves = 2;
  struct Wave {
    double fx, fy, phase, amplitude;
  };
  int rows_, channels_, components_;
  std::vector<Wave> waves_;
  std::vector<float> base_;
};

}  // namespace omninav::signature::testing
