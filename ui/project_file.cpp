// SPDX-License-Identifier: Apache-2.0
#include "ui/project_file.h"

#include "core/io/artcam_file.h"
#include "ui/preview_view.h"

#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QSaveFile>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>

namespace artcam::ui {
namespace {

QJsonArray point(const Eigen::Vector2d& p) { return {p.x(), p.y()}; }

std::optional<Eigen::Vector2d> readPoint(const QJsonValue& v) {
  const QJsonArray a = v.toArray();
  if (a.size() != 2 || !a[0].isDouble() || !a[1].isDouble()) return std::nullopt;
  const Eigen::Vector2d p(a[0].toDouble(), a[1].toDouble());
  if (!std::isfinite(p.x()) || !std::isfinite(p.y())) return std::nullopt;
  return p;
}

std::string str(const QString& s) { return s.toStdString(); }

// A string from the file quoted for a one-line message: JSON-escaped (Qt's parser lets raw
// control characters, newlines included, through inside strings) and cut at 40 characters.
std::string quoted(const QString& s) {
  const QByteArray array = QJsonDocument(QJsonArray{s.left(40)}).toJson(QJsonDocument::Compact);
  return array.mid(1, array.size() - 2).toStdString();  // drop the [ ]
}

// A depth mask larger than this is refused before it is allocated (two bytes per pixel while it
// is decoded): 2^30 pixels is beyond any photo the studio edits (a 30 000 × 20 000 photo is
// 0.6 Gpix), and a few bytes of runs must not be able to ask for gigabytes.
constexpr std::uint64_t kMaxMaskPixels = std::uint64_t{1} << 30;

// Pixels the run bytes cover, read with region_mask.h's grammar (a value byte, then the run
// length as a little-endian base-128 varint) but without allocating the mask; nullopt when the
// bytes are malformed. Lets a lying size or broken runs be refused before anything is allocated.
std::optional<std::uint64_t> pixelsCoveredByRuns(const QByteArray& runs) {
  std::uint64_t covered = 0;
  qsizetype i = 0;
  while (i < runs.size()) {
    ++i;  // the value byte
    std::uint64_t run = 0;
    for (int shift = 0;; shift += 7) {
      if (i >= runs.size() || shift > 35) return std::nullopt;
      const auto b = static_cast<std::uint8_t>(runs[i++]);
      run |= static_cast<std::uint64_t>(b & 0x7f) << shift;
      if (!(b & 0x80)) break;
    }
    covered += run;  // at most 2^42 per run: no overflow for any file that fits in memory
  }
  return covered;
}

QString pathForFile(const QString& path, const QString& project_path) {
  const QDir base = QFileInfo(project_path).absoluteDir();
  const QString relative = base.relativeFilePath(path);
  return relative.startsWith("..") ? path : relative;
}

QString pathFromFile(const QString& path, const QString& project_path) {
  return QFileInfo(path).isAbsolute() ? path
                                      : QFileInfo(project_path).absoluteDir().absoluteFilePath(path);
}

QJsonObject depthToJson(const Project& project, const QString& project_path) {
  QJsonObject depth;
  QJsonArray layers;
  for (const DepthPlaneLayer& l : project.depth_layers) {
    QJsonObject o;
    o["name"] = l.name;
    o["size"] = QJsonArray{l.mask.width(), l.mask.height()};
    const std::vector<uint8_t> runs = encodeMaskRuns(l.mask);
    o["mask"] = QString::fromLatin1(
        QByteArray(reinterpret_cast<const char*>(runs.data()), static_cast<qsizetype>(runs.size()))
            .toBase64());
    QJsonArray anchors;
    for (const DepthAnchor& a : l.anchors)
      anchors.append(QJsonObject{{"pixel", point(a.pixel)}, {"depth", a.depth}});
    o["anchors"] = anchors;
    layers.append(o);
  }
  depth["layers"] = layers;
  if (project.depth_map)
    depth["map"] = QJsonObject{{"path", pathForFile(project.depth_map->path, project_path)},
                               {"scale", project.depth_map->options.scale},
                               {"inverse", project.depth_map->options.inverse}};
  return depth;
}

// Reads the optional "depth" object; `name` prefixes messages with the file name.
Status parseDepth(const QJsonObject& depth, const std::string& name, const QString& project_path,
                  Project& p) {
  const QJsonArray layers = depth["layers"].toArray();
  for (qsizetype i = 0; i < layers.size(); ++i) {
    const QJsonObject o = layers[i].toObject();
    const std::string where = name + ": /depth/layers/" + std::to_string(i);
    DepthPlaneLayer l;
    l.name = o["name"].toString();
    const QJsonArray size = o["size"].toArray();
    if (size.size() != 2 || !size[0].isDouble() || !size[1].isDouble())
      return Status::failure(where + "/size: expected [width, height]");
    const QByteArray raw = QByteArray::fromBase64(o["mask"].toString().toLatin1(),
                                                  QByteArray::AbortOnBase64DecodingErrors);
    if (raw.isEmpty() && !o["mask"].toString().isEmpty())
      return Status::failure(where + "/mask: not base64");
    const int width = size[0].toInt(), height = size[1].toInt();
    const std::uint64_t pixels = static_cast<std::uint64_t>(std::max(width, 0)) *
                                 static_cast<std::uint64_t>(std::max(height, 0));
    if (pixels > kMaxMaskPixels)
      return Status::failure(where + "/size: " + std::to_string(width) + "x" +
                             std::to_string(height) + " is larger than the 2^30-pixel limit of a mask");
    const auto covered = pixelsCoveredByRuns(raw);
    if (!covered) return Status::failure(where + "/mask: truncated or malformed run lengths");
    if (pixels > 0 && *covered != pixels)
      return Status::failure(where + "/mask: runs cover " + std::to_string(*covered) + " of " +
                             std::to_string(pixels) + " pixels");
    const std::vector<uint8_t> runs(raw.begin(), raw.end());
    Result<RegionMask> mask = decodeMaskRuns(runs, width, height, where + "/mask");
    if (!mask) return mask.status;
    l.mask = std::move(*mask.value);
    const QJsonArray anchors = o["anchors"].toArray();
    if (anchors.size() > DepthModel::kAnchorCount)
      return Status::failure(where + "/anchors: at most 3 depth points");
    for (qsizetype k = 0; k < anchors.size(); ++k) {
      const QJsonObject a = anchors[k].toObject();
      const auto pixel = readPoint(a["pixel"]);
      const double z = a["depth"].toDouble(-1.0);
      const std::string at = where + "/anchors/" + std::to_string(k);
      if (!pixel) return Status::failure(at + "/pixel: expected [x, y]");
      if (!(z > 0.0) || !std::isfinite(z))
        return Status::failure(at + "/depth: expected a number greater than 0");
      l.anchors.push_back({*pixel, z});
    }
    p.depth_layers.push_back(std::move(l));
  }
  if (depth.contains("map")) {
    const QJsonObject m = depth["map"].toObject();
    DepthMapRef ref;
    const QString path = m["path"].toString();
    if (path.isEmpty()) return Status::failure(name + ": /depth/map/path: missing");
    ref.path = pathFromFile(path, project_path);
    ref.options.scale = m["scale"].toDouble(1.0);
    if (!(ref.options.scale > 0.0) || !std::isfinite(ref.options.scale))
      return Status::failure(name + ": /depth/map/scale: expected a number greater than 0");
    ref.options.inverse = m["inverse"].toBool(false);
    p.depth_map = ref;
  }
  return Status::success();
}

}  // namespace

QByteArray projectToJson(const Project& project, const QString& project_path) {
  QJsonObject root;
  root["format"] = "artcam-studio-project";
  const bool has_depth = !project.depth_layers.empty() || project.depth_map.has_value();
  // Parts need version 2 too: an older studio would drop them silently on its next save.
  const bool needs_v2 = has_depth || !project.parts.isEmpty();
  root["version"] = needs_v2 ? kProjectFormatVersion : kProjectVersionWithoutDepth;
  if (!project.parts.isEmpty()) root["parts"] = project.parts;
  root["photo"] = pathForFile(project.photo_path, project_path);
  root["model"] = QString::fromUtf8(modelClassName(project.model).data(),
                                    static_cast<qsizetype>(modelClassName(project.model).size()));
  QJsonArray pairs;
  for (const Pair& p : project.pairs) {
    QJsonObject o;
    o["source"] = point(p.source);
    o["target"] = point(p.target);
    o["enabled"] = p.enabled;
    pairs.append(o);
  }
  root["pairs"] = pairs;
  if (project.manual_camera) {
    const std::string text = toArtcamJson(Artcam(*project.manual_camera));
    root["camera"] = QJsonDocument::fromJson(QByteArray::fromStdString(text)).object();
  }
  QJsonObject view;
  view["scale"] = project.view.scale;
  view["centre"] = QJsonArray{project.view.centre.x(), project.view.centre.y()};
  view["preview_mode"] = project.view.preview_mode;
  view["opacity"] = project.view.opacity;
  const CanvasViewState& c = project.view.canvas;
  view["canvas"] = QJsonObject{{"mode", canvasViewModeName(c.mode)},
                               {"compare_mode", canvasViewModeName(c.compare_mode)},
                               {"split", c.split},
                               {"onion_opacity", c.onion_opacity}};
  root["view"] = view;
  if (has_depth) root["depth"] = depthToJson(project, project_path);
  // QJson writes doubles with enough digits to read back exactly (shortest round-trip form).
  return QJsonDocument(root).toJson(QJsonDocument::Indented);
}

Result<Project> parseProject(const QByteArray& json, const QString& project_path) {
  const std::string name = str(QFileInfo(project_path).fileName());
  QJsonParseError error{};
  const QJsonDocument doc = QJsonDocument::fromJson(json, &error);
  if (error.error != QJsonParseError::NoError)
    return Result<Project>::failure(name + ": not valid JSON at offset " +
                                    std::to_string(error.offset) + ": " + str(error.errorString()));
  const QJsonObject root = doc.object();
  if (root["format"].toString() != "artcam-studio-project")
    return Result<Project>::failure(name + ": /format: not an ARTcam Studio project");
  const int version = root["version"].toInt(-1);
  if (version < 1) return Result<Project>::failure(name + ": /version: missing or not a number");
  if (version > kProjectFormatVersion)
    return Result<Project>::failure(name + ": written by a newer ARTcam Studio (project version " +
                                    std::to_string(version) + "; this one reads up to " +
                                    std::to_string(kProjectFormatVersion) + ")");
  Project p;
  const QString photo = root["photo"].toString();
  if (photo.isEmpty()) return Result<Project>::failure(name + ": /photo: missing photo path");
  p.photo_path = pathFromFile(photo, project_path);
  const auto model = modelClassFromName(str(root["model"].toString("auto")));
  if (!model)
    return Result<Project>::failure(name + ": /model: unknown model " +
                                    quoted(root["model"].toString()));
  p.model = *model;
  const QJsonArray pairs = root["pairs"].toArray();
  for (qsizetype i = 0; i < pairs.size(); ++i) {
    const QJsonObject o = pairs[i].toObject();
    const auto s = readPoint(o["source"]);
    const auto t = readPoint(o["target"]);
    const std::string where = name + ": /pairs/" + std::to_string(i);
    if (!s) return Result<Project>::failure(where + "/source: expected [x, y]");
    if (!t) return Result<Project>::failure(where + "/target: expected [x, y]");
    p.pairs.push_back({*s, *t, o["enabled"].toBool(true)});
  }
  if (root.contains("camera")) {
    const QByteArray text = QJsonDocument(root["camera"].toObject()).toJson(QJsonDocument::Compact);
    Result<Artcam> cam = parseArtcam(text.toStdString(), name + ": /camera");
    if (!cam) return Result<Project>::failure(cam.status.message);
    if (cam->layers.size() != 1 || cam->pieces)
      return Result<Project>::failure(name + ": /camera: expected one camera, found a " +
                                      std::string(artcamKindName(cam->kind())) + " camera");
    p.manual_camera = cam->main();
  }
  const QJsonObject view = root["view"].toObject();
  p.view.scale = view["scale"].toDouble(0.0);
  const auto centre = readPoint(view["centre"]);
  if (centre) p.view.centre = QPointF(centre->x(), centre->y());
  p.view.preview_mode = view["preview_mode"].toInt(0);
  p.view.opacity = view["opacity"].toDouble(0.5);
  // The view is restored as it is read (the mode becomes an enum, the scale a zoom), so values no
  // studio writes are refused here rather than turned into a broken view.
  if (!(p.view.scale >= 0.0) || !std::isfinite(p.view.scale))
    return Result<Project>::failure(name + ": /view/scale: expected a number ≥ 0");
  if (p.view.preview_mode < 0 || p.view.preview_mode > static_cast<int>(PreviewMode::WarpedOnly))
    return Result<Project>::failure(name + ": /view/preview_mode: expected 0 to " +
                                    std::to_string(static_cast<int>(PreviewMode::WarpedOnly)));
  if (!(p.view.opacity >= 0.0 && p.view.opacity <= 1.0))
    return Result<Project>::failure(name + ": /view/opacity: expected a number from 0 to 1");
  // Projects written before the canvas showed the result have no "canvas": the defaults.
  if (view.contains("canvas")) {
    const QJsonObject c = view["canvas"].toObject();
    CanvasViewState& s = p.view.canvas;
    const std::pair<const char*, CanvasViewMode*> modes[] = {{"mode", &s.mode},
                                                             {"compare_mode", &s.compare_mode}};
    for (const auto& [key, field] : modes) {
      if (!c.contains(QLatin1String(key))) continue;
      const auto mode = canvasViewModeFromName(str(c[QLatin1String(key)].toString()));
      if (!mode)
        return Result<Project>::failure(name + ": /view/canvas/" + key +
                                        ": expected photo, result, split or onion");
      *field = *mode;
    }
    // `\` returns from the photo to compare_mode, so it is one of the result views.
    if (s.compare_mode == CanvasViewMode::Photo)
      return Result<Project>::failure(
          name + ": /view/canvas/compare_mode: expected result, split or onion");
    s.split = c["split"].toDouble(s.split);
    s.onion_opacity = c["onion_opacity"].toDouble(s.onion_opacity);
    if (!(s.split >= 0.0 && s.split <= 1.0))
      return Result<Project>::failure(name + ": /view/canvas/split: expected a number from 0 to 1");
    if (!(s.onion_opacity >= 0.0 && s.onion_opacity <= 1.0))
      return Result<Project>::failure(
          name + ": /view/canvas/onion_opacity: expected a number from 0 to 1");
  }
  if (root.contains("parts")) {
    if (!root["parts"].isObject())
      return Result<Project>::failure(name + ": /parts: expected an object of named parts");
    p.parts = root["parts"].toObject();
  }
  if (root.contains("depth")) {
    if (!root["depth"].isObject())
      return Result<Project>::failure(name + ": /depth: expected an object");
    if (const Status depth_status = parseDepth(root["depth"].toObject(), name, project_path, p);
        !depth_status)
      return Result<Project>::failure(depth_status.message);
  }
  return Result<Project>::success(std::move(p));
}

Result<Project> readProject(const QString& path) {
  QFile file(path);
  if (!file.open(QIODevice::ReadOnly))
    return Result<Project>::failure(str(path) + ": cannot open: " + str(file.errorString()));
  return parseProject(file.readAll(), path);
}

Status writeProject(const QString& path, const Project& project) {
  QSaveFile file(path);
  if (!file.open(QIODevice::WriteOnly))
    return Status::failure(str(path) + ": cannot write: " + str(file.errorString()));
  const QByteArray json = projectToJson(project, path);
  if (file.write(json) != json.size()) {
    file.cancelWriting();
    return Status::failure(str(path) + ": write failed: " + str(file.errorString()));
  }
  if (!file.commit())
    return Status::failure(str(path) + ": could not save: " + str(file.errorString()));
  return Status::success();
}

}  // namespace artcam::ui
