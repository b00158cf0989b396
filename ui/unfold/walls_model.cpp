// SPDX-License-Identifier: Apache-2.0
#include "ui/unfold/walls_model.h"

#include "core/io/walls_csv.h"
#include "ui/document.h"

#include <QJsonArray>
#include <QUndoStack>

#include <algorithm>
#include <cmath>

namespace artcam::ui {
namespace {

Eigen::Vector2d centroid(const WallOutline& w) {
  Eigen::Vector2d c = Eigen::Vector2d::Zero();
  for (const Eigen::Vector2d& p : w.photo_px) c += p;
  return w.photo_px.empty() ? c : Eigen::Vector2d(c / static_cast<double>(w.photo_px.size()));
}

}  // namespace

WallOutline withBaseFirst(WallOutline wall) {
  std::vector<Eigen::Vector2d>& c = wall.photo_px;
  const size_t n = c.size();
  if (n < 3) return wall;
  size_t base = 0;
  double lowest = -std::numeric_limits<double>::infinity();
  for (size_t k = 0; k < n; ++k) {
    const double y = 0.5 * (c[k].y() + c[(k + 1) % n].y());
    if (y > lowest) lowest = y, base = k;
  }
  std::rotate(c.begin(), c.begin() + static_cast<std::ptrdiff_t>(base), c.end());
  // The base runs left to right: otherwise the outline is walked the other way round from the
  // base's left end.
  if (c[1].x() < c[0].x()) {
    std::vector<Eigen::Vector2d> turned{c[1], c[0]};
    for (size_t k = n - 1; k >= 2; --k) turned.push_back(c[k]);
    c = std::move(turned);
  }
  return wall;
}

std::vector<WallOutline> leftToRight(std::vector<WallOutline> walls) {
  std::stable_sort(walls.begin(), walls.end(), [](const WallOutline& a, const WallOutline& b) {
    return centroid(a).x() < centroid(b).x();
  });
  return walls;
}

WallsModel::WallsModel(Document* document, QObject* parent) : QObject(parent), document_(document) {
  // Outlines are pixels of the old photo.
  connect(document_, &Document::photoChanged, this, [this] { setWalls({}); });
}

void WallsModel::setWalls(std::vector<WallOutline> walls) {
  walls_ = std::move(walls);
  emit wallsChanged();
}

void WallsModel::edit(std::vector<WallOutline> next, const QString& text) {
  auto same = [](const std::vector<WallOutline>& a, const std::vector<WallOutline>& b) {
    if (a.size() != b.size()) return false;
    for (size_t i = 0; i < a.size(); ++i)
      if (a[i].name != b[i].name || a[i].photo_px != b[i].photo_px) return false;
    return true;
  };
  if (same(next, walls_)) return;
  document_->undoStack()->push(new SetWallsCommand(this, walls_, std::move(next), text));
}

void WallsModel::addWall(std::vector<Eigen::Vector2d> corners) {
  if (corners.size() < 3 || walls_.size() >= kMaxWalls) return;
  corners.resize(std::min(corners.size(), kMaxWallCorners));
  // The lowest free number, so names stay short after removals.
  int number = 1;
  for (bool taken = true; taken; ++number) {
    taken = false;
    for (const WallOutline& w : walls_)
      if (w.name == "wall " + std::to_string(number)) taken = true;
    if (!taken) break;
  }
  std::vector<WallOutline> next = walls_;
  next.push_back(withBaseFirst({"wall " + std::to_string(number), std::move(corners)}));
  edit(leftToRight(std::move(next)), tr("Mark Wall"));
}

SetWallsCommand::SetWallsCommand(WallsModel* model, std::vector<WallOutline> before,
                                 std::vector<WallOutline> after, const QString& text)
    : model_(model), before_(std::move(before)), after_(std::move(after)) {
  setText(text);
}

QJsonObject wallsToJson(const std::vector<WallOutline>& walls) {
  if (walls.empty()) return {};
  QJsonArray list;
  for (const WallOutline& w : walls) {
    QJsonArray corners;
    for (const Eigen::Vector2d& p : w.photo_px) corners.append(QJsonArray{p.x(), p.y()});
    list.append(QJsonObject{{"name", QString::fromStdString(w.name)}, {"corners", corners}});
  }
  return QJsonObject{{"walls", list}};
}

Result<std::vector<WallOutline>> wallsFromJson(const QJsonObject& json, FrameSize photo,
                                               const std::string& where) {
  using R = Result<std::vector<WallOutline>>;
  const QJsonArray list = json.value("walls").toArray();
  if (!json.value("walls").isArray()) return R::failure(where + "/walls: expected a list");
  if (static_cast<size_t>(list.size()) > kMaxWalls)
    return R::failure(where + "/walls: " + std::to_string(list.size()) + " walls (at most " +
                      std::to_string(kMaxWalls) + ")");
  std::vector<WallOutline> walls;
  for (qsizetype i = 0; i < list.size(); ++i) {
    const std::string at = where + "/walls/" + std::to_string(i);
    const QJsonObject o = list[i].toObject();
    const QJsonArray corners = o.value("corners").toArray();
    if (!o.value("name").isString() || !o.value("corners").isArray())
      return R::failure(at + ": expected a name and a list of corners");
    if (corners.size() < 3 || static_cast<size_t>(corners.size()) > kMaxWallCorners)
      return R::failure(at + "/corners: " + std::to_string(corners.size()) + " corners (3 to " +
                        std::to_string(kMaxWallCorners) + ")");
    WallOutline w;
    w.name = o.value("name").toString().toStdString();
    for (qsizetype k = 0; k < corners.size(); ++k) {
      const QJsonArray xy = corners[k].toArray();
      const double x = xy.size() == 2 && xy[0].isDouble() ? xy[0].toDouble() : NAN;
      const double y = xy.size() == 2 && xy[1].isDouble() ? xy[1].toDouble() : NAN;
      if (!std::isfinite(x) || !std::isfinite(y) || x < -1 || y < -1 || x > photo.width + 1 ||
          y > photo.height + 1)
        return R::failure(at + "/corners/" + std::to_string(k) + ": expected [x, y] inside the " +
                          std::to_string(photo.width) + "x" + std::to_string(photo.height) +
                          " photo");
      w.photo_px.emplace_back(x, y);
    }
    walls.push_back(std::move(w));
  }
  return R::success(std::move(walls));
}

}  // namespace artcam::ui
