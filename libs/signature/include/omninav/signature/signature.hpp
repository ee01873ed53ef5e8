#pragma once
// The Fourier signature of a panorama (Menegatti et al. 2004, §2.1): the 1-D discrete Fourier
// transform of every row of the panoramic cylinder, of which only the first m components are
// kept. Their magnitudes do not change when the robot turns on the spot (a turn only shifts the
// rows circularly, Eq. 1): they say *where* the robot is. Their phases change by k·δ for a turn
// δ: they say *which way* it looks (phase_heading.hpp).
//
// Conventions (ours, not the paper's, which leaves them open):
//   - Component k of row y is F_y(k) = (1/W) Σ_x f_y(x) e^{−2πi·k·x/W}, x the column, W the
//     panorama width. Dividing by W makes magnitudes independent of the width (|F_y(0)| is
//     the row's mean grey level, 0..255), so a 720-column query compares with a 360-column map.
//   - Components are k = 0, 1, ..., m−1: "the first 15 Fourier components" include the mean.
//   - A "line" is one row of one channel: luminance signatures have H lines, colour ones 3·H
//     (blue rows first, then green, then red: OpenCV's BGR order).
//   - Phases are in radians, in (−π, π].
//   - With normalise_brightness, magnitudes are rescaled per channel (below); phases never are.

#include <complex>
#include <cstddef>
#include <memory>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace omninav {
class ConfigReader;
}

namespace omninav::signature {

// What a row is before the Fourier transform.
enum class ColourMode {
  kLuminance,   // one line per row: Y = 0.299 R + 0.587 G + 0.114 B (ITU-R BT.601, OpenCV's)
  kPerChannel,  // three lines per row, B, G and R transformed apart
};

std::string to_string(ColourMode mode);
// "luminance" or "per_channel"; throws UsageError otherwise.
ColourMode colour_mode_from_string(const std::string& text);

struct SignatureParams {
  // m, components kept per line: "we represent the omnidirectional image with just the 15
  // values of the first 15 Fourier components" (Menegatti et al. 2004, §2.1, Figs. 5-6).
  // Range 1..W/2+1.
  int components = 15;
  // Luminance rows (the paper's grey images) or each colour channel apart; docs/memory.md
  // measures which localises better.
  ColourMode colour = ColourMode::kLuminance;
  // Beyond the paper: scale each channel's magnitudes so that its mean brightness (the mean of
  // its rows' k = 0 components) is 128 grey levels. An exposure or white-balance change
  // multiplies a channel's every component by one gain, which this cancels exactly (short of
  // clipping); docs/memory.md measures what it costs and what it buys. The paper: false.
  bool normalise_brightness = true;

  // The range of memory.yaml's signature.components (1..4096). Throws UsageError naming the key
  // (core/param_check.hpp); the loader and SignatureExtractor's constructor call it.
  void check() const;
};

// Reads the `signature:` section of memory.yaml (keys components, colour,
// normalise_brightness).
void load_signature_params(const ConfigReader& section, SignatureParams& params);

// A panorama's signature: magnitudes and phases of the first `components` Fourier components
// of each of its `lines`, stored line by line: value (line, k) is at [line·components + k].
struct Signature {
  int rows = 0;                  // panorama rows H
  int channels = 1;              // 1 (luminance) or 3 (B, G, R)
  int components = 0;            // m
  int width_px = 0;              // W of the panorama it came from
  std::vector<float> magnitude;  // |F_y(k)|, grey levels
  std::vector<float> phase_rad;  // arg F_y(k), radians in (−π, π]

  int lines() const { return rows * channels; }
  std::size_t size() const { return static_cast<std::size_t>(lines()) * components; }
  std::size_t at(int line, int k) const {
    return static_cast<std::size_t>(line) * components + static_cast<std::size_t>(k);
  }
  std::complex<double> coefficient(int line, int k) const {
    return std::polar<double>(magnitude[at(line, k)], phase_rad[at(line, k)]);
  }
  // The same signature with only its first `m` components (m ≤ components).
  Signature truncated(int m) const;
  bool same_layout(const Signature& other) const {
    return rows == other.rows && channels == other.channels;
  }
};

// The components a pairwise measurement of `a` and `b` works on: `components`, or all that both
// hold when it is −1. Throws UsageError naming the measurement (`what`, e.g. "estimate motion")
// when the layouts differ or fewer than 2 or more than both hold are asked for.
int pair_components(const Signature& a, const Signature& b, int components,
                    const std::string& what);

// How an extractor computes the components. Both give the same signature to float precision
// (tests/signature/fast_path_test.cpp: every coefficient within 1e-3 grey levels, plus the
// polynomial atan2's 1e-5 rad); kFast is the one to use.
enum class SignaturePath {
  // Lines converted one at a time (luminance as OpenCV computes it, src/panorama_lines.hpp),
  // the direct transform of the first components where it applies (below), FFTW elsewhere,
  // vectorised magnitudes and phases (a polynomial atan2, error < 1e-5 rad).
  kFast,
  // The reference: cv::cvtColor into a grey image, FFTW for every size, std::hypot and
  // std::atan2. The oracle the fast path is tested against, and the benchmark's baseline.
  kReference,
};

// Computes signatures of panoramas of any size. Widths divisible by 4 with m ≤ 32 use a direct
// transform of the first m components (faster than a whole FFT, src/low_frequency_dft.hpp);
// other sizes and full spectra use FFTW, one plan per (width, lines), made once per process
// (under a mutex: FFTW's planner is not thread-safe) and executed on this extractor's own
// buffers, so one extractor per thread runs in parallel. Deterministic: FFTW plans are made
// with FFTW_ESTIMATE, whose choice does not depend on timing. After the first call with a
// given size, compute() allocates nothing but the returned signature.
class SignatureExtractor {
 public:
  explicit SignatureExtractor(SignatureParams params = {},
                              SignaturePath path = SignaturePath::kFast);
  ~SignatureExtractor();
  SignatureExtractor(SignatureExtractor&&) noexcept;
  SignatureExtractor& operator=(SignatureExtractor&&) noexcept;

  // The signature of an 8-bit grey or BGR panorama (a grey one gives three equal channels in
  // kPerChannel mode). Throws InputError naming `what` for an empty or non-8-bit image, and
  // UsageError when the panorama is narrower than 2·(components − 1) columns.
  Signature compute(const cv::Mat& panorama, const std::string& what = "panorama");

  // All W/2 + 1 magnitudes of every line (for Fig. 5's power spectrum and Fig. 6's sweep
  // over m): row-major, lines × (W/2 + 1).
  cv::Mat full_spectrum(const cv::Mat& panorama, const std::string& what = "panorama");

  const SignatureParams& params() const { return params_; }

 private:
  struct Workspace;
  void transform(const cv::Mat& panorama, const std::string& what);  // into lines of floats
  void run_fft();
  SignatureParams params_;
  SignaturePath path_;
  std::unique_ptr<Workspace> work_;
};

// One-off convenience: a fresh extractor per call (the plan is still made only once).
Signature compute_signature(const cv::Mat& panorama, const SignatureParams& params = {});

}  // namespace omninav::signature
