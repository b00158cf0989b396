// SPDX-License-Identifier: Apache-2.0
// A strip across the top of the canvas, shown while the document's camera is set by hand
// (tensor edits, presets, an .artcam without matches): "Camera set by hand — pairs not fitted"
// with [Fit again], which pushes SetCameraCommand(nullopt) (one undo step back to the fit).
// While it shows, the canvas draws the pair markers neutral (their residuals measure a camera
// nobody fitted to them, so red markers would accuse good pairs); the banner's tooltip says so.
#pragma once

#include <QFrame>

class QLabel;
class QPushButton;

namespace artcam::ui {

class Document;

class ManualCameraBanner : public QFrame {
  Q_OBJECT

 public:
  // A child of `canvas`, kept across its top edge.
  ManualCameraBanner(Document* document, QWidget* canvas);

  QString text() const;
  QPushButton* fitAgainButton() const { return fit_again_; }

 protected:
  bool eventFilter(QObject* watched, QEvent* event) override;

 private:
  void sync();
  void place();

  Document* document_;
  QLabel* label_;
  QPushButton* fit_again_;
};

}  // namespace artcam::ui
