// SPDX-License-Identifier: Apache-2.0
// The depth part of the document: painted regions ("depth layers"), each given
// depth at three clicked points (a plane in inverse depth, core/depth/inverse_depth_plane.h),
// and an optional depth map file underneath them all. Owned by Document; changed only through
// the commands of depth_commands.h (which call the mutators below), except a brush stroke in
// progress, which paints live (maskForStroke + maskEdited) and becomes one command on release.
//
// Frames: masks are the photo's size; anchors are photo PIXELS (centres at i + 0.5).
#pragma once

#include "core/depth/depth_raster.h"
#include "core/depth/inverse_depth_plane.h"
#include "core/depth/region_mask.h"
#include "core/io/depth_file.h"
#include "core/model/camera.h"

#include <QObject>
#include <QString>

#include <memory>
#include <optional>
#include <vector>

namespace artcam::ui {

struct DepthPlaneLayer {
  QString name;
  RegionMask mask;
  std::vector<DepthAnchor> anchors;  // up to 3; the plane exists once there are 3
  bool operator==(const DepthPlaneLayer&) const = default;
};

struct DepthMapSource {
  QString path;  // absolute
  DepthFileOptions options;
  std::shared_ptr<const ImageF> map;  // 1-channel depths, 0 = none (depth_file.h)
  bool operator==(const DepthMapSource& o) const {
    return path == o.path && options.scale == o.options.scale &&
           options.inverse == o.options.inverse &&
           options.baseline_focal == o.options.baseline_focal && map == o.map;
  }
};

class DepthModel : public QObject {
  Q_OBJECT

 public:
  static constexpr int kAnchorCount = 3;

  explicit DepthModel(QObject* parent = nullptr);

  // Replaces everything (new photo or project). Layers whose masks are not `frame` are dropped.
  void reset(FrameSize frame, std::vector<DepthPlaneLayer> layers = {},
             std::optional<DepthMapSource> map = std::nullopt);
  FrameSize frame() const { return frame_; }

  const std::vector<DepthPlaneLayer>& layers() const { return layers_; }
  int layerCount() const { return static_cast<int>(layers_.size()); }
  const DepthPlaneLayer& layer(int index) const { return layers_.at(static_cast<size_t>(index)); }
  // A new, empty layer of the photo's size named "Plane N".
  DepthPlaneLayer makeLayer() const;

  // The plane of a layer once it has three good anchors; otherwise the reason it has none.
  const std::optional<InverseDepthPlane>& plane(int index) const;
  QString planeStatus(int index) const;

  const std::optional<DepthMapSource>& map() const { return map_; }
  bool hasDepth() const;  // any layer with a plane and coverage, or a map

  // Everything rasterised: layers over the map (core/depth/depth_raster.h).
  ImageF rasterise(const DepthRasterOptions& options = {}, DepthRasterSummary* summary = nullptr) const;

  // --- view state (not undoable, not saved) ---
  int activeLayer() const { return active_; }  // -1: none
  void setActiveLayer(int index);

  // --- raw mutators for depth_commands.h ---
  void insertLayer(int index, DepthPlaneLayer layer);
  void removeLayer(int index);
  void setAnchors(int index, std::vector<DepthAnchor> anchors);
  void setName(int index, const QString& name);
  void pasteMask(int index, const PixelRect& rect, const std::vector<uint8_t>& bytes);
  void setMap(std::optional<DepthMapSource> map);

  // --- a stroke in progress (see the header comment) ---
  RegionMask* maskForStroke(int index);
  void maskEdited(int index, const PixelRect& rect);

 signals:
  void layersChanged();  // added, removed, renamed, reset
  void depthChanged();   // any depth value may have changed (masks, anchors, map)
  void activeLayerChanged(int index);

 private:
  void updatePlane(size_t index);

  FrameSize frame_;
  std::vector<DepthPlaneLayer> layers_;
  std::vector<std::optional<InverseDepthPlane>> planes_;  // one per layer
  std::vector<QString> plane_status_;
  std::optional<DepthMapSource> map_;
  int active_ = -1;
};

}  // namespace artcam::ui
