// SPDX-License-Identifier: Apache-2.0
#include "ui/depth_model.h"

#include <QCoreApplication>

#include <algorithm>
#include <array>

namespace artcam::ui {

DepthModel::DepthModel(QObject* parent) : QObject(parent) {}

void DepthModel::reset(FrameSize frame, std::vector<DepthPlaneLayer> layers,
                       std::optional<DepthMapSource> map) {
  frame_ = frame;
  std::erase_if(layers, [&](const DepthPlaneLayer& l) {
    return l.mask.width() != frame.width || l.mask.height() != frame.height;
  });
  layers_ = std::move(layers);
  planes_.assign(layers_.size(), std::nullopt);
  plane_status_.assign(layers_.size(), QString());
  for (size_t i = 0; i < layers_.size(); ++i) updatePlane(i);
  map_ = std::move(map);
  active_ = layers_.empty() ? -1 : 0;
  emit layersChanged();
  emit activeLayerChanged(active_);
  emit depthChanged();
}

DepthPlaneLayer DepthModel::makeLayer() const {
  DepthPlaneLayer l;
  int n = layerCount() + 1;
  auto taken = [&](const QString& name) {
    return std::any_of(layers_.begin(), layers_.end(),
                       [&](const DepthPlaneLayer& o) { return o.name == name; });
  };
  while (taken(QCoreApplication::translate("DepthModel", "Plane %1").arg(n))) ++n;
  l.name = QCoreApplication::translate("DepthModel", "Plane %1").arg(n);
  l.mask = RegionMask(frame_.width, frame_.height);
  return l;
}

const std::optional<InverseDepthPlane>& DepthModel::plane(int index) const {
  return planes_.at(static_cast<size_t>(index));
}

QString DepthModel::planeStatus(int index) const {
  return plane_status_.at(static_cast<size_t>(index));
}

bool DepthModel::hasDepth() const {
  if (map_) return true;
  for (size_t i = 0; i < layers_.size(); ++i)
    if (planes_[i] && layers_[i].mask.coveredCount() > 0) return true;
  return false;
}

ImageF DepthModel::rasterise(const DepthRasterOptions& options, DepthRasterSummary* summary) const {
  if (!frame_.isImage()) return {};
  std::vector<DepthLayer> layers;
  for (size_t i = 0; i < layers_.size(); ++i) layers.push_back({&layers_[i].mask, planes_[i]});
  return rasteriseDepth(layers, frame_.width, frame_.height, map_ ? map_->map.get() : nullptr,
                        options, summary);
}

void DepthModel::setActiveLayer(int index) {
  if (index < -1 || index >= layerCount()) index = layers_.empty() ? -1 : 0;
  if (index == active_) return;
  active_ = index;
  emit activeLayerChanged(active_);
}

void DepthModel::insertLayer(int index, DepthPlaneLayer layer) {
  index = std::clamp(index, 0, layerCount());
  layers_.insert(layers_.begin() + index, std::move(layer));
  planes_.insert(planes_.begin() + index, std::nullopt);
  plane_status_.insert(plane_status_.begin() + index, QString());
  updatePlane(static_cast<size_t>(index));
  active_ = index;
  emit layersChanged();
  emit activeLayerChanged(active_);
  emit depthChanged();
}

void DepthModel::removeLayer(int index) {
  if (index < 0 || index >= layerCount()) return;
  layers_.erase(layers_.begin() + index);
  planes_.erase(planes_.begin() + index);
  plane_status_.erase(plane_status_.begin() + index);
  active_ = std::min(active_, layerCount() - 1);
  emit layersChanged();
  emit activeLayerChanged(active_);
  emit depthChanged();
}

void DepthModel::setAnchors(int index, std::vector<DepthAnchor> anchors) {
  if (index < 0 || index >= layerCount()) return;
  anchors.resize(std::min<size_t>(anchors.size(), kAnchorCount));
  layers_[static_cast<size_t>(index)].anchors = std::move(anchors);
  updatePlane(static_cast<size_t>(index));
  emit layersChanged();  // the status line changed
  emit depthChanged();
}

void DepthModel::setName(int index, const QString& name) {
  if (index < 0 || index >= layerCount()) return;
  layers_[static_cast<size_t>(index)].name = name;
  emit layersChanged();
}

void DepthModel::pasteMask(int index, const PixelRect& rect, const std::vector<uint8_t>& bytes) {
  if (index < 0 || index >= layerCount() || rect.empty()) return;
  layers_[static_cast<size_t>(index)].mask.pasteRect(rect, bytes);
  emit depthChanged();
}

void DepthModel::setMap(std::optional<DepthMapSource> map) {
  map_ = std::move(map);
  emit layersChanged();
  emit depthChanged();
}

RegionMask* DepthModel::maskForStroke(int index) {
  if (index < 0 || index >= layerCount()) return nullptr;
  return &layers_[static_cast<size_t>(index)].mask;
}

void DepthModel::maskEdited(int index, const PixelRect& rect) {
  if (index < 0 || index >= layerCount() || rect.empty()) return;
  emit depthChanged();
}

void DepthModel::updatePlane(size_t index) {
  const DepthPlaneLayer& l = layers_[index];
  planes_[index].reset();
  if (l.anchors.size() < kAnchorCount) {
    const int need = kAnchorCount - static_cast<int>(l.anchors.size());
    plane_status_[index] =
        QCoreApplication::translate("DepthModel", "Click %n more depth point(s) in the region.",
                                    nullptr, need);
    return;
  }
  const std::array<DepthAnchor, 3> three{l.anchors[0], l.anchors[1], l.anchors[2]};
  const Result<InverseDepthPlane> p = planeFromAnchors(three);
  if (!p) {
    plane_status_[index] = QString::fromStdString(p.status.message);
    return;
  }
  planes_[index] = *p;
  plane_status_[index] = QCoreApplication::translate("DepthModel", "Plane set from 3 points.");
}

}  // namespace artcam::ui
