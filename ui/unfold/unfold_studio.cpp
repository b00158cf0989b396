// SPDX-License-Identifier: Apache-2.0
#include "ui/unfold/unfold_studio.h"

#include "core/piecewise/unfold_walls.h"
#include "ui/background_job.h"
#include "ui/canvas.h"
#include "ui/commands.h"
#include "ui/depth_model.h"
#include "ui/document.h"
#include "ui/session.h"
#include "ui/unfold/wall_tool.h"
#include "ui/unfold/walls_model.h"

#include <QAction>
#include <QFileInfo>
#include <QInputDialog>
#include <QKeySequence>
#include <QMainWindow>
#include <QMenu>
#include <QMenuBar>
#include <QMessageBox>
#include <QSettings>
#include <QStatusBar>

#include <memory>

namespace artcam::ui {
namespace {

constexpr char kFocalKey[] = "unfold/focal_px";

}  // namespace

UnfoldStudio::UnfoldStudio(QMainWindow* window, Canvas* canvas, Document* document)
    : QObject(window),
      window_(window),
      canvas_(canvas),
      document_(document),
      walls_(new WallsModel(document, this)) {
  QMenu* menu = new QMenu(tr("&Unfold"), window);
  const QList<QAction*> top = window->menuBar()->actions();
  window->menuBar()->insertMenu(top.isEmpty() ? nullptr : top.back(), menu);  // before Help
  wall_action_ = menu->addAction(tr("&Wall Tool"));
  wall_action_->setShortcut(QKeySequence(tr("W")));
  wall_action_->setIconText(tr("Walls"));
  wall_action_->setToolTip(
      tr("Click a wall's corners; Enter closes it. Mark every wall to unfold; Del removes the "
         "wall under the cursor (W)"));
  connect(wall_action_, &QAction::triggered, this,
          [this] { canvas_->setTool(std::make_unique<WallTool>(canvas_, document_, walls_)); });
  menu->addAction(tr("&Unfold Walls…"), this, &UnfoldStudio::unfoldDialog)
      ->setToolTip(tr("Each marked wall seen orthogonally, side by side, its plane from the "
                      "depth map (File ▸ Depth from Stereo Pair…); the roof stretched to fit"));
  menu->addAction(tr("&Clear Walls"), this, [this] { walls_->edit({}, tr("Clear Walls")); });
  connect(walls_, &WallsModel::wallsChanged, canvas_, [this] { canvas_->update(); });
}

void UnfoldStudio::attachToSession(Session* session) {
  Session::ProjectPart part;
  part.name = QStringLiteral("walls");
  part.save = [this] { return wallsToJson(walls_->walls()); };
  part.load = [this](const QJsonObject& json) {
    if (json.isEmpty() || !document_->photo()) return;
    auto walls = wallsFromJson(json, document_->photo()->size(), "project: /parts/walls");
    if (!walls) {
      fail(QString::fromStdString(walls.status.message));
      return;
    }
    walls_->setWalls(std::move(*walls));  // part of opening, not an undoable edit
  };
  session->addProjectPart(std::move(part));
}

void UnfoldStudio::fail(const QString& message) {
  window_->statusBar()->showMessage(tr("Unfold walls: %1").arg(message), 10000);
  if (interactive_) QMessageBox::warning(window_, tr("Unfold walls"), message);
  emit unfolded(false, message);
}

void UnfoldStudio::unfoldDialog() {
  const PhotoPtr photo = document_->photo();
  if (!photo) return;
  QSettings settings;
  bool ok = false;
  const double focal = QInputDialog::getDouble(
      window_, tr("Unfold walls"), tr("The photo's focal length in pixels"),
      settings.value(kFocalKey, static_cast<double>(photo->size().width)).toDouble(), 1e-3, 1e7, 2,
      &ok);
  if (!ok) return;
  settings.setValue(kFocalKey, focal);
  unfold(focal);
}

void UnfoldStudio::unfold(double focal_px) {
  const PhotoPtr photo = document_->photo();
  if (!photo) return fail(tr("open a photo first"));
  if (running_) return fail(tr("an unfold is running"));
  if (walls_->walls().empty())
    return fail(tr("mark the walls first (Unfold ▸ Wall Tool, W): click each wall's corners"));
  if (!document_->depth()->hasDepth())
    return fail(tr("%1 has no depth: load a depth map or make one from a stereo pair (File ▸ "
                   "Depth from Stereo Pair…)")
                    .arg(QFileInfo(photo->path).fileName()));
  // Rasterised here (the depth model lives on the GUI thread), unfolded off it.
  auto depth = std::make_shared<const ImageF>(document_->depth()->rasterise());
  const std::vector<WallOutline> walls = walls_->walls();
  UnfoldOptions options;
  options.focal_px = focal_px;
  options.frame = photo->size();
  running_ = true;
  window_->statusBar()->showMessage(
      tr("Unfolding %n wall(s)…", nullptr, static_cast<int>(walls.size())));
  struct Made {
    Result<Artcam> camera;
    UnfoldSummary summary;
  };
  runInBackground(
      this,
      [depth, photo, walls, options](JobContext&) {
        Made made;
        made.camera = unfoldWalls(*depth, photo->size(), walls, options, &made.summary);
        return made;
      },
      [this, photo](JobOutcome<Made> outcome) {
        running_ = false;
        // Another photo opened meanwhile (its full decode, of the same photo, may have replaced
        // a first look: that one is still the photo the walls were marked on).
        const PhotoPtr now = document_->photo();
        if (!now || now->path != photo->path || now->size() != photo->size()) {
          const QString message = tr("not applied: another photo was opened meanwhile");
          window_->statusBar()->showMessage(tr("Unfold walls: %1").arg(message), 10000);
          emit unfolded(false, message);
          return;
        }
        if (!outcome.value) return fail(outcome.error);
        if (!outcome.value->camera)
          return fail(QString::fromStdString(outcome.value->camera.status.message));
        Artcam camera = std::move(*outcome.value->camera);
        camera.frame = CameraFrame::Upright;  // the walls were marked on the photo as shown
        const UnfoldSummary& summary = outcome.value->summary;
        QStringList parts;
        for (const UnfoldedWall& w : summary.walls) {
          QString part = tr("%1 %2 × %3")
                             .arg(QString::fromStdString(w.name))
                             .arg(w.width, 0, 'g', 3)
                             .arg(w.height, 0, 'g', 3);
          if (w.roof_height > 0)
            part += tr(" (the roof over it stretched ×%1)").arg(w.roof_stretch, 0, 'f', 2);
          parts << part;
        }
        document_->undoStack()->push(
            new SetCameraCommand(document_, std::move(camera), tr("Unfold Walls")));
        const QString message =
            tr("Unfolded %n wall(s): %1", nullptr, static_cast<int>(summary.walls.size()))
                .arg(parts.join(QStringLiteral(", ")));
        window_->statusBar()->showMessage(message, 10000);
        emit unfolded(true, message);
      });
}

}  // namespace artcam::ui
