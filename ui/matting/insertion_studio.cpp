// SPDX-License-Identifier: Apache-2.0
#include "ui/matting/insertion_studio.h"

#include "ui/canvas.h"
#include "ui/document.h"
#include "ui/matting/insertion_model.h"
#include "ui/matting/insertion_panel.h"
#include "ui/matting/insertion_preview.h"
#include "ui/matting/insertion_project.h"
#include "ui/session.h"
#include "ui/tools/region_tool.h"

#include <QAction>
#include <QDockWidget>
#include <QKeySequence>
#include <QMainWindow>
#include <QMenu>
#include <QMenuBar>
#include <QStatusBar>
#include <QToolButton>
#include <QVBoxLayout>

#include <memory>

namespace artcam::ui {

InsertionStudio::InsertionStudio(QMainWindow* window, Canvas* canvas, Document* document)
    : QObject(window),
      canvas_(canvas),
      document_(document),
      model_(new InsertionModel(document, this)),
      preview_(new InsertionPreview(model_, this)),
      panel_(new InsertionPanel(model_, preview_, window)),
      dock_(new QDockWidget(tr("Insertion"), window)) {
  dock_->setObjectName("insertionDock");
  dock_->setWidget(panel_);
  if (auto* pairs = window->findChild<QDockWidget*>(QStringLiteral("pairsDock"))) {
    window->tabifyDockWidget(pairs, dock_);
    pairs->raise();  // tabifying shows the new tab; the studio opens on its pairs
  } else
    window->addDockWidget(Qt::RightDockWidgetArea, dock_);

  QMenu* menu = new QMenu(tr("&Insertion"), window);
  const QList<QAction*> top = window->menuBar()->actions();
  // Before Help, which stays last.
  window->menuBar()->insertMenu(top.isEmpty() ? nullptr : top.back(), menu);

  grid_action_ = menu->addAction(tr("&Grid Tool"));
  grid_action_->setShortcut(QKeySequence(tr("C")));
  grid_action_->setIconText(tr("Grid"));  // the toolbar's short label
  grid_action_->setToolTip(
      tr("Click grid corners in the photo, matched to the corner selected in "
         "the board view; snaps to the corner (Shift: no snap), Del removes (C)"));
  connect(grid_action_, &QAction::triggered, this, [this] {
    canvas_->setTool(
        std::make_unique<GridTool>(canvas_, document_, model_, preview_, defaultCornerSnapper()));
    dock_->show();
    dock_->raise();
  });
  region_action_ = menu->addAction(tr("&Region Tool"));
  region_action_->setShortcut(QKeySequence(tr("R")));
  region_action_->setIconText(tr("Region"));
  region_action_->setToolTip(
      tr("Click a polygon around the reflecting or refracting object; "
         "Enter closes it; the composite stays inside it (R)"));
  connect(region_action_, &QAction::triggered, this, [this] {
    canvas_->setTool(std::make_unique<RegionTool>(canvas_, document_, model_, preview_));
    dock_->show();
    dock_->raise();
  });
  menu->addSeparator();
  menu->addAction(tr("Load &Graphic…"), QKeySequence(tr("Ctrl+Shift+I")), panel_,
                  &InsertionPanel::loadGraphicDialog)
      ->setToolTip(tr("The image to insert into the reflection or refraction"));
  menu->addAction(tr("&Import Grid Matches…"), panel_, &InsertionPanel::importGridCsvDialog)
      ->setToolTip(tr("CSV src_x,src_y,dst_x,dst_y: board pixels → photo pixels"));
  menu->addAction(tr("&Export Grid Matches…"), panel_, &InsertionPanel::exportGridCsvDialog)
      ->setToolTip(tr("Save the grid matches as CSV"));
  menu->addAction(tr("Export Inserted &Image…"), QKeySequence(tr("Ctrl+Shift+E")), panel_,
                  &InsertionPanel::exportCompositeDialog)
      ->setToolTip(tr("The graphic inserted into the full-resolution photo"));
  menu->addAction(tr("Export Piecewise &Camera…"), panel_, &InsertionPanel::exportCameraDialog)
      ->setToolTip(tr("The fitted patches as a .artcam file (artcam insert --camera reads it)"));
  QAction* error_map = menu->addAction(tr("Show Error &Map"));
  error_map->setCheckable(true);
  error_map->setChecked(model_->errorMapVisible());
  error_map->setShortcut(QKeySequence(tr("Shift+M")));
  error_map->setToolTip(
      tr("Each patch outlined in the photo, green at 0 px to red at the max error"));
  connect(error_map, &QAction::toggled, model_, &InsertionModel::setErrorMapVisible);
  connect(model_, &InsertionModel::errorMapVisibilityChanged, error_map, &QAction::setChecked);
  menu->addAction(tr("&Clear Region"), panel_, &InsertionPanel::clearRegion)
      ->setToolTip(tr("The composite is then not limited"));
  menu->addSeparator();
  menu->addAction(dock_->toggleViewAction());

  for (QAction* a : {grid_action_, region_action_}) {
    auto* b = new QToolButton(panel_);
    b->setDefaultAction(a);
    b->setToolButtonStyle(Qt::ToolButtonTextOnly);
    b->setSizePolicy(QSizePolicy::Expanding, QSizePolicy::Fixed);
    panel_->toolArea()->addWidget(b);
  }

  auto repaint = [this] { canvas_->update(); };
  connect(preview_, &InsertionPreview::compositeChanged, canvas_, repaint);
  connect(preview_, &InsertionPreview::fitChanged, canvas_, repaint);
  connect(model_, &InsertionModel::stateChanged, canvas_, repaint);
  connect(model_, &InsertionModel::selectionChanged, canvas_, repaint);
  connect(model_, &InsertionModel::errorMapVisibilityChanged, canvas_, repaint);
  connect(preview_, &InsertionPreview::failed, window, [window](const QString& m) {
    window->statusBar()->showMessage(tr("Insertion failed: %1").arg(m), 8000);
  });
}

void InsertionStudio::attachToSession(Session* session) {
  Session::ProjectPart part;
  part.name = QStringLiteral("insertion");
  part.save = [this] { return insertionToJson(model_->state()); };
  part.load = [this](const QJsonObject& json) {
    if (json.isEmpty()) return;  // the new photo already reset the mode
    auto state = insertionFromJson(json, "project: /parts/insertion");
    if (!state) {
      panel_->reportLoadProblem(QString::fromStdString(state.status.message));
      return;
    }
    const QString graphic = state->graphic_path;
    model_->setState(std::move(*state));  // part of opening, not an undoable edit
    if (!graphic.isEmpty()) panel_->loadGraphic(graphic, /*undoable=*/false);
  };
  session->addProjectPart(std::move(part));
}

}  // namespace artcam::ui
