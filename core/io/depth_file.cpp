// SPDX-License-Identifier: Apache-2.0
#include "core/io/depth_file.h"
#include "core/io/oiio_io.h"

#include "core/io/image_input.h"
#include "core/io/io_text.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace artcam {

namespace {

bool isInteger(OIIO::TypeDesc::BASETYPE t) {
  return t == OIIO::TypeDesc::UINT8 || t == OIIO::TypeDesc::INT8 || t == OIIO::TypeDesc::UINT16 ||
         t == OIIO::TypeDesc::INT16;
}

// The first channel's stored values as floats: integer counts exactly (asking OpenImageIO for
// FLOAT would normalise them to [0, 1]), float values as they are.
bool readFirstChannel(OIIO::ImageInput& in, std::vector<float>& values) {
  const OIIO::ImageSpec& spec = in.spec();
  const size_t n = static_cast<size_t>(spec.width) * static_cast<size_t>(spec.height);
  values.resize(n);
  const OIIO::TypeDesc::BASETYPE t = static_cast<OIIO::TypeDesc::BASETYPE>(spec.format.basetype);
  if (!isInteger(t)) return in.read_image(0, 0, 0, 1, OIIO::TypeDesc::FLOAT, values.data());
  const auto widen = [&](auto tag, OIIO::TypeDesc type) {
    std::vector<decltype(tag)> raw(n);
    if (!in.read_image(0, 0, 0, 1, type, raw.data())) return false;
    std::transform(raw.begin(), raw.end(), values.begin(),
                   [](auto v) { return static_cast<float>(v); });
    return true;
  };
  switch (t) {
    case OIIO::TypeDesc::UINT8:
      return widen(uint8_t{}, OIIO::TypeDesc::UINT8);
    case OIIO::TypeDesc::INT8:
      return widen(int8_t{}, OIIO::TypeDesc::INT8);
    case OIIO::TypeDesc::UINT16:
      return widen(uint16_t{}, OIIO::TypeDesc::UINT16);
    default:
      return widen(int16_t{}, OIIO::TypeDesc::INT16);
  }
}

}  // namespace

namespace oiio_io {

Result<ImageF> readDepthFile(const std::string& path, const DepthFileOptions& options,
                             DepthFileSummary* summary) {
  using R = Result<ImageF>;
  if (!(options.scale > 0.0) || !std::isfinite(options.scale))
    return R::failure(path + ": the depth scale must be a finite number greater than 0");
  if (!(options.baseline_focal >= 0.0) || !std::isfinite(options.baseline_focal))
    return R::failure(path + ": baseline·focal must be a finite number ≥ 0");
  auto opened = io_input::openImageInput(path);
  if (!opened) return R::failure(opened.status.message);
  OIIO::ImageInput& in = **opened;
  const OIIO::ImageSpec& spec = in.spec();
  if (static_cast<int64_t>(spec.width) * spec.height > (int64_t{1} << 30))
    return R::failure(path + ": the depth map is too large (" + std::to_string(spec.width) + "x" +
                      std::to_string(spec.height) + ")");
  std::vector<float> values;
  const double scale =
      isInteger(static_cast<OIIO::TypeDesc::BASETYPE>(spec.format.basetype)) ? options.scale : 1.0;
  if (!readFirstChannel(in, values))
    return R::failure(path + ": cannot read pixels: " + io_text::oneLine(in.geterror()));
  // A decoder that reports damage but returns success (a TIFF cut in half) would leave the rest
  // of the map as holes: refused like the image readers refuse it.
  if (const Status damage = io_input::decodeProblems(in, path); !damage)
    return R::failure(damage.message);

  const double disparity_factor = options.baseline_focal > 0.0 ? options.baseline_focal
                                  : options.inverse            ? 1.0
                                                               : 0.0;
  ImageF depth(spec.width, spec.height, 1);
  DepthFileSummary s;
  s.pixel_type = spec.format.c_str();
  s.channels = spec.nchannels;
  s.min_depth = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < values.size(); ++i) {
    double z = static_cast<double>(values[i]) * scale;
    if (disparity_factor > 0.0) z = disparity_factor / z;  // 0 → inf: a hole below
    if (!(z > 0.0) || !std::isfinite(z)) {
      ++s.holes;
      continue;  // stays 0: no depth
    }
    depth.data[i] = static_cast<float>(z);
    s.min_depth = std::min(s.min_depth, z);
    s.max_depth = std::max(s.max_depth, z);
  }
  if (s.holes == static_cast<long long>(values.size()))
    return R::failure(path + ": no pixel holds a usable (positive, finite) depth");
  if (summary) *summary = s;
  return R::success(std::move(depth));
}

}  // namespace oiio_io
}  // namespace artcam
