// SPDX-License-Identifier: Apache-2.0
#include "ui/project_file.h"

#include "ui/preview_view.h"

#include <QFileInfo>
#include <QJsonArray>
#include <QJsonDocument>

#include <cmath>
#include <string>

namespace artcam::ui {
namespace {

std::string str(const QString& s) { return s.toStdString(); }
QString qstr(const std::string& s) { return QString::fromStdString(s); }

StudioProject toCore(const Project& p) {
  StudioProject c;
  c.photo_path = str(p.photo_path);
  c.photo_size = p.photo_size;
  for (const Pair& pair : p.pairs) c.pairs.push_back({pair.source, pair.target, pair.enabled});
  c.lines = p.lines;
  c.model = p.model;
  c.line_model = p.line_model;
  c.manual_camera = p.manual_camera;
  c.effects = p.effects;
  for (const DepthPlaneLayer& l : p.depth_layers) c.depth_layers.push_back({str(l.name), l.mask, l.anchors});
  if (p.depth_map) c.depth_map = ProjectDepthMap{str(p.depth_map->path), p.depth_map->options};
  if (p.second_path) c.second_path = str(*p.second_path);
  c.finish = p.finish;
  QJsonObject view;
  view["scale"] = p.view.scale;
  view["centre"] = QJsonArray{p.view.centre.x(), p.view.centre.y()};
  view["preview_mode"] = p.view.preview_mode;
  view["opacity"] = p.view.opacity;
  const CanvasViewState& canvas = p.view.canvas;
  view["canvas"] = QJsonObject{{"mode", canvasViewModeName(canvas.mode)},
                               {"compare_mode", canvasViewModeName(canvas.compare_mode)},
                               {"split", canvas.split},
                               {"onion_opacity", canvas.onion_opacity}};
  c.view_json = QJsonDocument(view).toJson(QJsonDocument::Compact).toStdString();
  if (!p.parts.isEmpty())
    c.parts_json = QJsonDocument(p.parts).toJson(QJsonDocument::Compact).toStdString();
  return c;
}

// The view object, checked: the mode becomes an enum and the scale a zoom.
Status readView(const std::string& text, const std::string& name, ViewState& v) {
  if (text.empty()) return Status::success();
  const QJsonObject view = QJsonDocument::fromJson(QByteArray::fromStdString(text)).object();
  v.scale = view["scale"].toDouble(0.0);
  const QJsonArray centre = view["centre"].toArray();
  if (centre.size() == 2 && centre[0].isDouble() && centre[1].isDouble())
    v.centre = QPointF(centre[0].toDouble(), centre[1].toDouble());
  v.preview_mode = view["preview_mode"].toInt(0);
  v.opacity = view["opacity"].toDouble(0.5);
  if (!(v.scale >= 0.0) || !std::isfinite(v.scale))
    return Status::failure(name + ": /view/scale: expected a number ≥ 0");
  if (v.preview_mode < 0 || v.preview_mode > static_cast<int>(PreviewMode::WarpedOnly))
    return Status::failure(name + ": /view/preview_mode: expected 0 to " +
                           std::to_string(static_cast<int>(PreviewMode::WarpedOnly)));
  if (!(v.opacity >= 0.0 && v.opacity <= 1.0))
    return Status::failure(name + ": /view/opacity: expected a number from 0 to 1");
  // Projects written before the canvas showed the result have no "canvas": the defaults.
  if (view.contains("canvas")) {
    const QJsonObject c = view["canvas"].toObject();
    CanvasViewState& s = v.canvas;
    const std::pair<const char*, CanvasViewMode*> modes[] = {{"mode", &s.mode},
                                                             {"compare_mode", &s.compare_mode}};
    for (const auto& [key, field] : modes) {
      if (!c.contains(QLatin1String(key))) continue;
      const auto mode = canvasViewModeFromName(str(c[QLatin1String(key)].toString()));
      if (!mode)
        return Status::failure(name + ": /view/canvas/" + key +
                               ": expected photo, result, split or onion");
      *field = *mode;
    }
    // `\` returns from the photo to compare_mode, so it is one of the result views.
    if (s.compare_mode == CanvasViewMode::Photo)
      return Status::failure(name + ": /view/canvas/compare_mode: expected result, split or onion");
    s.split = c["split"].toDouble(s.split);
    s.onion_opacity = c["onion_opacity"].toDouble(s.onion_opacity);
    if (!(s.split >= 0.0 && s.split <= 1.0))
      return Status::failure(name + ": /view/canvas/split: expected a number from 0 to 1");
    if (!(s.onion_opacity >= 0.0 && s.onion_opacity <= 1.0))
      return Status::failure(name + ": /view/canvas/onion_opacity: expected a number from 0 to 1");
  }
  return Status::success();
}

Result<Project> fromCore(StudioProject c, const std::string& name) {
  Project p;
  p.photo_path = qstr(c.photo_path);
  p.photo_size = projectPhotoSize(c);
  for (const PointMatch& m : c.pairs)
    p.pairs.push_back({Eigen::Vector2d(m.source.x(), m.source.y()),
                       Eigen::Vector2d(m.target.x(), m.target.y()), m.enabled});
  p.lines = std::move(c.lines);
  p.model = c.model;
  p.line_model = c.line_model;
  p.manual_camera = std::move(c.manual_camera);
  p.effects = std::move(c.effects);
  for (ProjectDepthLayer& l : c.depth_layers)
    p.depth_layers.push_back({qstr(l.name), std::move(l.mask), std::move(l.anchors)});
  if (c.depth_map) p.depth_map = DepthMapRef{qstr(c.depth_map->path), c.depth_map->options};
  if (c.second_path) p.second_path = qstr(*c.second_path);
  p.finish = c.finish;
  if (const Status view = readView(c.view_json, name, p.view); !view)
    return Result<Project>::failure(view.message);
  if (!c.parts_json.empty())
    p.parts = QJsonDocument::fromJson(QByteArray::fromStdString(c.parts_json)).object();
  return Result<Project>::success(std::move(p));
}

}  // namespace

QByteArray projectToJson(const Project& project, const QString& project_path) {
  return QByteArray::fromStdString(studioProjectToJson(toCore(project), str(project_path)));
}

Result<Project> parseProject(const QByteArray& json, const QString& project_path) {
  Result<StudioProject> read = parseStudioProject(
      std::string_view(json.constData(), static_cast<size_t>(json.size())), str(project_path));
  if (!read) return Result<Project>::failure(read.status.message);
  return fromCore(std::move(*read.value), str(QFileInfo(project_path).fileName()));
}

Result<Project> readProject(const QString& path) {
  Result<StudioProject> read = readStudioProject(str(path));
  if (!read) return Result<Project>::failure(read.status.message);
  return fromCore(std::move(*read.value), str(QFileInfo(path).fileName()));
}

Status writeProject(const QString& path, const Project& project) {
  return writeStudioProject(str(path), toCore(project));
}

Status checkPhotoSize(const Project& project, FrameSize photo, const QString& photo_path,
                      const QString& project_path) {
  StudioProject sizes;  // only the size: the check reads nothing else
  sizes.photo_size = project.photo_size;
  return checkProjectPhotoSize(sizes, photo, str(photo_path),
                               str(QFileInfo(project_path).fileName()));
}

}  // namespace artcam::ui
