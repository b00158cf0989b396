// SPDX-License-Identifier: Apache-2.0
// Assembles Insertion mode into the main window (so MainWindow needs one line for it): the
// model, the fit/preview worker, the dock panel, the "Insertion" menu with the grid and region
// tools, and the canvas repaints. Holds no editing logic of its own.
#pragma once

#include "ui/tools/grid_tool.h"

#include <QObject>

class QAction;
class QDockWidget;
class QMainWindow;

namespace artcam::ui {

class Canvas;
class Document;
class Session;
class InsertionModel;
class InsertionPanel;
class InsertionPreview;

// snapToGridCorner (core/piecewise/corner_snap.h) with its default options.
CornerSnapper defaultCornerSnapper();

class InsertionStudio : public QObject {
  Q_OBJECT

 public:
  InsertionStudio(QMainWindow* window, Canvas* canvas, Document* document);
  // Keeps the mode's state in the session's projects (and so in autosaves and recoveries).
  void attachToSession(Session* session);

  InsertionModel* model() const { return model_; }
  InsertionPreview* preview() const { return preview_; }
  InsertionPanel* panel() const { return panel_; }
  QDockWidget* dock() const { return dock_; }
  QAction* gridToolAction() const { return grid_action_; }
  QAction* regionToolAction() const { return region_action_; }

 private:
  Canvas* canvas_;
  Document* document_;
  InsertionModel* model_;
  InsertionPreview* preview_;
  InsertionPanel* panel_;
  QDockWidget* dock_;
  QAction* grid_action_;
  QAction* region_action_;
};

}  // namespace artcam::ui
