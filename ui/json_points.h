// SPDX-License-Identifier: Apache-2.0
// 2D points in the studio's JSON files (projects and their parts): `[x, y]`, numbers written
// round-trip exactly by QJsonDocument. One place for the reader's rules (two finite numbers).
#pragma once

#include <QJsonArray>
#include <QJsonValue>

#include <Eigen/Core>

#include <optional>

namespace artcam::ui {

inline QJsonArray jsonFromPoint(const Eigen::Vector2d& p) { return QJsonArray{p.x(), p.y()}; }

// Empty unless `v` is an array of exactly two finite numbers.
inline std::optional<Eigen::Vector2d> pointFromJson(const QJsonValue& v) {
  const QJsonArray a = v.toArray();
  if (a.size() != 2 || !a[0].isDouble() || !a[1].isDouble()) return std::nullopt;
  const Eigen::Vector2d p(a[0].toDouble(), a[1].toDouble());
  if (!p.allFinite()) return std::nullopt;
  return p;
}

}  // namespace artcam::ui
