// SPDX-License-Identifier: Apache-2.0
#include "ui/result_inverse.h"

#include "core/model/artcam.h"
#include "core/model/structure.h"
#include "core/render/position_map.h"

#include <QCoreApplication>

#include <cmath>
#include <exception>
#include <limits>

namespace artcam::ui {
namespace {

QString tr(const char* text) { return QCoreApplication::translate("ResultInverse", text); }

// What to do instead, in the GUI's terms: the photo itself is one key away.
QString orOnThePhoto() {
  return tr("click where the result shows the photo, or press \\ to work on the photo");
}

}  // namespace

ResultInverse::ResultInverse(const Artcam& camera, FrameSize photo_px) : photo_px_(photo_px) {
  if (camera.layers.empty()) {
    refusal_ = tr("No camera to map the result back through: press \\ to work on the photo");
    return;
  }
  if (camera.isPiecewise()) {
    refusal_ =
        tr("A piecewise camera's result is not mapped back point by point: press \\ to "
           "work on the photo");
    return;
  }
  const Camera& main = camera.main();
  try {
    if (analyseStructure(main).geometry_depends_on_attributes) {
      refusal_ =
          tr("Where this camera moves a pixel depends on its colour or depth, so the "
             "result is not mapped back: press \\ to work on the photo");
      return;
    }
    inverse_.emplace(main, photo_px, photo_px);
    camera_ = main;
  } catch (const std::exception&) {
    // No 2D position block, or a map undefined all around the photo's centre: nothing of the
    // photo reaches the result to map back to (a click says so; never a crash).
    inverse_.reset();
    refusal_ =
        tr("This camera maps nothing of the photo to the result: press \\ to work on the "
           "photo");
  }
}

PhotoPoint ResultInverse::photoPixelOf(const Eigen::Vector2d& result_px,
                                       const std::optional<Eigen::Vector2d>& start) const {
  if (!inverse_) return {std::nullopt, refusal_};
  const std::optional<Eigen::Vector2d> s = inverse_->sourceOf(result_px, start);
  if (!s)
    return {std::nullopt,
            tr("No photo pixel shows here (beyond the camera's pole or fold): ") + orOnThePhoto()};
  if (!(s->x() >= 0.0 && s->y() >= 0.0 && s->x() <= photo_px_.width && s->y() <= photo_px_.height))
    return {std::nullopt,
            tr("This point of the result comes from outside the photo: ") + orOnThePhoto()};
  return {s, QString()};
}

std::optional<Eigen::Vector2d> ResultInverse::resultPixelOf(const Eigen::Vector2d& photo_px) const {
  if (!inverse_) return std::nullopt;
  return inverse_->targetOf(photo_px);
}

const std::vector<Eigen::Vector2f>& ResultInverse::photoPixelsOfGrid(FrameSize grid) const {
  if (grid.width == grid_px_.width && grid.height == grid_px_.height) return grid_;
  grid_px_ = grid;
  grid_.assign(static_cast<size_t>(grid.width) * static_cast<size_t>(grid.height),
               Eigen::Vector2f::Constant(std::numeric_limits<float>::quiet_NaN()));
  if (!inverse_ || grid.width < 1 || grid.height < 1) return grid_;
  // The warp's own inverse map (position_map.h) at the grid's size: the camera is normalised, so
  // the same positions as the full result's, sampled coarser.
  try {
    const PositionMap map = sourcePositionMap(camera_, photo_px_, grid);
    for (size_t k = 0; k < grid_.size(); ++k)
      if (map.preimage[k] != Preimage::None) grid_[k] = {map.x_px[k], map.y_px[k]};
  } catch (const std::invalid_argument&) {
    // Refused by the warp too: the result shows nothing to tint.
  }
  return grid_;
}

}  // namespace artcam::ui
