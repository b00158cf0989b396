// SPDX-License-Identifier: Apache-2.0
#include "ui/photo.h"

#include "ui/image_convert.h"

#include <algorithm>
#include <cmath>

namespace artcam::ui {

PhotoPtr makePhoto(QString path, LoadedImage loaded) {
  auto photo = std::make_shared<Photo>();
  photo->path = std::move(path);
  photo->full = std::move(loaded);
  photo->preview = boxDownscale(photo->full.image, kPreviewMaxSide);
  photo->display = qimageFromLinear(boxDownscale(photo->full.image, kDisplayMaxSide));
  if (!photo->display.isNull()) {
    photo->pyramid_base = photo->display.convertToFormat(QImage::Format_RGBA8888_Premultiplied);
    const QImage& base = photo->pyramid_base;
    ConstImageView view = packedView<const void>(base.constBits(), base.width(), base.height(), 4,
                                                 PixelType::UInt8, /*alpha_channel=*/3);
    view.row_bytes = base.bytesPerLine();
    photo->pyramid = std::make_shared<const StoredMipPyramid>(view);
  }
  return photo;
}

FrameSize livePreviewSize(const Photo& photo) {
  const FrameSize full = photo.size();
  const double scale = std::min({1.0, static_cast<double>(kLivePreviewMaxWidth) / full.width,
                                 static_cast<double>(kLivePreviewMaxHeight) / full.height});
  if (scale >= 1.0) return full;
  return {std::max(1, static_cast<int>(std::lround(full.width * scale))),
          std::max(1, static_cast<int>(std::lround(full.height * scale)))};
}

}  // namespace artcam::ui
