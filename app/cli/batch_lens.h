// SPDX-License-Identifier: Apache-2.0
// artcam batch --lens-from-exif: each photo's lens camera, made from its own EXIF
// (core/lens/photo_lens.h) and kept for every later photo with the same key (lensfun camera,
// lens, focal length, crop factor, raster size), so a zoom shoot makes one camera per focal
// length. Used from batch's decoding thread only.
#pragma once

#include "app/cli/warp_job.h"
#include "core/lens/lens_database.h"
#include "core/lens/photo_lens.h"

#include <map>
#include <memory>
#include <string>

namespace artcam::cli {

struct BatchLensFrame {
  std::shared_ptr<const WarpCameraFile> camera;
  PhotoLensChoice choice;
  int camera_number = 0;  // 1, 2, … in the order the cameras were made
};

class BatchLensCameras {
 public:
  // Loads the lensfun database; throws CommandError when it cannot be read.
  BatchLensCameras();
  // Throws CommandError naming `path` when its EXIF gives no lens camera.
  BatchLensFrame forPhoto(const std::string& path);
  int made() const { return static_cast<int>(cameras_.size()); }

 private:
  std::shared_ptr<const LensDatabase> database_;
  std::map<std::string, std::pair<int, std::shared_ptr<const WarpCameraFile>>> cameras_;
};

}  // namespace artcam::cli
