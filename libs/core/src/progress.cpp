#include "omninav/core/progress.hpp"

#include <unistd.h>

#include <cstdio>

#include "omninav/core/log.hpp"

namespace omninav {

Progress::Progress(std::string label, std::size_t total)
    : label_(std::move(label)),
      total_(total),
      enabled_(isatty(STDERR_FILENO) == 1 && log_level() >= LogLevel::kInfo),
      start_(std::chrono::steady_clock::now()),
      last_draw_(start_) {}

Progress::~Progress() {
  if (enabled_) draw(true);
}

void Progress::advance(std::size_t steps) {
  done_ += steps;
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  // Redraw at most ten times a second: drawing is slower than many loop bodies.
  if (now - last_draw_ < std::chrono::milliseconds(100) && done_ < total_) return;
  last_draw_ = now;
  draw(false);
}

void Progress::draw(bool final) {
  constexpr int kBarWidth = 30;
  const double fraction = total_ == 0 ? 1.0 : static_cast<double>(done_) / total_;
  const int filled = static_cast<int>(fraction * kBarWidth + 0.5);
  const double elapsed_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const double remaining_s = fraction > 0.0 ? elapsed_s * (1.0 - fraction) / fraction : 0.0;
  std::fprintf(stderr, "\r%s [%-*s] %zu/%zu  %.0f s left ", label_.c_str(), kBarWidth,
               std::string(static_cast<std::size_t>(filled), '#').c_str(), done_, total_,
               final ? 0.0 : remaining_s);
  if (final) std::fprintf(stderr, "\n");
  std::fflush(stderr);
}

}  // namespace omninav
