// SPDX-License-Identifier: Apache-2.0
// The unfolded view in the studio (the paper's Fig 2; core/piecewise/unfold_walls.h), assembled
// into the main window: the walls model, the wall tool, the Unfold menu, the walls' place in
// the project, and the unfold itself — the marked walls and the document's depth (its depth
// map, e.g. from File ▸ Depth from Stereo Pair…, under any painted planes) made into the
// unfolding camera off the GUI thread, which becomes the document's camera in one undo step.
// The walls are laid out in the photo's own frame, at the largest scale that fits, from its
// top-left corner: the studio's camera keeps the photo's frame on every path (canvas, export,
// project), so the unfolded picture is neither stretched nor cropped (Export's crop to the
// valid pixels gives the command line's picture back).
#pragma once

#include <QObject>
#include <QString>

class QAction;
class QMainWindow;

namespace artcam::ui {

class Canvas;
class Document;
class Session;
class WallsModel;

class UnfoldStudio : public QObject {
  Q_OBJECT

 public:
  UnfoldStudio(QMainWindow* window, Canvas* canvas, Document* document);
  // Keeps the walls in the session's projects (and so in autosaves and recoveries).
  void attachToSession(Session* session);

  WallsModel* walls() const { return walls_; }
  QAction* wallToolAction() const { return wall_action_; }
  // When false, failures are only reported (unfolded), not shown in a message box (tests).
  void setInteractive(bool interactive) { interactive_ = interactive; }

  // Starts the unfold with the photo's focal length in pixels; `unfolded` says how it ended.
  void unfold(double focal_px);
  // Unfold ▸ Unfold Walls…: asks the focal length (the last one given is offered), then unfold.
  void unfoldDialog();

 signals:
  void unfolded(bool ok, const QString& message);

 private:
  void fail(const QString& message);

  QMainWindow* window_;
  Canvas* canvas_;
  Document* document_;
  WallsModel* walls_;
  QAction* wall_action_;
  bool interactive_ = true;
  bool running_ = false;
};

}  // namespace artcam::ui
