// SPDX-License-Identifier: Apache-2.0
// The walls the user marks for the unfolded view (the paper's Fig 2; core/piecewise/
// unfold_walls.h): outlines in photo PIXELS, kept in the order unfoldWalls wants them (left to
// right, each with its base as its first edge), so the marking order does not matter.
// Changed only through SetWallsCommand on the document's undo stack; a new photo starts over.
#pragma once

#include "core/model/status.h"
#include "core/piecewise/unfold_walls.h"

#include <QJsonObject>
#include <QObject>
#include <QUndoCommand>

#include <vector>

namespace artcam::ui {

class Document;

// The outline turned so its first edge is its base — the edge lowest in the photo (largest
// mean y), run left to right — as unfoldWalls reads it.
WallOutline withBaseFirst(WallOutline wall);
// The walls sorted left to right by their centroids.
std::vector<WallOutline> leftToRight(std::vector<WallOutline> walls);

class WallsModel : public QObject {
  Q_OBJECT

 public:
  explicit WallsModel(Document* document, QObject* parent = nullptr);

  Document* document() const { return document_; }
  const std::vector<WallOutline>& walls() const { return walls_; }
  // Raw mutator for SetWallsCommand and project loading.
  void setWalls(std::vector<WallOutline> walls);
  // One undo step (none when unchanged).
  void edit(std::vector<WallOutline> next, const QString& text);
  // A new wall from marked corners (at least 3): base first, named "wall N", in its place.
  void addWall(std::vector<Eigen::Vector2d> corners);

 signals:
  void wallsChanged();

 private:
  Document* document_;
  std::vector<WallOutline> walls_;
};

class SetWallsCommand : public QUndoCommand {
 public:
  SetWallsCommand(WallsModel* model, std::vector<WallOutline> before,
                  std::vector<WallOutline> after, const QString& text);
  void undo() override { model_->setWalls(before_); }
  void redo() override { model_->setWalls(after_); }

 private:
  WallsModel* model_;
  std::vector<WallOutline> before_, after_;
};

// The project's "walls" part: {"walls": [{"name": …, "corners": [[x, y], …]}, …]}; empty
// object for no walls. Reading is bounded as the walls CSV is (walls_csv.h) and every corner
// must be a finite number inside `photo` (one pixel of slack); `where` names the place.
QJsonObject wallsToJson(const std::vector<WallOutline>& walls);
Result<std::vector<WallOutline>> wallsFromJson(const QJsonObject& json, FrameSize photo,
                                               const std::string& where);

}  // namespace artcam::ui
