#include "omninav/core/log.hpp"

#include <atomic>
#include <iostream>
#include <mutex>

namespace omninav {
namespace {

std::atomic<LogLevel> current_level{LogLevel::kInfo};
std::mutex output_mutex;

void write(LogLevel level, std::string_view prefix, std::string_view message) {
  if (level > current_level.load()) return;
  const std::lock_guard lock(output_mutex);
  std::cerr << prefix << message << '\n';
}

}  // namespace

void set_log_level(LogLevel level) {
  current_level = level;
}
LogLevel log_level() {
  return current_level.load();
}

void log_error(std::string_view message) {
  write(LogLevel::kError, "error: ", message);
}
void log_warning(std::string_view message) {
  write(LogLevel::kWarning, "warning: ", message);
}
void log_info(std::string_view message) {
  write(LogLevel::kInfo, "", message);
}
void log_debug(std::string_view message) {
  write(LogLevel::kDebug, "debug: ", message);
}

}  // namespace omninav
