#pragma once
// A progress line on stderr for long loops, drawn only when stderr is a terminal, so that CI
// logs and redirected output stay clean (docs/design.md, Conventions: Output).

#include <chrono>
#include <cstddef>
#include <string>

namespace omninav {

class Progress {
 public:
  Progress(std::string label, std::size_t total);
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  void advance(std::size_t steps = 1);

 private:
  void draw(bool final);

  std::string label_;
  std::size_t total_;
  std::size_t done_ = 0;
  bool enabled_;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_draw_;
};

}  // namespace omninav
