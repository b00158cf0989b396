// SPDX-License-Identifier: Apache-2.0
#include "core/lens/photo_lens.h"

#include "core/io/photo_metadata.h"
#include "core/io/stored_image.h"

#include <cstdio>

namespace artcam {

namespace {

std::string number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}

}  // namespace

std::string PhotoLensChoice::key() const {
  return lookup.camera + "\n" + options.lens + "\n" + number(options.focal_mm) + "\n" +
         number(options.aperture) + "\n" + number(options.distance_m) + "\n" +
         number(options.crop) + "\n" + std::to_string(options.size.width) + "x" +
         std::to_string(options.size.height);
}

std::string PhotoLensChoice::describe() const {
  std::string out = options.lens + " at " + number(options.focal_mm) + " mm";
  if (options.aperture > 0) out += " f/" + number(options.aperture);
  if (options.crop > 0) out += ", crop " + number(options.crop);
  if (!lookup.camera.empty()) out += " (camera " + lookup.camera + ")";
  return out;
}

Result<PhotoLensChoice> lensForPhoto(const LensDatabase& database, const std::string& path,
                                     const LensCameraOptions& base) {
  using R = Result<PhotoLensChoice>;
  const Result<StoredShape> shape = readStoredShape(path);
  if (!shape) return R::failure(shape.status.message);
  const auto metadata = readPhotoMetadata(path);
  if (!metadata)
    return R::failure(path +
                      ": no EXIF to take the lens from (name it with --lens NAME --focal MM)");
  PhotoLensChoice choice;
  choice.path = path;
  const LensHint hint = photoLensTags(*metadata);
  if (hint.lens_model.empty() && hint.camera_model.empty())
    return R::failure(path +
                      ": its EXIF names no lens (Exif.Photo.LensModel) and no camera "
                      "(Exif.Image.Model)");
  if (!(hint.focal_mm > 0))
    return R::failure(path + ": its EXIF has no focal length (Exif.Photo.FocalLength)");
  choice.lookup = database.lookUp(hint);
  const PhotoLensLookup& found = choice.lookup;
  if (found.lenses.empty())
    return R::failure(path + ": no lens in the lensfun database matches " + found.searched());
  if (found.lens_match == "the camera's lenses" && found.lenses.size() != 1)
    // Without a lens name lensfun knows, only a camera with one lens (a compact's) decides it.
    return R::failure(path + ": its EXIF names no lens lensfun knows (" + found.searched() +
                      "), and " + std::to_string(found.lenses.size()) +
                      " lenses fit that camera (name one with --lens NAME)");
  choice.options = base;
  choice.options.lens = found.lenses.front().model;
  choice.options.focal_mm = hint.focal_mm;
  // The caller's aperture and distance win; the EXIF's fill in (vignetting needs them).
  if (!(base.aperture > 0)) choice.options.aperture = hint.aperture;
  if (hint.distance_m > 0 && base.distance_m == LensCameraOptions{}.distance_m)
    choice.options.distance_m = hint.distance_m;
  if (!(base.crop > 0)) choice.options.crop = found.camera_crop;
  choice.options.size = FrameSize{shape->width, shape->height};
  return R::success(std::move(choice));
}

}  // namespace artcam
