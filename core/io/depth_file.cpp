#include "core/io/depth_file.h"

#include <OpenImageIO/imagebuf.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace artcam {

Result<ImageF> readDepthFile(const std::string& path, const DepthFileOptions& options,
                             DepthFileSummary* summary) {
  if (!(options.scale > 0.0) || !std::isfinite(options.scale))
    return Result<ImageF>::failure(path + ": the depth scale must be a positive number");
  if (!(options.baseline_focal >= 0.0) || !std::isfinite(options.baseline_focal))
    return Result<ImageF>::failure(path + ": baseline·focal must be a number ≥ 0");
  OIIO::ImageBuf buf(path);
  if (!buf.init_spec(path, 0, 0))
    return Result<ImageF>::failure(path + ": cannot open as an image: " + buf.geterror());
  const OIIO::ImageSpec spec = buf.spec();  // a copy: reading as float changes buf.spec()
  if (spec.nchannels < 1 || spec.width < 1 || spec.height < 1)
    return Result<ImageF>::failure(path + ": the depth image is empty");
  // Read the stored values without any colour conversion: raw counts or raw floats.
  const bool is_float = spec.format.basetype == OIIO::TypeDesc::FLOAT ||
                        spec.format.basetype == OIIO::TypeDesc::HALF ||
                        spec.format.basetype == OIIO::TypeDesc::DOUBLE;
  std::vector<float> first(static_cast<size_t>(spec.width) * static_cast<size_t>(spec.height));
  if (!buf.read(0, 0, true, OIIO::TypeDesc::FLOAT) ||
      !buf.get_pixels(OIIO::ROI(0, spec.width, 0, spec.height, 0, 1, 0, 1), OIIO::TypeDesc::FLOAT,
                      first.data()))
    return Result<ImageF>::failure(path + ": cannot read pixels: " + buf.geterror());
  // OIIO converts integers to [0, 1]; undo that to get counts.
  const double counts = is_float ? 1.0 : static_cast<double>(spec.format.basetype == OIIO::TypeDesc::UINT16 ? 65535
                                                               : spec.format.basetype == OIIO::TypeDesc::UINT8 ? 255
                                                               : 1);
  const double scale = is_float ? 1.0 : options.scale * counts;
  ImageF depth(spec.width, spec.height, 1);
  DepthFileSummary s;
  s.min_depth = std::numeric_limits<double>::infinity();
  s.max_depth = 0.0;
  for (size_t i = 0; i < first.size(); ++i) {
    double v = first[i] * scale;
    if (options.baseline_focal > 0.0) v = options.baseline_focal / v;
    if (!(v > 0.0) || !std::isfinite(v)) {
      ++s.holes;
      continue;  // stays 0: no depth
    }
    depth.data[i] = static_cast<float>(v);
    s.min_depth = std::min(s.min_depth, v);
    s.max_depth = std::max(s.max_depth, v);
  }
  if (s.holes == static_cast<long long>(first.size()))
    return Result<ImageF>::failure(path + ": no pixel holds a usable (positive, finite) depth");
  if (summary) *summary = s;
  return Result<ImageF>::success(std::move(depth));
}

}  // namespace artcam
