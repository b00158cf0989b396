// SPDX-License-Identifier: Apache-2.0
// The document's camera as a pure function of its fit inputs (photo frame, pairs, model class,
// hand-made camera, colour block), so it can run on the GUI thread for discrete edits and in
// the FitWorker for a drag's mouse moves and give bit-identical results either way. Counts the
// fits per thread kind so tests and artcam-studio-bench can check where fits ran.
#pragma once

#include "core/fit/fit_image.h"
#include "core/model/camera.h"

#include <Eigen/Core>

#include <optional>
#include <vector>

namespace artcam::ui {

struct Pair;

struct FitInputs {
  FrameSize frame;                  // the photo's pixels; not an image frame: no photo yet
  std::vector<PointMatch> matches;  // every pair, with its enabled flag
  ModelClass model = ModelClass::Auto;
  std::optional<Camera> manual_camera;
  std::optional<Camera> colour_block;
};

struct FittedCamera {
  FitSummary fit;
  Camera camera;
  std::vector<double> residual_by_pair;  // target px per pair; negative: unknown
};

// Any thread; never throws (an engine exception becomes a failed fit and the identity camera).
FittedCamera fitDocumentCamera(const FitInputs& inputs);

// Cameras need image frames; before a photo is open a 1×1 placeholder keeps them valid.
Camera identityImageCamera(FrameSize frame);

// Enabled pairs still missing before `model` is determined (0 when enough).
int pairsNeededFor(ModelClass model, int enabled_pairs);

// How many fitDocumentCamera calls ran on the application's (GUI) thread and elsewhere since
// the process started.
struct FitThreadCounts {
  long gui_thread = 0;
  long other_threads = 0;
};
FitThreadCounts fitThreadCounts();

}  // namespace artcam::ui
