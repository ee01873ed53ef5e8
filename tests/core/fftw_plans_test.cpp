// The process-wide FFTW plan cache (omninav/core/fftw_plans.hpp).
#include "omninav/core/fftw_plans.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <thread>
#include <vector>

#include "omninav/core/errors.hpp"

namespace omninav::fftw {
namespace {

// A plan is made once per shape and handed out again, also to threads asking at once.
TEST(FftwPlans, OnePlanPerShapeAlsoAcrossThreads) {
  const LinesShape shape{90, 3, 48, Planning::kEstimate};
  std::vector<fftw_plan> seen(8, nullptr);
  std::vector<std::thread> threads;
  for (std::size_t t = 0; t < seen.size(); ++t) {
    threads.emplace_back([&seen, t, shape] { seen[t] = lines_r2c(shape); });
  }
  for (std::thread& thread : threads) thread.join();
  for (const fftw_plan plan : seen) EXPECT_EQ(plan, seen.front());
  EXPECT_NE(lines_r2c({90, 3, 0, Planning::kEstimate}), seen.front());  // packed: another shape
  EXPECT_NE(lines_c2r(shape), nullptr);
}

// Forward then backward gives the lines back times their length, with spectra `stride` apart;
// single precision's forward transform gives double's spectra; the plans run on other Buffers
// than the ones they were made on.
TEST(FftwPlans, ForwardThenBackwardRecoversTheLines) {
  const int width = 12, lines = 2, stride = 8;
  Buffer<double> real(width * lines), back(width * lines);
  Buffer<fftw_complex> spectra(stride * lines);
  Buffer<float> real_f(width * lines);
  Buffer<fftwf_complex> spectra_f(stride * lines);
  for (int i = 0; i < width * lines; ++i) {
    real.data()[i] = std::sin(0.7 * i) + i % 5;
    real_f.data()[i] = static_cast<float>(real.data()[i]);
  }
  const LinesShape shape{width, lines, stride, Planning::kEstimate};
  fftw_execute_dft_r2c(lines_r2c(shape), real.data(), spectra.data());
  EXPECT_NEAR(
      spectra.data()[stride][0],
      [&] {  // DC of the second line
        double sum = 0.0;
        for (int c = 0; c < width; ++c) sum += real.data()[width + c];
        return sum;
      }(),
      1e-9);
  fftw_execute_dft_c2r(lines_c2r(shape), spectra.data(), back.data());
  fftwf_execute_dft_r2c(lines_r2c_float(shape), real_f.data(), spectra_f.data());
  for (int i = 0; i < width * lines; ++i) {
    EXPECT_NEAR(back.data()[i] / width, real.data()[i], 1e-12) << i;
  }
  for (int line = 0; line < lines; ++line) {
    for (int k = 0; k <= width / 2; ++k) {
      for (int part = 0; part < 2; ++part) {
        EXPECT_NEAR(spectra_f.data()[line * stride + k][part],
                    spectra.data()[line * stride + k][part], 1e-4)
            << line << ' ' << k;
      }
    }
  }
}

TEST(FftwPlans, ImpossibleShapesAreErrors) {
  EXPECT_THROW(lines_r2c({0, 1, 0, Planning::kEstimate}), Error);
  EXPECT_THROW(lines_r2c({16, 0, 0, Planning::kEstimate}), Error);
  EXPECT_THROW(lines_r2c_float({16, 2, 5, Planning::kEstimate}), Error);  // stride < 9 bins
}

}  // namespace
}  // namespace omninav::fftw
