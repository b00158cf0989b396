// SPDX-License-Identifier: Apache-2.0
// PLY writing (see ply.h): binary little endian by default, uchar sRGB colours from linear
// premultiplied ones, numbers in ASCII as the shortest text that reads back exactly.
#include "core/io/ply.h"

#include "core/io/atomic_file.h"
#include "core/colour/transfer.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <stdexcept>

namespace artcam {

namespace {

template <class T>
void appendBinary(std::string& out, T v, bool big_endian) {
  std::array<char, sizeof(T)> b;
  std::memcpy(b.data(), &v, sizeof(T));
  if (big_endian != (std::endian::native == std::endian::big)) std::reverse(b.begin(), b.end());
  out.append(b.data(), b.size());
}

template <class T>
void appendText(std::string& out, T v) {
  std::array<char, 64> b;
  const auto r = std::to_chars(b.data(), b.data() + b.size(), v);  // shortest round trip
  out.append(b.data(), r.ptr);
}

}  // namespace

std::string plyBytes(const PointCloud& cloud, const PlyWriteOptions& options) {
  const bool colour = cloud.hasColour();
  bool alpha = colour && cloud.has_alpha;
  for (size_t i = 0; colour && !alpha && i < cloud.size(); ++i) alpha = cloud.colours[i][3] != 1.0f;
  const char* pos_type = options.double_positions ? "double" : "float";
  std::string out = "ply\nformat ";
  out += options.format == PlyFormat::Ascii                ? "ascii"
         : options.format == PlyFormat::BinaryLittleEndian ? "binary_little_endian"
                                                           : "binary_big_endian";
  out += " 1.0\n";
  if (!options.comment.empty()) out += "comment " + options.comment + "\n";
  out += "element vertex " + std::to_string(cloud.size()) + "\n";
  for (const char* axis : {"x", "y", "z"})
    out += std::string("property ") + pos_type + " " + axis + "\n";
  if (colour) out += "property uchar red\nproperty uchar green\nproperty uchar blue\n";
  if (alpha) out += "property uchar alpha\n";
  out += "end_header\n";

  const Transfer srgb = Transfer::srgb();
  const auto toByte = [](double v) {
    return static_cast<std::uint8_t>(std::lround(std::clamp(v, 0.0, 1.0) * 255.0));
  };
  const bool big = options.format == PlyFormat::BinaryBigEndian;
  out.reserve(out.size() + cloud.size() * (options.double_positions ? 28 : 16));
  for (size_t i = 0; i < cloud.size(); ++i) {
    const Eigen::Vector3d& p = cloud.positions[i];
    std::array<std::uint8_t, 4> c{};
    if (colour) {
      const Eigen::Vector4f& q = cloud.colours[i];
      const double a = q[3];
      for (int k = 0; k < 3; ++k)
        c[k] = toByte(a > 0 ? srgb.encode(q[k] / a) : 0.0);  // unpremultiply
      c[3] = toByte(a);
    }
    const int channels = colour ? (alpha ? 4 : 3) : 0;
    if (options.format == PlyFormat::Ascii) {
      for (int k = 0; k < 3; ++k) {
        if (k) out += ' ';
        if (options.double_positions)
          appendText(out, p[k]);
        else
          appendText(out, static_cast<float>(p[k]));
      }
      for (int k = 0; k < channels; ++k) out += ' ' + std::to_string(c[k]);
      out += '\n';
    } else {
      for (int k = 0; k < 3; ++k) {
        if (options.double_positions)
          appendBinary(out, p[k], big);
        else
          appendBinary(out, static_cast<float>(p[k]), big);
      }
      for (int k = 0; k < channels; ++k) out += static_cast<char>(c[k]);
    }
  }
  return out;
}

Status writePly(const std::string& path, const PointCloud& cloud, const PlyWriteOptions& options) {
  if (cloud.hasColour() && cloud.colours.size() != cloud.size())
    throw std::invalid_argument("writePly: colours and positions differ in count");
  const std::string bytes = plyBytes(cloud, options);
  return writeAtomically(path, [&](const std::string& temp) {
    std::ofstream out(temp, std::ios::binary | std::ios::trunc);
    if (!out) return Status::failure(path + ": cannot write (" + std::strerror(errno) + ")");
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    out.flush();
    if (!out) return Status::failure(path + ": write failed (" + std::strerror(errno) + ")");
    return Status::success();
  });
}

}  // namespace artcam
