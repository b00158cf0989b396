// SPDX-License-Identifier: Apache-2.0
// The canonical calibration board in a small widget: its squares, its interior corners (a
// dot per corner, filled when the corner already has a match in the photo) and the selected
// corner, which the next photo click with the grid tool is matched to. Clicking near a corner
// selects it; arrow keys move the selection.
#pragma once

#include <QWidget>

namespace artcam::ui {

class InsertionModel;

class BoardView : public QWidget {
  Q_OBJECT

 public:
  explicit BoardView(InsertionModel* model, QWidget* parent = nullptr);

  QSize sizeHint() const override { return {220, 220}; }
  bool hasHeightForWidth() const override { return true; }
  int heightForWidth(int w) const override;
  // Widget ↔ canonical board pixels for the current size.
  QPointF widgetFromBoard(const QPointF& board) const;
  QPointF boardFromWidget(const QPointF& widget) const;

 protected:
  void paintEvent(QPaintEvent* event) override;
  void mousePressEvent(QMouseEvent* event) override;
  void keyPressEvent(QKeyEvent* event) override;

 private:
  QRectF boardRect() const;

  InsertionModel* model_;
};

}  // namespace artcam::ui
