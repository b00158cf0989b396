// SPDX-License-Identifier: Apache-2.0
// A canvas tool (after Krita's KoToolBase): the canvas owns no editing logic, it only
// forwards pointer and key events here. Positions arrive in widget coordinates; tools convert
// them with the canvas's ViewTransform. Pan and zoom are the canvas's own and never reach tools.
#pragma once

#include <QCursor>
#include <QString>

class QKeyEvent;
class QMouseEvent;
class QPainter;

namespace artcam::ui {

class Canvas;
class Document;

class Tool {
 public:
  Tool(Canvas* canvas, Document* document) : canvas_(canvas), document_(document) {}
  virtual ~Tool() = default;
  Tool(const Tool&) = delete;
  Tool& operator=(const Tool&) = delete;

  virtual void mousePress(QMouseEvent* event) = 0;
  virtual void mouseMove(QMouseEvent* event) = 0;
  virtual void mouseRelease(QMouseEvent* event) = 0;
  // Returns whether the key was used.
  virtual bool keyPress(QKeyEvent* event) = 0;
  // Overlay in widget coordinates, drawn after the photo and the pairs.
  virtual void paint(QPainter& painter) = 0;
  // Drop any half-made gesture (tool switch, new photo).
  virtual void cancel() = 0;
  // Whether a point is being placed or dragged now: the canvas then shows its loupe.
  virtual bool wantsLoupe() const { return false; }
  // Whether the tool works on the warped result: then the canvas may show the result while it
  // is active (canvas.h), and the tool maps its photo points through Canvas::photoPixelAt;
  // tools that only edit the photo in its own frame keep false (the canvas shows the photo).
  virtual bool worksOnResult() const { return false; }
  // What the status bar names as the active tool, and the cursor the canvas shows while it is
  // active (tool_cursor.h: a crosshair tagged with the tool's key), so the tool in use is
  // always visible where the user looks.
  virtual QString name() const { return QString(); }
  virtual QCursor cursor() const { return QCursor(Qt::CrossCursor); }

 protected:
  Canvas* canvas_;
  Document* document_;
};

}  // namespace artcam::ui
