// SPDX-License-Identifier: Apache-2.0
#include "core/pipeline/point_map.h"

#include "core/model/structure.h"
#include "core/render/attributed.h"

namespace artcam {

Result<PointMapper> PointMapper::of(const Artcam& camera, const std::string& name) {
  const Camera& main = camera.main();
  const int position = main.layout().find(BlockKind::Position);
  if (position < 0 || main.blocks()[static_cast<size_t>(position)].size != 3 ||
      !main.sourceSize().isImage())
    return Result<PointMapper>::failure(
        name + ": map needs an image camera (this one is 3D or has no position)");
  PointMapper mapper;
  for (size_t l = 0; l < camera.layers.size(); ++l) {
    const Camera& layer = camera.layers[l];
    if (analyseStructure(layer).geometry_depends_on_attributes)
      return Result<PointMapper>::failure(
          name + ": " + (camera.layers.size() > 1 ? "layer " + std::to_string(l + 1) + ": " : "") +
          "its positions depend on colour or depth, so where a point goes depends on the photo; "
          "map cannot say (warp renders it)");
    mapper.geometry_.push_back(layer.blocks().size() == 1 ? layer : positionPart(layer));
  }
  mapper.pieces_ = camera.pieces;
  return Result<PointMapper>::success(std::move(mapper));
}

std::optional<Eigen::Vector2d> PointMapper::map(size_t layer,
                                                const Eigen::Vector2d& source_px) const {
  return pieces_ ? pieces_->targetPixelFromSourcePixel(source_px)
                 : targetPixelFromSourcePixel(geometry_.at(layer), source_px);
}

}  // namespace artcam
