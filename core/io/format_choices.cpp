// SPDX-License-Identifier: Apache-2.0
#include "core/io/format_choices.h"

#include "core/io/photo_metadata.h"

#include <algorithm>

namespace artcam::io_format {

void setFormatChoices(OIIO::ImageSpec& spec, const std::string& format,
                      const WriteImageOptions& options, const ImageInfo* like,
                      const OIIO::ImageSpec* like_spec) {
  spec.attribute("Software", writingSoftware());
  if (format == "jpeg") {
    const int quality = jpegQualityFor(options, like);
    spec.attribute("CompressionQuality", quality);
    spec.attribute("Compression", "jpeg:" + std::to_string(quality));
    spec.attribute("jpeg:subsampling", jpegSubsamplingFor(options, like));
  } else if (format == "png") {
    if (options.jpeg_quality)
      spec.attribute("png:compressionLevel", std::clamp(*options.jpeg_quality / 10, 0, 9));
  } else if (format == "dpx") {
    const int bits = like_spec && like && like->format_name == "dpx"
                         ? like_spec->get_int_attribute("oiio:BitsPerSample", 0)
                         : 0;
    if (spec.format == OIIO::TypeDesc::UINT16 && options.pixel_type.empty() &&
        (bits == 10 || bits == 12))
      spec.attribute("oiio:BitsPerSample", bits);
  }
}

}  // namespace artcam::io_format
