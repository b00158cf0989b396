#include "core/depth/depth_map_file.h"

#include "core/io/io_text.h"

#include <OpenImageIO/imageio.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <vector>

namespace artcam {

Result<ImageF> readDepthMap(const std::string& path, const DepthMapOptions& options,
                            DepthMapInfo* info) {
  using R = Result<ImageF>;
  using io_text::oneLine;
  if (!(options.scale > 0.0) || !std::isfinite(options.scale))
    return R::failure(path + ": depth scale must be a finite number greater than 0");
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error))
    return R::failure(path + ": cannot read: " +
                      (std::filesystem::exists(path, error) ? "not a file" : "no such file"));
  auto in = OIIO::ImageInput::open(path);
  if (!in) return R::failure(path + ": cannot read: " + oneLine(OIIO::geterror()));
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0)
    return R::failure(path + ": the depth map is empty");
  if (static_cast<int64_t>(spec.width) * spec.height > (int64_t{1} << 30))
    return R::failure(path + ": the depth map is too large (" + std::to_string(spec.width) + "x" +
                      std::to_string(spec.height) + ")");
  const bool integer = spec.format.basetype == OIIO::TypeDesc::UINT8 ||
                       spec.format.basetype == OIIO::TypeDesc::UINT16 ||
                       spec.format.basetype == OIIO::TypeDesc::INT8 ||
                       spec.format.basetype == OIIO::TypeDesc::INT16;
  const size_t n = static_cast<size_t>(spec.width) * static_cast<size_t>(spec.height);
  std::vector<float> values(n);
  bool ok = false;
  if (integer) {
    // Stored integers, exactly: read in the file's own width (OIIO would normalise a float
    // request to [0, 1]).
    const bool wide = spec.format.size() > 1;
    if (wide) {
      std::vector<uint16_t> raw(n);
      ok = in->read_image(0, 0, 0, 1, OIIO::TypeDesc::UINT16, raw.data());
      for (size_t i = 0; ok && i < n; ++i) values[i] = static_cast<float>(raw[i]);
    } else {
      std::vector<uint8_t> raw(n);
      ok = in->read_image(0, 0, 0, 1, OIIO::TypeDesc::UINT8, raw.data());
      for (size_t i = 0; ok && i < n; ++i) values[i] = static_cast<float>(raw[i]);
    }
  } else {
    ok = in->read_image(0, 0, 0, 1, OIIO::TypeDesc::FLOAT, values.data());
  }
  if (!ok) return R::failure(path + ": cannot read: " + oneLine(in->geterror()));
  ImageF depth(spec.width, spec.height, 2, 1);
  size_t missing = 0;
  for (size_t i = 0; i < n; ++i) {
    double z = static_cast<double>(values[i]) * options.scale;
    if (options.inverse && z > 0.0) z = 1.0 / z;
    if (!(z > 0.0) || !std::isfinite(z)) {
      ++missing;
      continue;
    }
    depth.data[2 * i] = static_cast<float>(z);
    depth.data[2 * i + 1] = 1.0f;
  }
  if (info) {
    info->pixel_type = integer ? (spec.format.size() == 1 ? "uint8" : "uint16")
                               : (spec.format.basetype == OIIO::TypeDesc::HALF ? "half" : "float");
    info->missing = missing;
  }
  return R::success(std::move(depth));
}

}  // namespace artcam
