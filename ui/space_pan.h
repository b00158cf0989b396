// SPDX-License-Identifier: Apache-2.0
// Space pans wherever the pointer is: an application-wide event filter that, while the pointer
// is over the canvas, takes Space from whichever widget has the focus (the pairs table would
// toggle a pair with it) and holds the canvas's Space-pan; the release is taken too while the
// canvas pans, wherever the pointer has gone by then. Space over any other widget keeps its
// usual meaning there, and so does Space typed into a text or number field.
#pragma once

#include <QObject>

namespace artcam::ui {

class Canvas;

class SpacePanFilter : public QObject {
  Q_OBJECT

 public:
  // Installs itself on the application; removed with `canvas`.
  explicit SpacePanFilter(Canvas* canvas);

 protected:
  bool eventFilter(QObject* watched, QEvent* event) override;

 private:
  Canvas* canvas_;
};

}  // namespace artcam::ui
