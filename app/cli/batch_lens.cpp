// SPDX-License-Identifier: Apache-2.0
#include "app/cli/batch_lens.h"

#include "app/cli/commands.h"
#include "core/lens/lens_camera.h"
#include "core/pipeline/render.h"

namespace artcam::cli {

BatchLensCameras::BatchLensCameras() {
  auto db = LensDatabase::load();
  if (!db) throw CommandError(db.status.message);
  database_ = *db.value;
}

BatchLensFrame BatchLensCameras::forPhoto(const std::string& path) {
  // The defaults of `artcam lens camera --from`, so a frame's output equals that camera warped.
  Result<PhotoLensChoice> chosen = lensForPhoto(*database_, path);
  if (!chosen) throw CommandError(chosen.status.message);
  BatchLensFrame frame{nullptr, std::move(*chosen.value), 0};
  const std::string key = frame.choice.key();
  if (const auto at = cameras_.find(key); at != cameras_.end()) {
    frame.camera_number = at->second.first;
    frame.camera = at->second.second;
    return frame;
  }
  LensCameraSummary summary = lensCamera(*database_, frame.choice.options);
  if (!summary.status)
    throw CommandError(path + ": " + frame.choice.describe() + ": " + summary.status.message);
  auto camera = std::make_shared<WarpCameraFile>();
  camera->path = "the lens camera of " + frame.choice.describe();
  camera->camera = std::move(summary.camera);
  camera->linear = needsLinearPhoto(camera->camera);
  frame.camera_number = made() + 1;
  frame.camera = camera;
  cameras_.emplace(key, std::pair{frame.camera_number, frame.camera});
  return frame;
}

}  // namespace artcam::cli
