// SPDX-License-Identifier: Apache-2.0
#include "tests/support/exr_files.h"

#include <OpenImageIO/imageio.h>

namespace artcam::test {

bool writeFloatExr(const std::string& path, int w, int h, const std::vector<std::string>& names,
                   int alpha, int x0, int y0, const std::function<float(int, int, int)>& value) {
  const int channels = static_cast<int>(names.size());
  OIIO::ImageSpec spec(w, h, channels, OIIO::TypeDesc::FLOAT);
  spec.channelnames = names;
  spec.alpha_channel = alpha;
  spec.x = spec.full_x = x0;
  spec.y = spec.full_y = y0;
  std::vector<float> pixels;
  pixels.reserve(static_cast<size_t>(w) * static_cast<size_t>(h) * static_cast<size_t>(channels));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < channels; ++c) pixels.push_back(value(c, x, y));
  auto out = OIIO::ImageOutput::create(path);
  return out && out->open(path, spec) && out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()) &&
         out->close();
}

}  // namespace artcam::test
