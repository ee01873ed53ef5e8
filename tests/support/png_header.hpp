// A PNG of its signature and a valid IHDR chunk declaring width x height (8-bit RGB), then
// nothing: a decoder that trusts the header allocates width x height x 3 bytes before it finds
// no pixel data. For the tests of the decoded-size limit (core/image_size.hpp).
#pragma once

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

namespace omninav::testing {

inline void write_header_only_png(const std::filesystem::path& file, std::uint32_t width,
                                  std::uint32_t height) {
  std::string png = "\x89PNG\r\n\x1a\n";
  const auto big_endian = [&png](std::uint32_t value) {
    for (int shift = 24; shift >= 0; shift -= 8) png += static_cast<char>((value >> shift) & 0xFF);
  };
  big_endian(13);
  const std::size_t chunk = png.size();
  png += "IHDR";
  big_endian(width);
  big_endian(height);
  png += std::string("\x08\x02\x00\x00\x00", 5);
  // The chunk's CRC-32 (ISO 3309, as in the PNG specification's annex) over its type and data.
  std::uint32_t crc = 0xFFFFFFFFu;
  for (std::size_t i = chunk; i < png.size(); ++i) {
    crc ^= static_cast<unsigned char>(png[i]);
    for (int bit = 0; bit < 8; ++bit) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
  }
  big_endian(crc ^ 0xFFFFFFFFu);
  std::ofstream(file, std::ios::binary) << png;
}

}  // namespace omninav::testing
