// SPDX-License-Identifier: Apache-2.0
// The depth tool's settings, shared by the tool on the canvas and the depth panel's controls
// (view state: neither undoable nor saved). Radius is in photo pixels.
#pragma once

#include <QObject>

#include <algorithm>

namespace artcam::ui {

enum class DepthToolMode { Brush, Eraser, Polygon, Points };

class DepthToolSettings : public QObject {
  Q_OBJECT

 public:
  static constexpr double kMinRadius = 0.5;
  static constexpr double kMaxRadius = 2000.0;

  explicit DepthToolSettings(QObject* parent = nullptr) : QObject(parent) {}

  double radius() const { return radius_; }
  double hardness() const { return hardness_; }
  double nextDepth() const { return next_depth_; }  // given to a newly placed depth point
  // Edge-aware brush (core/depth/edge_aware_brush.h): a dab floods only the pixels of its
  // disc connected to the stroke's first pixel through colours within the tolerance of it.
  bool edgeAware() const { return edge_aware_; }
  double edgeTolerance() const { return edge_tolerance_; }  // linear RGB distance

 public slots:
  void setRadius(double r) {
    r = std::clamp(r, kMinRadius, kMaxRadius);
    if (r == radius_) return;
    radius_ = r;
    emit changed();
  }
  void setHardness(double h) {
    h = std::clamp(h, 0.0, 1.0);
    if (h == hardness_) return;
    hardness_ = h;
    emit changed();
  }
  void setEdgeAware(bool on) {
    if (on == edge_aware_) return;
    edge_aware_ = on;
    emit changed();
  }
  void setEdgeTolerance(double t) {
    t = std::clamp(t, 0.0, 2.0);
    if (t == edge_tolerance_) return;
    edge_tolerance_ = t;
    emit changed();
  }
  void setNextDepth(double d) {
    if (!(d > 0.0) || d == next_depth_) return;
    next_depth_ = d;
    emit changed();
  }

 signals:
  void changed();

 private:
  double radius_ = 25.0;
  double hardness_ = 0.7;
  double next_depth_ = 10.0;
  bool edge_aware_ = false;
  double edge_tolerance_ = 0.12;
};

}  // namespace artcam::ui
