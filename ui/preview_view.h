// SPDX-License-Identifier: Apache-2.0
// Shows the warped preview next to the photo: side by side, overlaid with adjustable opacity,
// or split by a slider (photo left of it, warped right). Reads images only from the document
// (photo) and the PreviewController (warped); never renders itself.
#pragma once

#include "ui/scaled_image_cache.h"

#include <QWidget>

class QComboBox;
class QSlider;

namespace artcam::ui {

class Document;
class PreviewController;

enum class PreviewMode { SideBySide = 0, Overlay = 1, Split = 2, WarpedOnly = 3 };

class PreviewArea : public QWidget {
  Q_OBJECT

 public:
  PreviewArea(Document* document, PreviewController* controller, QWidget* parent = nullptr);

  PreviewMode mode() const { return mode_; }
  double opacity() const { return opacity_; }
  double split() const { return split_; }

 public slots:
  void setMode(PreviewMode mode);
  void setOpacity(double opacity);  // overlay: weight of the warped image, [0, 1]
  void setSplit(double split);      // split: position of the divider, [0, 1]

 protected:
  void paintEvent(QPaintEvent* event) override;

 private:
  Document* document_;
  PreviewController* controller_;
  ScaledImageCache source_cache_;  // the photo's display copy at the drawn size
  PreviewMode mode_ = PreviewMode::SideBySide;
  double opacity_ = 0.5;
  double split_ = 0.5;
};

class PreviewView : public QWidget {
  Q_OBJECT

 public:
  PreviewView(Document* document, PreviewController* controller, QWidget* parent = nullptr);
  PreviewArea* area() const { return area_; }
  void setMode(PreviewMode mode);
  void setOpacity(double opacity);

 private:
  void updateSliderRole();

  PreviewArea* area_;
  QComboBox* mode_box_;
  QSlider* slider_;
};

}  // namespace artcam::ui
