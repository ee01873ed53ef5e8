#include "omninav/core/errors.hpp"

#include <system_error>

namespace omninav {

std::string unreadable_file_reason(const std::filesystem::path& path, const std::string& kind) {
  namespace fs = std::filesystem;
  const std::string a_kind = (kind.find_first_of("aeiou") == 0 ? "an " : "a ") + kind;
  std::error_code error;
  const fs::file_status status = fs::status(path, error);
  if (error && error != std::errc::no_such_file_or_directory) {
    return "cannot reach the " + kind + " (" + error.message() + ")";
  }
  switch (status.type()) {
    case fs::file_type::not_found:
      return "no such " + kind;
    case fs::file_type::directory:
      return "is a folder, not " + a_kind;
    case fs::file_type::fifo:
      return "is a FIFO, not " + a_kind;
    case fs::file_type::socket:
      return "is a socket, not " + a_kind;
    case fs::file_type::block:
    case fs::file_type::character:
      return "is a device, not " + a_kind;
    default:
      return "is not " + a_kind;
  }
}

}  // namespace omninav
