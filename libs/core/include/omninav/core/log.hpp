#pragma once
// Logging to stderr. The app sets the level once from --quiet/--verbose; libraries only log.

#include <string_view>

namespace omninav {

enum class LogLevel { kError = 0, kWarning = 1, kInfo = 2, kDebug = 3 };

void set_log_level(LogLevel level);
LogLevel log_level();

void log_error(std::string_view message);
void log_warning(std::string_view message);
void log_info(std::string_view message);
void log_debug(std::string_view message);

}  // namespace omninav
