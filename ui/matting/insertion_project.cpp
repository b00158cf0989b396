// SPDX-License-Identifier: Apache-2.0
#include "ui/matting/insertion_project.h"

#include <QJsonArray>

#include <cmath>
#include <optional>

namespace artcam::ui {
namespace {

QJsonArray point(const Eigen::Vector2d& p) { return QJsonArray{p.x(), p.y()}; }

std::optional<Eigen::Vector2d> readPoint(const QJsonValue& v) {
  const QJsonArray a = v.toArray();
  if (a.size() != 2 || !a[0].isDouble() || !a[1].isDouble()) return std::nullopt;
  const Eigen::Vector2d p(a[0].toDouble(), a[1].toDouble());
  if (!p.allFinite()) return std::nullopt;
  return p;
}

}  // namespace

QJsonObject insertionToJson(const InsertionState& s) {
  if (s.matches.empty() && s.region.empty() && s.graphic_path.isEmpty()) return {};
  QJsonObject o;
  o["board"] = QJsonArray{s.board_size.width, s.board_size.height};
  o["squares"] = s.squares;
  o["max_error_px"] = s.max_error_px;
  QJsonArray matches;
  for (const GridMatch& m : s.matches) {
    QJsonObject match{{"board", point(m.board)}, {"photo", point(m.photo)}};
    if (m.on_table) match["on_table"] = true;  // absent: through the object (older projects)
    matches.append(match);
  }
  o["matches"] = matches;
  QJsonArray region;
  for (const Eigen::Vector2d& p : s.region) region.append(point(p));
  o["region"] = region;
  if (!s.graphic_path.isEmpty()) o["graphic"] = s.graphic_path;
  o["placement"] = QJsonObject{{"origin", point(s.placement.origin)}, {"width", s.placement.width}};
  return o;
}

Result<InsertionState> insertionFromJson(const QJsonObject& o, const std::string& where) {
  const auto fail = [&](const std::string& m) { return Result<InsertionState>::failure(where + m); };
  InsertionState s;
  const QJsonArray board = o["board"].toArray();
  if (board.size() != 2 || board[0].toInt(0) <= 0 || board[1].toInt(0) <= 0)
    return fail("/board: expected [width, height] in pixels");
  s.board_size = {board[0].toInt(), board[1].toInt()};
  s.squares = o["squares"].toInt(0);
  if (s.squares < 2) return fail("/squares: expected a whole number ≥ 2");
  s.max_error_px = o["max_error_px"].toDouble(-1.0);
  if (!(s.max_error_px > 0.0) || !std::isfinite(s.max_error_px))
    return fail("/max_error_px: expected a positive number");
  const QJsonArray matches = o["matches"].toArray();
  for (qsizetype i = 0; i < matches.size(); ++i) {
    const QJsonObject m = matches[i].toObject();
    const auto b = readPoint(m["board"]), p = readPoint(m["photo"]);
    if (!b || !p) return fail("/matches/" + std::to_string(i) + ": expected board and photo [x, y]");
    const QJsonValue on_table = m["on_table"];
    if (!on_table.isUndefined() && !on_table.isBool())
      return fail("/matches/" + std::to_string(i) + "/on_table: expected true or false");
    s.matches.push_back({*b, *p, on_table.toBool(false)});
  }
  const QJsonArray region = o["region"].toArray();
  for (qsizetype i = 0; i < region.size(); ++i) {
    const auto p = readPoint(region[i]);
    if (!p) return fail("/region/" + std::to_string(i) + ": expected [x, y]");
    s.region.push_back(*p);
  }
  s.graphic_path = o["graphic"].toString();
  const QJsonObject placement = o["placement"].toObject();
  if (const auto origin = readPoint(placement["origin"])) s.placement.origin = *origin;
  s.placement.width = placement["width"].toDouble(0.0);
  return Result<InsertionState>::success(std::move(s));
}

}  // namespace artcam::ui
