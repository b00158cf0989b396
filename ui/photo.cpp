#include "ui/photo.h"

#include "ui/image_convert.h"

namespace artcam::ui {

PhotoPtr makePhoto(QString path, LoadedImage loaded) {
  auto photo = std::make_shared<Photo>();
  photo->path = std::move(path);
  photo->full = std::move(loaded);
  photo->preview = boxDownscale(photo->full.image, kPreviewMaxSide);
  photo->display = qimageFromLinear(boxDownscale(photo->full.image, kDisplayMaxSide));
  return photo;
}

}  // namespace artcam::ui
