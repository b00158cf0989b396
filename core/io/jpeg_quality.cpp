// SPDX-License-Identifier: Apache-2.0
#include "core/io/jpeg_quality.h"

#include <array>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <limits>

namespace artcam {

namespace {

// The standard luminance table (ITU T.81 Annex K), in zig-zag order as DQT stores it.
constexpr std::array<int, 64> kLuminanceZigZag = {
    16, 11, 12,  14,  12,  10, 16, 14,  13,  14,  18,  17,  16, 19,  24,  40,
    26, 24, 22,  22,  24,  49, 35, 37,  29,  40,  58,  51,  61, 60,  57,  51,
    56, 55, 64,  72,  92,  78, 64, 68,  87,  69,  55,  56,  80, 109, 81,  87,
    95, 98, 103, 104, 103, 62, 77, 113, 121, 112, 100, 120, 92, 101, 103, 99};

// libjpeg's jpeg_quality_scaling and jpeg_add_quant_table with force_baseline.
int scaledEntry(int base, int quality) {
  const int scale = quality < 50 ? 5000 / quality : 200 - 2 * quality;
  const long v = (static_cast<long>(base) * scale + 50) / 100;
  return static_cast<int>(v < 1 ? 1 : v > 255 ? 255 : v);
}

int nearestQuality(const std::array<int, 64>& table) {
  int best = 0;
  long best_error = std::numeric_limits<long>::max();
  for (int q = 1; q <= 100; ++q) {
    long error = 0;
    for (size_t i = 0; i < 64; ++i)
      error += std::labs(scaledEntry(kLuminanceZigZag[i], q) - table[i]);
    if (error < best_error) best_error = error, best = q;
  }
  return best;
}

}  // namespace

int estimateJpegQuality(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  auto byte = [&in]() -> int {
    const int c = in.get();
    return c == std::char_traits<char>::eof() ? -1 : c;
  };
  if (byte() != 0xFF || byte() != 0xD8) return 0;
  // Segments up to the first scan; a hostile file ends the walk at EOF or at a bad length.
  for (int segments = 0; segments < 1000; ++segments) {
    int marker = byte();
    if (marker != 0xFF) return 0;
    while (marker == 0xFF) marker = byte();                              // fill bytes
    if (marker < 0 || marker == 0xD9 || marker == 0xDA) return 0;        // EOI, SOS, EOF
    if (marker == 0x01 || (marker >= 0xD0 && marker <= 0xD7)) continue;  // no length
    const int high = byte(), low = byte();
    if (high < 0 || low < 0) return 0;
    int length = high * 256 + low - 2;
    if (length < 0) return 0;
    if (marker != 0xDB) {
      in.seekg(length, std::ios::cur);
      if (!in) return 0;
      continue;
    }
    // DQT: tables of (precision << 4 | id) then 64 entries of 1 or 2 bytes.
    while (length > 0) {
      const int pq_tq = byte();
      if (pq_tq < 0) return 0;
      const bool sixteen = (pq_tq >> 4) != 0;
      std::array<int, 64> table{};
      for (int& entry : table) {
        entry = byte();
        if (sixteen) entry = entry < 0 ? -1 : entry * 256 + byte();
        if (entry < 0) return 0;
      }
      length -= 1 + (sixteen ? 128 : 64);
      if ((pq_tq & 0x0F) == 0) return sixteen ? 0 : nearestQuality(table);
    }
  }
  return 0;
}

std::string jpegSubsampling(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  auto byte = [&in]() -> int {
    const int c = in.get();
    return c == std::char_traits<char>::eof() ? -1 : c;
  };
  if (byte() != 0xFF || byte() != 0xD8) return "";
  for (int segments = 0; segments < 1000; ++segments) {
    int marker = byte();
    if (marker != 0xFF) return "";
    while (marker == 0xFF) marker = byte();
    if (marker < 0 || marker == 0xD9 || marker == 0xDA) return "";
    if (marker == 0x01 || (marker >= 0xD0 && marker <= 0xD7)) continue;
    const int high = byte(), low = byte();
    if (high < 0 || low < 0) return "";
    const int length = high * 256 + low - 2;
    if (length < 0) return "";
    // SOF0…SOF15 but DHT (C4), JPG (C8) and DAC (CC): precision, height, width, components,
    // then per component (id, H << 4 | V, table).
    const bool frame =
        marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC;
    if (!frame) {
      in.seekg(length, std::ios::cur);
      if (!in) return "";
      continue;
    }
    for (int k = 0; k < 5; ++k)
      if (byte() < 0) return "";
    const int components = byte();
    if (components != 3 || length < 6 + 3 * 3) return "";
    int h[3], v[3];
    for (int c = 0; c < 3; ++c) {
      byte();
      const int hv = byte();
      if (byte() < 0 || hv < 0) return "";
      h[c] = hv >> 4, v[c] = hv & 0x0F;
    }
    if (h[1] != h[2] || v[1] != v[2] || h[1] < 1 || v[1] < 1 || h[0] % h[1] || v[0] % v[1])
      return "";
    const int across = h[0] / h[1], down = v[0] / v[1];
    if (across == 1 && down == 1) return "4:4:4";
    if (across == 2 && down == 1) return "4:2:2";
    if (across == 2 && down == 2) return "4:2:0";
    if (across == 1 && down == 2) return "4:4:0";
    if (across == 4 && down == 1) return "4:1:1";
    return "";
  }
  return "";
}

}  // namespace artcam
