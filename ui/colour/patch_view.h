// SPDX-License-Identifier: Apache-2.0
// A photo shown whole (fitted into the widget, aspect kept) with the colour samples' patches
// drawn as squares; the colour dock has one for the source photo and one for the reference.
// It owns its widget ↔ photo-pixel transform and forwards presses, drags and releases as
// signals in photo PIXELS (centres at i + 0.5); what they mean is the dock's business.
#pragma once

#include "core/model/camera.h"

#include <QImage>
#include <QString>
#include <QWidget>

#include <Eigen/Core>

#include <optional>
#include <vector>

namespace artcam::ui {

struct PatchMark {
  Eigen::Vector2d centre{0.0, 0.0};  // photo pixels
  int number = 0;                    // shown beside the square (1-based sample number)
  bool selected = false;
  bool enabled = true;
  bool pending = false;  // half of a pair still waiting for its other patch
};

class PatchView : public QWidget {
  Q_OBJECT

 public:
  explicit PatchView(QString placeholder, QWidget* parent = nullptr);

  // `display` is any downscaled copy of a photo of `photo_px` pixels (8-bit sRGB).
  void setPhoto(QImage display, FrameSize photo_px);
  void setMarks(std::vector<PatchMark> marks, int radius);
  bool hasPhoto() const { return photo_px_.isImage() && !display_.isNull(); }

  QPointF widgetFromPhoto(const Eigen::Vector2d& photo) const;
  Eigen::Vector2d photoFromWidget(const QPointF& widget) const;
  // The mark under a widget point (its square grown to at least 6 widget px), or -1.
  int markAt(const QPointF& widget) const;

  QSize sizeHint() const override { return {240, 180}; }

 signals:
  void pressedEmpty(const Eigen::Vector2d& photo_px);
  void pressedMark(int index);
  void draggedTo(const Eigen::Vector2d& photo_px);
  void released();

 protected:
  void paintEvent(QPaintEvent* event) override;
  void mousePressEvent(QMouseEvent* event) override;
  void mouseMoveEvent(QMouseEvent* event) override;
  void mouseReleaseEvent(QMouseEvent* event) override;

 private:
  QRectF imageRect() const;  // where the photo is drawn, widget px
  double scale() const;      // widget px per photo px

  QString placeholder_;
  QImage display_;
  FrameSize photo_px_;
  std::vector<PatchMark> marks_;
  int radius_ = 0;
  bool dragging_ = false;
};

}  // namespace artcam::ui
