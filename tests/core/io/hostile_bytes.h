// SPDX-License-Identifier: Apache-2.0
// Crafted bytes of image files that lie about their size (for the hostile-input tests of the
// readers and of `artcam warp`): valid up to the lie, so the reader gets as far as the size.
#pragma once

#include <array>
#include <cstdint>
#include <string>

namespace artcam::test {

// CRC-32 of PNG chunks (ISO 3309, the polynomial 0xEDB88320 reflected), written out so the
// crafted header is a valid PNG up to the lie in its size.
inline std::uint32_t crc32(const std::string& bytes) {
  std::uint32_t crc = 0xFFFFFFFFu;
  for (const unsigned char byte : bytes) {
    crc ^= byte;
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
  }
  return ~crc;
}

inline std::string bigEndian32(std::uint32_t v) {
  return {static_cast<char>(v >> 24), static_cast<char>(v >> 16), static_cast<char>(v >> 8),
          static_cast<char>(v)};
}

inline std::string pngChunk(const std::string& type, const std::string& data) {
  return bigEndian32(static_cast<std::uint32_t>(data.size())) + type + data +
         bigEndian32(crc32(type + data));
}

// A PNG whose IHDR claims width × height RGB pixels, with no image data at all (59 bytes).
inline std::string pngHeaderOnly(std::uint32_t width, std::uint32_t height) {
  const std::string ihdr =
      bigEndian32(width) + bigEndian32(height) + std::string("\x08\x02\x00\x00\x00", 5);
  // libpng reads chunks up to the first IDAT when the file is opened; a bare zlib header is
  // enough to get past that (and IEND straight after IHDR is refused as out of place).
  return std::string("\x89PNG\r\n\x1a\n", 8) + pngChunk("IHDR", ihdr) +
         pngChunk("IDAT", "\x78\x9c") + pngChunk("IEND", "");
}

inline std::string littleEndian(std::uint32_t v, int bytes) {
  std::string out;
  for (int k = 0; k < bytes; ++k) out += static_cast<char>(v >> (8 * k));
  return out;
}

// A baseline grey TIFF whose one strip claims width × height bytes (2^31 for 65536 × 32768)
// that the file does not hold.
inline std::string tiffHeaderOnly(std::uint32_t width, std::uint32_t height) {
  struct Entry {
    std::uint16_t tag, type;
    std::uint32_t value;
  };
  constexpr std::uint16_t kShort = 3, kLong = 4;
  const std::array<Entry, 9> entries{{{256, kLong, width},
                                      {257, kLong, height},
                                      {258, kShort, 8},
                                      {259, kShort, 1},
                                      {262, kShort, 1},
                                      {273, kLong, 200},
                                      {277, kShort, 1},
                                      {278, kLong, height},
                                      {279, kLong, width * height}}};
  std::string out = std::string("II*\0", 4) + littleEndian(8, 4) + littleEndian(entries.size(), 2);
  for (const Entry& e : entries)
    out += littleEndian(e.tag, 2) + littleEndian(e.type, 2) + littleEndian(1, 4) +
           littleEndian(e.value, 4);
  return out + littleEndian(0, 4);
}

}  // namespace artcam::test
