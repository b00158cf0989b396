// SPDX-License-Identifier: Apache-2.0
// Status bar contents: model in use, RMS / max residual, preview render time, load progress.
// Listens to the document and the preview controller; MainWindow just places it.
#pragma once

#include <QWidget>

class QLabel;
class QPointF;
class QProgressBar;

namespace artcam::ui {

class Document;
class PreviewController;

class FitStatus : public QWidget {
  Q_OBJECT

 public:
  FitStatus(Document* document, PreviewController* preview, QWidget* parent = nullptr);

  QString modelText() const;
  QString residualText() const;
  QString renderText() const;
  QString cursorText() const;
  bool isLoadProgressShown() const;  // the "Loading n%" bar

 public slots:
  void setLoadProgress(int percent);  // -1 hides the bar
  void setCursorPosition(const QPointF& image_point);

 private:
  void updateFit();
  void updateRender();

  Document* document_;
  PreviewController* preview_;
  QLabel* cursor_ = nullptr;
  QLabel* model_;
  QLabel* residual_;
  QLabel* render_;
  QProgressBar* progress_;
};

}  // namespace artcam::ui
