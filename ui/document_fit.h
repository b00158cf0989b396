// SPDX-License-Identifier: Apache-2.0
// The document's fit, core's fitDocumentGeometry (core/project/document_camera.h), called from
// the GUI thread for discrete edits and from the FitWorker for a drag's mouse moves: a pure
// function of its inputs, so both give bit-identical results. This wrapper counts the fits per
// thread kind so tests and artcam-studio-bench can check where fits ran.
#pragma once

#include "core/project/document_camera.h"

namespace artcam::ui {

using FitInputs = DocumentFitInputs;
using FittedCamera = DocumentFit;

// Any thread; never throws.
FittedCamera fitDocumentCamera(const FitInputs& inputs);

// How many fitDocumentCamera calls ran on the application's (GUI) thread and elsewhere since
// the process started.
struct FitThreadCounts {
  long gui_thread = 0;
  long other_threads = 0;
};
FitThreadCounts fitThreadCounts();

}  // namespace artcam::ui
