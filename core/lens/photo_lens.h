// SPDX-License-Identifier: Apache-2.0
// The lens camera settings a photo's own EXIF gives (`artcam lens camera --from PHOTO`, `artcam
// batch --lens-from-exif`): the camera, lens and focal length it was shot with, looked up in
// the lensfun database by LensDatabase::lookUp (the lookup the studio's lens dialog makes), and
// the size of the photo's stored raster.
//
// Frames. A lens distorts the sensor's raster, so the camera is made for the raster as stored
// (its width and height before any EXIF turn), as `artcam lens camera --size` takes it.
#pragma once

#include "core/lens/lens_camera.h"
#include "core/lens/lens_database.h"
#include "core/model/status.h"

#include <string>

namespace artcam {

struct PhotoLensChoice {
  std::string path;
  PhotoLensLookup lookup;
  // lens, focal_mm, crop and size from the photo, and aperture and distance_m where its EXIF has
  // them and the caller gave none; the rest the caller's.
  LensCameraOptions options;
  // Photos with equal keys get the same camera: lensfun's camera, the lens, the focal length,
  // the aperture and distance, the crop factor and the raster size (a zoom shoot makes one
  // camera per focal length, and per aperture where vignetting is corrected).
  std::string key() const;
  // "Nikon AF-S Nikkor 50mm f/1.4G at 50 mm, crop 1 (camera Nikon D750)"
  std::string describe() const;
};

// `base` holds the caller's settings (distort, tca, max_error_px; crop > 0 overrides the
// camera's); the photo gives the rest. The crop factor is lensfun's for the EXIF camera, else
// the lens's calibration one. Refusals are one line naming `path` and what is missing: no
// EXIF, no focal length, no lens or camera named, no lens in lensfun for what was searched, or
// (without a lens name) several lenses that fit the camera.
Result<PhotoLensChoice> lensForPhoto(const LensDatabase& database, const std::string& path,
                                     const LensCameraOptions& base = {});

}  // namespace artcam
