// SPDX-License-Identifier: Apache-2.0
#include "core/depth/region_mask.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace artcam {
namespace {

// Coverage in [0, 1] of a dab at distance d from its centre (see region_mask.h).
double dabProfile(double d, double radius, double hardness) {
  if (d > radius) return 0.0;
  const double inner = std::clamp(hardness, 0.0, 1.0) * radius;
  if (d <= inner) return 1.0;
  const double t = (radius - d) / (radius - inner);  // 1 at inner, 0 at the rim
  return t * t * (3.0 - 2.0 * t);
}

}  // namespace

PixelRect PixelRect::united(const PixelRect& o) const {
  if (empty()) return o;
  if (o.empty()) return *this;
  return {std::min(x0, o.x0), std::min(y0, o.y0), std::max(x1, o.x1), std::max(y1, o.y1)};
}

RegionMask::RegionMask(int width, int height)
    : width_(std::max(0, width)),
      height_(std::max(0, height)),
      coverage_(static_cast<size_t>(width_) * static_cast<size_t>(height_), 0) {}

PixelRect RegionMask::clip(const PixelRect& r) const {
  PixelRect c{std::max(r.x0, 0), std::max(r.y0, 0), std::min(r.x1, width_),
              std::min(r.y1, height_)};
  return c.empty() ? PixelRect{} : c;
}

PixelRect RegionMask::dabRect(const Eigen::Vector2d& centre, double r) const {
  if (!(r > 0.0) || !centre.allFinite()) return {};
  return clip({static_cast<int>(std::floor(centre.x() - r - 0.5)),
               static_cast<int>(std::floor(centre.y() - r - 0.5)),
               static_cast<int>(std::ceil(centre.x() + r + 0.5)),
               static_cast<int>(std::ceil(centre.y() + r + 0.5))});
}

PixelRect RegionMask::stamp(const Eigen::Vector2d& centre, const BrushOptions& brush,
                            const DabLimit* limit) {
  const double r = brush.radius;
  if (!(r > 0.0) || !centre.allFinite()) return {};
  const PixelRect rect = dabRect(centre, r);
  for (int y = rect.y0; y < rect.y1; ++y)
    for (int x = rect.x0; x < rect.x1; ++x) {
      if (limit && !limit->allows(x, y)) continue;
      const double d = std::hypot(x + 0.5 - centre.x(), y + 0.5 - centre.y());
      const double a = dabProfile(d, r, brush.hardness);
      if (a <= 0.0) continue;
      const auto dab = static_cast<uint8_t>(std::lround(255.0 * a));
      uint8_t& c = coverage_[index(x, y)];
      c = brush.erase ? std::min<uint8_t>(c, static_cast<uint8_t>(255 - dab)) : std::max(c, dab);
    }
  return rect;
}

PixelRect RegionMask::segment(const Eigen::Vector2d& from, const Eigen::Vector2d& to,
                              const BrushOptions& brush) {
  if (!from.allFinite() || !to.allFinite()) return {};
  const double spacing = std::max(1.0, 0.25 * brush.radius);
  const double length = (to - from).norm();
  const int steps = std::max(1, static_cast<int>(std::ceil(length / spacing)));
  PixelRect touched;
  for (int s = 1; s <= steps; ++s)
    touched = touched.united(stamp(from + (to - from) * (static_cast<double>(s) / steps), brush));
  return touched;
}

PixelRect RegionMask::fillPolygon(const std::vector<Eigen::Vector2d>& vertices, bool erase) {
  if (vertices.size() < 3) return {};
  double min_x = vertices[0].x(), max_x = min_x, min_y = vertices[0].y(), max_y = min_y;
  for (const Eigen::Vector2d& v : vertices) {
    if (!v.allFinite()) return {};
    min_x = std::min(min_x, v.x());
    max_x = std::max(max_x, v.x());
    min_y = std::min(min_y, v.y());
    max_y = std::max(max_y, v.y());
  }
  const PixelRect rect =
      clip({static_cast<int>(std::floor(min_x)), static_cast<int>(std::floor(min_y)),
            static_cast<int>(std::ceil(max_x)) + 1, static_cast<int>(std::ceil(max_y)) + 1});
  const uint8_t value = erase ? 0 : 255;
  std::vector<double> crossings;
  const size_t n = vertices.size();
  for (int y = rect.y0; y < rect.y1; ++y) {
    const double cy = y + 0.5;
    crossings.clear();
    for (size_t i = 0; i < n; ++i) {
      const Eigen::Vector2d& a = vertices[i];
      const Eigen::Vector2d& b = vertices[(i + 1) % n];
      // Half-open in y so a vertex on the scanline is counted once.
      if ((a.y() <= cy) != (b.y() <= cy))
        crossings.push_back(a.x() + (cy - a.y()) * (b.x() - a.x()) / (b.y() - a.y()));
    }
    std::sort(crossings.begin(), crossings.end());
    for (size_t k = 0; k + 1 < crossings.size(); k += 2) {
      // Pixels x with centre x + 0.5 in [left, right).
      const int xa = std::max(rect.x0, static_cast<int>(std::ceil(crossings[k] - 0.5)));
      const int xb = std::min(rect.x1, static_cast<int>(std::ceil(crossings[k + 1] - 0.5)));
      for (int x = xa; x < xb; ++x) coverage_[index(x, y)] = value;
    }
  }
  return rect;
}

std::vector<uint8_t> RegionMask::copyRect(const PixelRect& rect) const {
  const PixelRect r = clip(rect);
  std::vector<uint8_t> out;
  out.reserve(static_cast<size_t>(r.width()) * static_cast<size_t>(r.height()));
  for (int y = r.y0; y < r.y1; ++y)
    out.insert(out.end(), coverage_.begin() + static_cast<std::ptrdiff_t>(index(r.x0, y)),
               coverage_.begin() + static_cast<std::ptrdiff_t>(index(r.x1 - 1, y)) + 1);
  return out;
}

void RegionMask::pasteRect(const PixelRect& rect, const std::vector<uint8_t>& bytes) {
  if (clip(rect) != rect ||
      bytes.size() != static_cast<size_t>(rect.width()) * static_cast<size_t>(rect.height()))
    throw std::invalid_argument("RegionMask::pasteRect: rectangle and bytes disagree");
  const size_t w = static_cast<size_t>(rect.width());
  for (int y = rect.y0; y < rect.y1; ++y)
    std::copy_n(bytes.begin() + static_cast<std::ptrdiff_t>(static_cast<size_t>(y - rect.y0) * w),
                w, coverage_.begin() + static_cast<std::ptrdiff_t>(index(rect.x0, y)));
}

size_t RegionMask::coveredCount() const {
  return static_cast<size_t>(
      std::count_if(coverage_.begin(), coverage_.end(), [](uint8_t c) { return c > 0; }));
}

std::vector<uint8_t> encodeMaskRuns(const RegionMask& mask) {
  std::vector<uint8_t> out;
  const std::vector<uint8_t>& c = mask.coverage();
  size_t i = 0;
  while (i < c.size()) {
    size_t j = i + 1;
    while (j < c.size() && c[j] == c[i]) ++j;
    out.push_back(c[i]);
    uint64_t run = j - i;
    do {
      uint8_t byte = run & 0x7f;
      run >>= 7;
      if (run) byte |= 0x80;
      out.push_back(byte);
    } while (run);
    i = j;
  }
  return out;
}

Result<RegionMask> decodeMaskRuns(const std::vector<uint8_t>& bytes, int width, int height,
                                  const std::string& where) {
  if (width <= 0 || height <= 0 || static_cast<int64_t>(width) * height > (int64_t{1} << 31))
    return Result<RegionMask>::failure(where + ": bad mask size " + std::to_string(width) + "x" +
                                       std::to_string(height));
  const uint64_t total = static_cast<uint64_t>(width) * static_cast<uint64_t>(height);
  RegionMask mask(width, height);
  std::vector<uint8_t> c(total, 0);
  uint64_t filled = 0;
  size_t i = 0;
  while (i < bytes.size()) {
    const uint8_t value = bytes[i++];
    uint64_t run = 0;
    int shift = 0;
    for (;;) {
      if (i >= bytes.size())
        return Result<RegionMask>::failure(where + ": truncated run at byte " + std::to_string(i));
      if (shift > 35)
        return Result<RegionMask>::failure(where + ": run length too long at byte " +
                                           std::to_string(i));
      const uint8_t b = bytes[i++];
      run |= static_cast<uint64_t>(b & 0x7f) << shift;
      shift += 7;
      if (!(b & 0x80)) break;
    }
    if (run == 0 || run > total - filled)
      return Result<RegionMask>::failure(where + ": runs exceed the mask size " +
                                         std::to_string(width) + "x" + std::to_string(height));
    std::fill_n(c.begin() + static_cast<std::ptrdiff_t>(filled), run, value);
    filled += run;
  }
  if (filled != total)
    return Result<RegionMask>::failure(where + ": runs cover " + std::to_string(filled) + " of " +
                                       std::to_string(total) + " pixels");
  mask.pasteRect(mask.bounds(), c);
  return Result<RegionMask>::success(std::move(mask));
}

}  // namespace artcam
