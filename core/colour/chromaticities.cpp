// SPDX-License-Identifier: Apache-2.0
#include "core/colour/chromaticities.h"

#include <cmath>
#include <cstdio>

namespace artcam {

namespace {

Matrix3 multiply(const Matrix3& a, const Matrix3& b) {
  Matrix3 m{};
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      for (int k = 0; k < 3; ++k) m[r * 3 + c] += a[r * 3 + k] * b[k * 3 + c];
  return m;
}

double determinant(const Matrix3& m) {
  return m[0] * (m[4] * m[8] - m[5] * m[7]) - m[1] * (m[3] * m[8] - m[5] * m[6]) +
         m[2] * (m[3] * m[7] - m[4] * m[6]);
}

Matrix3 inverse(const Matrix3& m) {
  const double d = determinant(m);
  return {(m[4] * m[8] - m[5] * m[7]) / d, (m[2] * m[7] - m[1] * m[8]) / d,
          (m[1] * m[5] - m[2] * m[4]) / d, (m[5] * m[6] - m[3] * m[8]) / d,
          (m[0] * m[8] - m[2] * m[6]) / d, (m[2] * m[3] - m[0] * m[5]) / d,
          (m[3] * m[7] - m[4] * m[6]) / d, (m[1] * m[6] - m[0] * m[7]) / d,
          (m[0] * m[4] - m[1] * m[3]) / d};
}

std::array<double, 3> apply(const Matrix3& m, const std::array<double, 3>& v) {
  return {m[0] * v[0] + m[1] * v[1] + m[2] * v[2], m[3] * v[0] + m[4] * v[1] + m[5] * v[2],
          m[6] * v[0] + m[7] * v[1] + m[8] * v[2]};
}

std::array<double, 3> xyzOf(double x, double y) { return {x / y, 1.0, (1.0 - x - y) / y}; }

// RGB → XYZ (SMPTE RP 177): the primaries' XYZ as columns, each scaled so RGB 1 is the white.
Matrix3 xyzFromRgb(const Chromaticities& c) {
  const auto r = xyzOf(c.xy[0], c.xy[1]), g = xyzOf(c.xy[2], c.xy[3]), b = xyzOf(c.xy[4], c.xy[5]);
  const Matrix3 primaries{r[0], g[0], b[0], r[1], g[1], b[1], r[2], g[2], b[2]};
  const auto s = apply(inverse(primaries), xyzOf(c.xy[6], c.xy[7]));
  Matrix3 m = primaries;
  for (int row = 0; row < 3; ++row)
    for (int col = 0; col < 3; ++col) m[row * 3 + col] *= s[col];
  return m;
}

// Bradford's chromatic adaptation from white `from` to white `to` (both xy).
Matrix3 bradford(double from_x, double from_y, double to_x, double to_y) {
  const Matrix3 cone{0.8951, 0.2664, -0.1614, -0.7502, 1.7135, 0.0367, 0.0389, -0.0685, 1.0296};
  const auto from = apply(cone, xyzOf(from_x, from_y));
  const auto to = apply(cone, xyzOf(to_x, to_y));
  const Matrix3 scale{to[0] / from[0], 0, 0, 0, to[1] / from[1], 0, 0, 0, to[2] / from[2]};
  return multiply(inverse(cone), multiply(scale, cone));
}

}  // namespace

Chromaticities Chromaticities::rec709() {
  return {{0.64, 0.33, 0.30, 0.60, 0.15, 0.06, 0.3127, 0.3290}};
}

bool Chromaticities::isRec709() const {
  const Chromaticities w = rec709();
  for (size_t k = 0; k < xy.size(); ++k)
    if (!(std::fabs(xy[k] - w.xy[k]) <= 1e-4)) return false;
  return true;
}

bool Chromaticities::valid() const {
  for (size_t k = 0; k < xy.size(); ++k)
    if (!std::isfinite(xy[k]) || (k % 2 == 1 && !(xy[k] > 0.0))) return false;
  // The primaries' xy triangle must have an area: else no RGB reaches the white.
  const double area = (xy[2] - xy[0]) * (xy[5] - xy[1]) - (xy[4] - xy[0]) * (xy[3] - xy[1]);
  if (!(std::fabs(area) > 1e-6)) return false;
  const Matrix3 m = xyzFromRgb(*this);
  for (double v : m)
    if (!std::isfinite(v)) return false;
  return std::isfinite(1.0 / determinant(m));
}

std::string Chromaticities::describe() const {
  // A value that is no number is said in words: a hostile file's NaN is not printed as "nan".
  const auto value = [](double v) {
    if (!std::isfinite(v)) return std::string("not a number");
    char text[32];
    std::snprintf(text, sizeof text, "%.4g", v);
    return std::string(text);
  };
  const char* names[] = {"R", "G", "B", "W"};
  std::string text;
  for (size_t k = 0; k < 4; ++k)
    text += (k ? " " : "") + std::string(names[k]) + "(" + value(xy[2 * k]) + ", " +
            value(xy[2 * k + 1]) + ")";
  return text;
}

Matrix3 workingFromChromaticities(const Chromaticities& file) {
  const Chromaticities working = Chromaticities::rec709();
  return multiply(
      inverse(xyzFromRgb(working)),
      multiply(bradford(file.xy[6], file.xy[7], working.xy[6], working.xy[7]), xyzFromRgb(file)));
}

Matrix3 chromaticitiesFromWorking(const Chromaticities& file) {
  return inverse(workingFromChromaticities(file));
}

std::optional<Chromaticities> chromaticitiesOfMatrix(const Matrix3& file_from_working) {
  if (!(std::fabs(determinant(file_from_working)) > 1e-12)) return std::nullopt;
  // Column k of XYZ-from-file is the XYZ of the file's primary k; their sum its white.
  const Matrix3 xyz = multiply(xyzFromRgb(Chromaticities::rec709()), inverse(file_from_working));
  Chromaticities c;
  for (int k = 0; k < 4; ++k) {
    const std::array<double, 3> v =
        k < 3 ? std::array<double, 3>{xyz[k], xyz[3 + k], xyz[6 + k]} : apply(xyz, {1.0, 1.0, 1.0});
    const double sum = v[0] + v[1] + v[2];
    if (!(std::fabs(sum) > 1e-12)) return std::nullopt;
    c.xy[2 * k] = v[0] / sum;
    c.xy[2 * k + 1] = v[1] / sum;
  }
  if (!c.valid()) return std::nullopt;
  return c;
}

void applyMatrix(const Matrix3& m, float* data, size_t pixels, int channels, int alpha_channel) {
  int rgb[3];
  int found = 0;
  for (int c = 0; c < channels && found < 3; ++c)
    if (c != alpha_channel) rgb[found++] = c;
  if (found < 3) return;
  for (size_t p = 0; p < pixels; ++p) {
    float* px = data + p * static_cast<size_t>(channels);
    const double r = px[rgb[0]], g = px[rgb[1]], b = px[rgb[2]];
    px[rgb[0]] = static_cast<float>(m[0] * r + m[1] * g + m[2] * b);
    px[rgb[1]] = static_cast<float>(m[3] * r + m[4] * g + m[5] * b);
    px[rgb[2]] = static_cast<float>(m[6] * r + m[7] * g + m[8] * b);
  }
}

}  // namespace artcam
