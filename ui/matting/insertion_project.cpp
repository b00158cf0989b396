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

QJsonArray matchesToJson(const std::vector<GridMatch>& list) {
  QJsonArray matches;
  for (const GridMatch& m : list) {
    QJsonObject match{{"board", point(m.board)}, {"photo", point(m.photo)}};
    if (m.on_table) match["on_table"] = true;  // absent: through the object (older projects)
    matches.append(match);
  }
  return matches;
}

QJsonArray regionToJson(const std::vector<Eigen::Vector2d>& region) {
  QJsonArray out;
  for (const Eigen::Vector2d& p : region) out.append(point(p));
  return out;
}

// "matches" and "region" of `o` into `matches` and `region`; an error names the place.
std::string readMedium(const QJsonObject& o, std::vector<GridMatch>& matches,
                       std::vector<Eigen::Vector2d>& region) {
  const QJsonArray list = o["matches"].toArray();
  for (qsizetype i = 0; i < list.size(); ++i) {
    const QJsonObject m = list[i].toObject();
    const auto b = readPoint(m["board"]), p = readPoint(m["photo"]);
    if (!b || !p) return "/matches/" + std::to_string(i) + ": expected board and photo [x, y]";
    const QJsonValue on_table = m["on_table"];
    if (!on_table.isUndefined() && !on_table.isBool())
      return "/matches/" + std::to_string(i) + "/on_table: expected true or false";
    matches.push_back({*b, *p, on_table.toBool(false)});
  }
  const QJsonArray corners = o["region"].toArray();
  for (qsizetype i = 0; i < corners.size(); ++i) {
    const auto p = readPoint(corners[i]);
    if (!p) return "/region/" + std::to_string(i) + ": expected [x, y]";
    region.push_back(*p);
  }
  return {};
}

}  // namespace

QJsonObject insertionToJson(const InsertionState& s) {
  if (s.matches.empty() && s.region.empty() && s.graphic_path.isEmpty() && s.other_media.empty())
    return {};
  QJsonObject o;
  o["board"] = QJsonArray{s.board_size.width, s.board_size.height};
  o["squares"] = s.squares;
  o["max_error_px"] = s.max_error_px;
  o["matches"] = matchesToJson(s.matches);
  o["region"] = regionToJson(s.region);
  if (!s.other_media.empty()) {
    QJsonArray media;
    for (const InsertionMedium& m : s.other_media)
      media.append(
          QJsonObject{{"matches", matchesToJson(m.matches)}, {"region", regionToJson(m.region)}});
    o["other_media"] = media;
    o["current_medium"] = s.current_medium;
  }
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
  if (const std::string e = readMedium(o, s.matches, s.region); !e.empty()) return fail(e);
  const QJsonArray media = o["other_media"].toArray();
  if (media.size() > kMaxInsertionMedia - 1)
    return fail("/other_media: " + std::to_string(media.size()) + " media (at most " +
                std::to_string(kMaxInsertionMedia - 1) + ")");
  for (qsizetype i = 0; i < media.size(); ++i) {
    InsertionMedium m;
    if (const std::string e = readMedium(media[i].toObject(), m.matches, m.region); !e.empty())
      return fail("/other_media/" + std::to_string(i) + e);
    s.other_media.push_back(std::move(m));
  }
  s.current_medium = o["current_medium"].toInt(0);
  if (s.current_medium < 0 || s.current_medium > static_cast<int>(s.other_media.size()))
    return fail("/current_medium: expected 0 to " + std::to_string(s.other_media.size()));
  s.graphic_path = o["graphic"].toString();
  const QJsonObject placement = o["placement"].toObject();
  if (const auto origin = readPoint(placement["origin"])) s.placement.origin = *origin;
  s.placement.width = placement["width"].toDouble(0.0);
  return Result<InsertionState>::success(std::move(s));
}

}  // namespace artcam::ui
