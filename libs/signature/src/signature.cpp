#include "omninav/signature/signature.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <opencv2/imgproc.hpp>
#include <optional>

#include "fast_math.hpp"
#include "low_frequency_dft.hpp"
#include "omninav/core/config.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/core/fftw_plans.hpp"
#include "omninav/core/panorama.hpp"
#include "omninav/core/param_check.hpp"
#include "panorama_lines.hpp"

namespace omninav::signature {

std::string to_string(ColourMode mode) {
  return mode == ColourMode::kLuminance ? "luminance" : "per_channel";
}

ColourMode colour_mode_from_string(const std::string& text) {
  if (text == "luminance") return ColourMode::kLuminance;
  if (text == "per_channel") return ColourMode::kPerChannel;
  throw UsageError("colour mode '" + text + "' is not one of: luminance, per_channel");
}

void SignatureParams::check() const {
  check_range("signature.components", components, 1, 4096);
}

void load_signature_params(const ConfigReader& section, SignatureParams& params) {
  section.read("components", params.components);
  std::string colour = to_string(params.colour);
  section.read("colour", colour, {"luminance", "per_channel"});
  params.colour = colour_mode_from_string(colour);
  section.read("normalise_brightness", params.normalise_brightness);
  check_loaded(section.source_name(), [&] { params.check(); });
}

int pair_components(const Signature& a, const Signature& b, int components,
                    const std::string& what) {
  if (!a.same_layout(b)) {
    throw UsageError("cannot " + what + " between signatures of different layouts (" +
                     std::to_string(a.lines()) + " and " + std::to_string(b.lines()) + " lines)");
  }
  const int held = std::min(a.components, b.components);
  const int m = components < 0 ? held : components;
  if (m < 2 || m > held) {
    throw UsageError("cannot " + what + " on " + std::to_string(m) + " components: 2.." +
                     std::to_string(held) + " possible");
  }
  return m;
}

Signature Signature::truncated(int m) const {
  if (m < 1 || m > components) {
    throw UsageError("cannot truncate a signature of " + std::to_string(components) +
                     " components to " + std::to_string(m));
  }
  Signature out;
  out.rows = rows;
  out.channels = channels;
  out.components = m;
  out.width_px = width_px;
  out.magnitude.resize(static_cast<std::size_t>(lines()) * m);
  out.phase_rad.resize(out.magnitude.size());
  for (int line = 0; line < lines(); ++line) {
    for (int k = 0; k < m; ++k) {
      out.magnitude[out.at(line, k)] = magnitude[at(line, k)];
      out.phase_rad[out.at(line, k)] = phase_rad[at(line, k)];
    }
  }
  return out;
}

struct SignatureExtractor::Workspace {
  int width = 0;
  int lines = 0;
  fftw::Buffer<float> in;  // lines × width, line after line, for FFTW
  cv::Mat grey;            // luminance, for the reference path only
  // FFTW, for full spectra and for sizes the direct transform does not serve.
  int fft_width = 0, fft_lines = 0;
  fftwf_plan plan = nullptr;
  fftw::Buffer<fftwf_complex> out;
  // The direct transform of the first components (low_frequency_dft.hpp) and its output.
  std::optional<detail::LowFrequencyDft> direct;
  std::vector<float> line;    // one line as floats (panorama_lines.hpp)
  std::vector<float> folded;  // up to LowFrequencyDft::kMaxLines folded lines
  std::vector<float> re, im;  // lines × m, unscaled
};

SignatureExtractor::SignatureExtractor(SignatureParams params, SignaturePath path)
    : params_(params), path_(path), work_(std::make_unique<Workspace>()) {
  params_.check();
}

SignatureExtractor::~SignatureExtractor() = default;
SignatureExtractor::SignatureExtractor(SignatureExtractor&&) noexcept = default;
SignatureExtractor& SignatureExtractor::operator=(SignatureExtractor&&) noexcept = default;

void SignatureExtractor::transform(const cv::Mat& panorama, const std::string& what) {
  require_panorama(panorama, what);
  const int width = panorama.cols;
  const int rows = panorama.rows;
  const int channels = params_.colour == ColourMode::kLuminance ? 1 : 3;
  const int lines = rows * channels;
  Workspace& work = *work_;
  if (work.width != width || work.lines != lines) {
    work.in = fftw::Buffer<float>(static_cast<std::size_t>(width) * lines);
    work.width = width;
    work.lines = lines;
  }
  float* in = work.in.data();
  if (path_ == SignaturePath::kFast) {
    for (int line = 0; line < lines; ++line) {
      detail::load_line(panorama, params_.colour, line,
                        in + static_cast<std::size_t>(line) * width);
    }
    return;
  }
  // The reference path: a whole grey image from OpenCV, then its rows as floats.
  if (channels == 1) {
    const cv::Mat* grey = &panorama;
    if (panorama.channels() == 3) {
      cv::cvtColor(panorama, work.grey, cv::COLOR_BGR2GRAY);
      grey = &work.grey;
    }
    for (int y = 0; y < rows; ++y) {
      const std::uint8_t* src = grey->ptr<std::uint8_t>(y);
      float* dst = in + static_cast<std::size_t>(y) * width;
      for (int x = 0; x < width; ++x) dst[x] = src[x];
    }
  } else {
    // Lines in BGR order: all blue rows, then green, then red.
    const std::size_t plane = static_cast<std::size_t>(rows) * width;
    for (int y = 0; y < rows; ++y) {
      const std::uint8_t* src = panorama.ptr<std::uint8_t>(y);
      float* b = in + static_cast<std::size_t>(y) * width;
      float* g = b + plane;
      float* r = g + plane;
      if (panorama.channels() == 3) {
        for (int x = 0; x < width; ++x) {
          b[x] = src[3 * x];
          g[x] = src[3 * x + 1];
          r[x] = src[3 * x + 2];
        }
      } else {
        for (int x = 0; x < width; ++x) b[x] = g[x] = r[x] = src[x];
      }
    }
  }
}

void SignatureExtractor::run_fft() {
  Workspace& work = *work_;
  if (work.fft_width != work.width || work.fft_lines != work.lines) {
    // `lines` real transforms of `width` points, line after line, from the process-wide cache.
    // FFTW_ESTIMATE: the plan depends on the sizes only, never on timing, so the same input
    // gives bit-identical signatures in every run (docs/design.md, Determinism).
    work.plan = fftw::lines_r2c_float({work.width, work.lines, 0, fftw::Planning::kEstimate});
    work.out =
        fftw::Buffer<fftwf_complex>(static_cast<std::size_t>(work.width / 2 + 1) * work.lines);
    work.fft_width = work.width;
    work.fft_lines = work.lines;
  }
  fftwf_execute_dft_r2c(work.plan, work.in.data(), work.out.data());
}

namespace {

// The reference path's magnitudes and phases (the fast path's is detail::to_polar): the C
// library's hypot and atan2 on each scaled coefficient.
void to_polar_reference(const float* re, const float* im, std::size_t count, float scale,
                        float* magnitude, float* phase_rad) {
  for (std::size_t i = 0; i < count; ++i) {
    const float a = re[i] * scale, b = im[i] * scale;
    magnitude[i] = std::hypot(a, b);
    phase_rad[i] = std::atan2(b, a);
    // atan2(−0, x < 0) is −π; the signature's phases are in (−π, π].
    if (phase_rad[i] <= -std::numbers::pi_v<float>) phase_rad[i] = std::numbers::pi_v<float>;
  }
}

// Every channel's magnitudes scaled so that its mean DC component over the rows is 128.
void normalise_brightness(Signature& signature) {
  const int m = signature.components;
  const std::size_t per_channel = static_cast<std::size_t>(signature.rows) * m;
  for (int c = 0; c < signature.channels; ++c) {
    float* channel = signature.magnitude.data() + static_cast<std::size_t>(c) * per_channel;
    double mean = 0.0;
    for (int y = 0; y < signature.rows; ++y) mean += channel[static_cast<std::size_t>(y) * m];
    mean /= signature.rows;
    if (mean <= 1e-3) continue;  // a black channel stays black
    const float gain = static_cast<float>(128.0 / mean);
    for (std::size_t i = 0; i < per_channel; ++i) channel[i] *= gain;
  }
}

}  // namespace

Signature SignatureExtractor::compute(const cv::Mat& panorama, const std::string& what) {
  const int m = params_.components;
  if (!panorama.empty() && panorama.cols / 2 + 1 < m) {
    throw UsageError(what + ": a panorama " + std::to_string(panorama.cols) +
                     " columns wide has only " + std::to_string(panorama.cols / 2 + 1) +
                     " Fourier components, fewer than the " + std::to_string(m) + " asked for");
  }
  require_panorama(panorama, what);
  Workspace& work = *work_;
  const int width = panorama.cols;
  const int channels = params_.colour == ColourMode::kLuminance ? 1 : 3;
  const int lines = panorama.rows * channels;
  const std::size_t count = static_cast<std::size_t>(lines) * m;
  work.re.resize(count);
  work.im.resize(count);
  if (path_ == SignaturePath::kFast && detail::LowFrequencyDft::applicable(width, m)) {
    // Line by line into a small buffer, folded, and transformed a few lines at a time: the
    // panorama is read once and nothing of its size is written.
    if (!work.direct || work.direct->width() != width || work.direct->components() != m) {
      work.direct.emplace(width, m);
    }
    const detail::LowFrequencyDft& direct = *work.direct;
    const int batch = detail::LowFrequencyDft::kMaxLines;
    work.line.resize(static_cast<std::size_t>(width));
    work.folded.resize(static_cast<std::size_t>(batch) * direct.folded_size());
    for (int first = 0; first < lines; first += batch) {
      const int n = std::min(batch, lines - first);
      for (int j = 0; j < n; ++j) {
        detail::load_line(panorama, params_.colour, first + j, work.line.data());
        direct.fold(work.line.data(),
                    work.folded.data() + static_cast<std::size_t>(j) * direct.folded_size());
      }
      direct.transform_folded(work.folded.data(), n,
                              work.re.data() + static_cast<std::size_t>(first) * m,
                              work.im.data() + static_cast<std::size_t>(first) * m);
    }
  } else {
    transform(panorama, what);
    run_fft();
    const int half = work.width / 2 + 1;
    for (int line = 0; line < work.lines; ++line) {
      const fftwf_complex* row = work.out.data() + static_cast<std::size_t>(line) * half;
      for (int k = 0; k < m; ++k) {
        work.re[static_cast<std::size_t>(line) * m + k] = row[k][0];
        work.im[static_cast<std::size_t>(line) * m + k] = row[k][1];
      }
    }
  }
  Signature signature;
  signature.rows = panorama.rows;
  signature.channels = channels;
  signature.components = m;
  signature.width_px = width;
  signature.magnitude.resize(count);
  signature.phase_rad.resize(count);
  const float scale = 1.0f / static_cast<float>(width);
  float* magnitude = signature.magnitude.data();
  if (path_ == SignaturePath::kFast) {
    detail::to_polar(work.re.data(), work.im.data(), count, scale, magnitude,
                     signature.phase_rad.data());
  } else {
    to_polar_reference(work.re.data(), work.im.data(), count, scale, magnitude,
                       signature.phase_rad.data());
  }
  if (params_.normalise_brightness) normalise_brightness(signature);
  return signature;
}

cv::Mat SignatureExtractor::full_spectrum(const cv::Mat& panorama, const std::string& what) {
  transform(panorama, what);
  run_fft();
  const Workspace& work = *work_;
  const int half = work.width / 2 + 1;
  cv::Mat spectrum(work.lines, half, CV_32F);
  const float scale = 1.0f / static_cast<float>(work.width);
  for (int line = 0; line < work.lines; ++line) {
    const fftwf_complex* row = work.out.data() + static_cast<std::size_t>(line) * half;
    float* dst = spectrum.ptr<float>(line);
    for (int k = 0; k < half; ++k) dst[k] = std::hypot(row[k][0], row[k][1]) * scale;
  }
  return spectrum;
}

Signature compute_signature(const cv::Mat& panorama, const SignatureParams& params) {
  SignatureExtractor extractor(params);
  return extractor.compute(panorama);
}

}  // namespace omninav::signature
