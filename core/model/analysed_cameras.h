// SPDX-License-Identifier: Apache-2.0
// Several cameras validated and analysed together (analyseStructure), for the renderers'
// overloads that take plain cameras and hand AnalysedCamera values on: one analysis each.
#pragma once

#include "core/model/camera.h"
#include "core/model/structure.h"

#include <vector>

namespace artcam {

// The camera's structure, after Camera::validate (which throws std::invalid_argument): the
// analysis reads the tensors by the block layout, so it must not see an invalid camera.
CameraStructure validatedStructure(const Camera& camera);

class AnalysedCameras {
 public:
  // Throws std::invalid_argument as Camera::validate does.
  explicit AnalysedCameras(const std::vector<Camera>& cameras);
  // The views borrow this object's analyses: it is neither copied nor moved.
  AnalysedCameras(const AnalysedCameras&) = delete;
  AnalysedCameras& operator=(const AnalysedCameras&) = delete;

  const std::vector<AnalysedCamera>& cameras() const { return analysed_; }

 private:
  std::vector<CameraStructure> structures_;
  std::vector<AnalysedCamera> analysed_;
};

}  // namespace artcam
