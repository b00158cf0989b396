// SPDX-License-Identifier: Apache-2.0
#include "core/model/analysed_cameras.h"

namespace artcam {

CameraStructure validatedStructure(const Camera& camera) {
  camera.validate();
  return analyseStructure(camera);
}

AnalysedCameras::AnalysedCameras(const std::vector<Camera>& cameras) {
  structures_.reserve(cameras.size());  // no reallocation: analysed_ points into it
  for (const Camera& camera : cameras) structures_.push_back(validatedStructure(camera));
  analysed_.reserve(cameras.size());
  for (size_t k = 0; k < cameras.size(); ++k) analysed_.push_back({cameras[k], structures_[k]});
}

}  // namespace artcam
