// SPDX-License-Identifier: Apache-2.0
// The 3D view of a point cloud: orbit by dragging (left button: yaw and
// pitch about the cloud's centre), zoom by the wheel (distance to the centre), a 3D effect of
// the paper's Fig 1 chosen from a list (the rows of core's 3D effects table at their defaults,
// built in the object frame of the cloud's bounds: effects_3d_table.h), and the document's
// current image camera applied live to the view as a lens (so moving a pair re-renders the
// cloud too). Renders in a CloudRenderWorker like the image preview: coarse first, newest
// request wins.
//
// Frames: the orbit looks at the cloud's bounding-box centre from
//   eye = centre + distance · (cos p · sin y, sin p, −cos p · cos y)
// in the cloud's world with y up (CameraPose::lookAt's default up), so yaw y = 0, pitch p = 0
// looks along +z; the default view is defaultViewPose's direction
// (4, 3, −5) with y up, i.e. yaw atan2(4, 5) and pitch asin(3/√50), at 2.8 bounding radii. The
// focal is chosen once per cloud so the default view frames it (framingPinhole) and stays fixed,
// so the wheel's distance change shows as zoom.
#pragma once

#include "core/cloud/cloud_render.h"
#include "core/cloud/point_cloud.h"
#include "core/effects/effects_3d_table.h"
#include "core/model/status.h"
#include "ui/cloud_render_worker.h"

#include <QImage>
#include <QString>
#include <QWidget>

#include <memory>
#include <string>

class QComboBox;

namespace artcam::ui {

class Document;

struct LoadedCloud {
  QString path;
  std::shared_ptr<const PointCloud> cloud;
  CloudBounds bounds;
  double point_spacing = 0.0;
  double focal = 2.0;  // for a square view at the default distance
};

class CloudView : public QWidget {
  Q_OBJECT

 public:
  static constexpr double kDefaultDistance = 2.8;  // bounding radii
  static constexpr double kRadiansPerPixel = 0.01;
  static constexpr double kMaxPitch = 1.5;
  static constexpr int kMaxRenderSide = 1024;

  // Reads a PLY and prepares it for viewing; pure, runs on a worker thread (Session).
  static Result<LoadedCloud> load(const QString& path);

  explicit CloudView(Document* document, QWidget* parent = nullptr);
  ~CloudView() override;

  void setCloud(LoadedCloud cloud);
  bool hasCloud() const { return cloud_.cloud != nullptr; }
  const LoadedCloud& cloud() const { return cloud_; }

  double yaw() const { return yaw_; }
  double pitch() const { return pitch_; }
  double distance() const { return distance_; }  // object units
  void setOrbit(double yaw, double pitch, double distance);

  // The 3D effect shown: a row of core's 3D effects table by name, "" for none (so is a name
  // the table does not have).
  const std::string& effect() const { return effect_; }
  void setEffect(const std::string& name);
  // What the view builds the effect with: the table's defaults, a viewer row's eye and at put
  // at the orbit's eye and the cloud's centre; in effectFrame(), the cloud's bounds (centre and
  // bounding radius; radius 1 for a cloud of one point).
  EffectValues effectValues() const;
  ObjectFrame effectFrame() const;

  // The request the current state makes (tests render it directly to compare).
  CloudRenderRequest currentRequest() const;
  QSize renderSize() const;

  const QImage& image() const { return image_; }
  quint64 imageGeneration() const { return image_generation_; }
  bool imageIsFinal() const { return image_final_; }
  quint64 requestedGeneration() const { return generation_; }
  CloudRenderWorker* worker() { return &worker_; }

 public slots:
  void schedule();
  void resetView();

 signals:
  void viewChanged();
  void renderFailed(const QString& message);

 protected:
  void paintEvent(QPaintEvent* event) override;
  void resizeEvent(QResizeEvent* event) override;
  void mousePressEvent(QMouseEvent* event) override;
  void mouseMoveEvent(QMouseEvent* event) override;
  void mouseReleaseEvent(QMouseEvent* event) override;
  void wheelEvent(QWheelEvent* event) override;

 private:
  void onRendered(const QImage& image, quint64 generation, bool final_pass, double ms);
  Eigen::Vector3d orbitEye() const;

  Document* document_;
  QComboBox* effect_box_;
  CloudRenderWorker worker_;
  LoadedCloud cloud_;
  double yaw_ = 0.0;
  double pitch_ = 0.0;
  double distance_ = 1.0;
  std::string effect_;
  bool dragging_ = false;
  QPoint drag_last_;
  quint64 generation_ = 0;
  QImage image_;
  quint64 image_generation_ = 0;
  bool image_final_ = false;
  double last_ms_ = 0.0;
};

}  // namespace artcam::ui
