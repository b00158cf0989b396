// SPDX-License-Identifier: Apache-2.0
// The depth overlay on the canvas: the document's depth (depth_model.h) rasterised at a reduced
// size and coloured by a perceptual ramp in INVERSE depth (near = warm red, far = deep blue;
// inverse depth because that is what the planes are affine in, and it spreads near detail),
// with a legend of the depth range. Pixels without depth stay transparent.
//
// Decisions: the raster is at most kMaxSide pixels on its long side, on the GUI thread (a few
// milliseconds at that size), and recomputed through a leading + trailing throttle (after
// Krita's KisSignalCompressor) so brush strokes stay fluid and the last state always shows.
#pragma once

#include "core/model/image.h"

#include <QColor>
#include <QImage>
#include <QObject>
#include <QTimer>

#include <memory>

namespace artcam::ui {

class Document;

class DepthOverlay : public QObject {
  Q_OBJECT

 public:
  static constexpr int kMaxSide = 512;
  static constexpr int kThrottleMs = 40;

  explicit DepthOverlay(Document* document, QObject* parent = nullptr);

  bool isVisible() const { return visible_; }
  double opacity() const { return opacity_; }
  const QImage& image() const { return image_; }  // ARGB32 premultiplied; null when no depth
  // The raster the image was coloured from (depth_raster.h's 2-channel form, ≤ kMaxSide), for
  // other readers of the painted depth (the effects panel); null when no depth.
  const std::shared_ptr<const ImageF>& raster() const { return raster_; }
  bool hasDepth() const { return max_depth_ > 0.0; }
  double minDepth() const { return min_depth_; }
  double maxDepth() const { return max_depth_; }

  // Colour of depth z for the current range (t = 0 far … 1 near in inverse depth).
  QColor colourFor(double depth) const;
  static QColor ramp(double t);

 public slots:
  void setVisible(bool visible);
  void setOpacity(double opacity);
  // Recomputes now (tests; the throttle calls it too).
  void update();

 signals:
  void changed();

 private:
  void schedule();

  Document* document_;
  QTimer trailing_;
  bool pending_ = false;
  bool visible_ = true;
  double opacity_ = 0.55;
  QImage image_;
  std::shared_ptr<const ImageF> raster_;
  double min_depth_ = 0.0;
  double max_depth_ = 0.0;
};

}  // namespace artcam::ui
