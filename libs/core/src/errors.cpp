#include "omninav/core/errors.hpp"

#include <system_error>

namespace omninav {

std::string unreadable_file_reason(const std::filesystem::path& path, const std::string& kind) {
  namespace fs = std::filesystem;
  const std::string a_kind = (kind.find_first_of("aeiouAEIOU") == 0 ? "an " : "a ") + kind;
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

std::string printable_name(std::string_view bytes) {
  static constexpr char kHex[] = "0123456789abcdef";
  std::string text;
  const auto escape = [&](unsigned char byte) {
    text += "\\x";
    text += kHex[byte >> 4];
    text += kHex[byte & 0xF];
  };
  for (std::size_t i = 0; i < bytes.size();) {
    const auto byte = static_cast<unsigned char>(bytes[i]);
    if (byte < 0x20 || byte == 0x7F) {
      escape(byte);
      ++i;
      continue;
    }
    // The length of a UTF-8 sequence from its first byte; 0 for a byte that cannot start one.
    const std::size_t length = byte < 0x80                    ? 1
                               : byte >= 0xC2 && byte <= 0xDF ? 2
                               : byte >= 0xE0 && byte <= 0xEF ? 3
                               : byte >= 0xF0 && byte <= 0xF4 ? 4
                                                              : 0;
    bool valid = length > 0 && i + length <= bytes.size();
    for (std::size_t k = 1; valid && k < length; ++k) {
      valid = (static_cast<unsigned char>(bytes[i + k]) & 0xC0) == 0x80;
    }
    if (valid && length >= 3) {  // no overlong forms, surrogates or code points past U+10FFFF
      const auto second = static_cast<unsigned char>(bytes[i + 1]);
      valid = !(byte == 0xE0 && second < 0xA0) && !(byte == 0xED && second > 0x9F) &&
              !(byte == 0xF0 && second < 0x90) && !(byte == 0xF4 && second > 0x8F);
    }
    if (!valid) {
      escape(byte);
      ++i;
      continue;
    }
    text.append(bytes.substr(i, length));
    i += length;
  }
  return text;
}

}  // namespace omninav
