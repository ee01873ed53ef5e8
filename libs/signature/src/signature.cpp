#include "omninav/signature/signature.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <optional>

#include "fast_math.hpp"
#include "fft_plans.hpp"
#include "low_frequency_dft.hpp"
#include "omninav/core/config.hpp"
#include "omninav/core/errors.hpp"
#include "omninav/core/panorama.hpp"

namespace omninav::signature {

std::string to_string(ColourMode mode) {
  return mode == ColourMode::kLuminance ? "luminance" : "per_channel";
}

ColourMode colour_mode_from_string(const std::string& text) {
  if (text == "luminance") return ColourMode::kLuminance;
  if (text == "per_channel") return ColourMode::kPerChannel;
  throw UsageError("colour mode '" + text + "' is not one of: luminance, per_channel");
}

void load_signature_params(const ConfigReader& section, SignatureParams& params) {
  section.read("components", params.components, 1, 4096);
  std::string colour = to_string(params.colour);
  section.read("colour", colour, {"luminance", "per_channel"});
  params.colour = colour_mode_from_string(colour);
  section.read("normalise_brightness", params.normalise_brightness);
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
  detail::FftwBuffer<float> in;  // lines × width, line after line
  cv::Mat grey;                  // luminance, reused between calls
  // FFTW, for full spectra and for sizes the direct transform does not serve.
  int fft_width = 0, fft_lines = 0;
  fftwf_plan plan = nullptr;
  detail::FftwBuffer<fftwf_complex> out;
  // The direct transform of the first components (low_frequency_dft.hpp) and its output.
  std::optional<detail::LowFrequencyDft> direct;
  std::vector<float> re, im;
};

SignatureExtractor::SignatureExtractor(SignatureParams params)
    : params_(params), work_(std::make_unique<Workspace>()) {
  if (params_.components < 1) {
    throw UsageError("a signature needs at least one component, got " +
                     std::to_string(params_.components));
  }
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
    work.in = detail::FftwBuffer<float>(static_cast<std::size_t>(width) * lines);
    work.width = width;
    work.lines = lines;
  }
  float* in = work.in.data();
  if (channels == 1) {
    const cv::Mat* grey = &panorama;
    if (panorama.channels() == 3) {
      // OpenCV's fixed-point BGR→grey is several times faster than a float loop; it rounds
      // to whole grey levels, as the 8-bit input already is.
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
    work.plan = detail::rows_r2c_plan(work.width, work.lines);
    work.out = detail::FftwBuffer<fftwf_complex>(static_cast<std::size_t>(work.width / 2 + 1) *
                                                 work.lines);
    work.fft_width = work.width;
    work.fft_lines = work.lines;
  }
  fftwf_execute_dft_r2c(work.plan, work.in.data(), work.out.data());
}

Signature SignatureExtractor::compute(const cv::Mat& panorama, const std::string& what) {
  const int m = params_.components;
  if (!panorama.empty() && panorama.cols / 2 + 1 < m) {
    throw UsageError(what + ": a panorama " + std::to_string(panorama.cols) +
                     " columns wide has only " + std::to_string(panorama.cols / 2 + 1) +
                     " Fourier components, fewer than the " + std::to_string(m) + " asked for");
  }
  transform(panorama, what);
  Workspace& work = *work_;
  const std::size_t count = static_cast<std::size_t>(work.lines) * m;
  work.re.resize(count);
  work.im.resize(count);
  if (detail::LowFrequencyDft::applicable(work.width, m)) {
    if (!work.direct || work.direct->width() != work.width || work.direct->components() != m) {
      work.direct.emplace(work.width, m);
    }
    for (int line = 0; line < work.lines; ++line) {
      work.direct->transform(work.in.data() + static_cast<std::size_t>(line) * work.width,
                             work.re.data() + static_cast<std::size_t>(line) * m,
                             work.im.data() + static_cast<std::size_t>(line) * m);
    }
  } else {
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
  signature.channels = params_.colour == ColourMode::kLuminance ? 1 : 3;
  signature.components = m;
  signature.width_px = work.width;
  signature.magnitude.resize(count);
  signature.phase_rad.resize(count);
  const float scale = 1.0f / static_cast<float>(work.width);
  const float* re = work.re.data();
  const float* im = work.im.data();
  float* magnitude = signature.magnitude.data();
  float* phase = signature.phase_rad.data();
  for (std::size_t i = 0; i < count; ++i) {
    const float a = re[i] * scale, b = im[i] * scale;
    magnitude[i] = std::sqrt(a * a + b * b);
    phase[i] = detail::fast_atan2(b, a);
  }
  if (params_.normalise_brightness) {
    const std::size_t per_channel = static_cast<std::size_t>(signature.rows) * m;
    for (int c = 0; c < signature.channels; ++c) {
      float* channel = magnitude + static_cast<std::size_t>(c) * per_channel;
      double mean = 0.0;
      for (int y = 0; y < signature.rows; ++y) mean += channel[static_cast<std::size_t>(y) * m];
      mean /= signature.rows;
      if (mean <= 1e-3) continue;  // a black channel stays black
      const float gain = static_cast<float>(128.0 / mean);
      for (std::size_t i = 0; i < per_channel; ++i) channel[i] *= gain;
    }
  }
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
