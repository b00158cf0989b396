// SPDX-License-Identifier: Apache-2.0
// The bundled photo as linear float, read with OpenImageIO directly so render tests do not
// depend on core/io's decoding.
#pragma once

#include "core/model/image.h"

#include <OpenImageIO/imagebuf.h>

#include <cmath>
#include <string>

namespace artcam::test {

inline float linearFromSrgb(float c) {
  return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

inline ImageF readLinearPhoto(const std::string& path) {
  OIIO::ImageBuf buf(path);
  if (!buf.read(0, 0, true, OIIO::TypeDesc::FLOAT)) return {};
  const OIIO::ImageSpec& spec = buf.spec();
  ImageF image(spec.width, spec.height, spec.nchannels);
  buf.get_pixels(OIIO::ROI::All(), OIIO::TypeDesc::FLOAT, image.data.data());
  for (float& v : image.data) v = linearFromSrgb(v);
  return image;
}

}  // namespace artcam::test
