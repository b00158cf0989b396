#include "ui/project_file.h"

#include "core/io/artcam_file.h"

#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QSaveFile>

#include <cmath>

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

}  // namespace

QByteArray projectToJson(const Project& project, const QString& project_path) {
  QJsonObject root;
  root["format"] = "artcam-studio-project";
  root["version"] = kProjectFormatVersion;
  const QDir base = QFileInfo(project_path).absoluteDir();
  const QString relative = base.relativeFilePath(project.photo_path);
  root["photo"] = relative.startsWith("..") ? project.photo_path : relative;
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
    ArtcamDocument doc;
    doc.camera = *project.manual_camera;
    const std::string text = toArtcamJson(doc);
    root["camera"] = QJsonDocument::fromJson(QByteArray::fromStdString(text)).object();
  }
  QJsonObject view;
  view["scale"] = project.view.scale;
  view["centre"] = QJsonArray{project.view.centre.x(), project.view.centre.y()};
  view["preview_mode"] = project.view.preview_mode;
  view["opacity"] = project.view.opacity;
  root["view"] = view;
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
  p.photo_path = QFileInfo(photo).isAbsolute()
                     ? photo
                     : QFileInfo(project_path).absoluteDir().absoluteFilePath(photo);
  const auto model = modelClassFromName(str(root["model"].toString("auto")));
  if (!model)
    return Result<Project>::failure(name + ": /model: unknown model \"" +
                                    str(root["model"].toString()) + "\"");
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
    Result<ArtcamDocument> cam = parseArtcamJson(text.toStdString(), name + ": /camera");
    if (!cam) return Result<Project>::failure(cam.status.message);
    p.manual_camera = cam->camera;
  }
  const QJsonObject view = root["view"].toObject();
  p.view.scale = view["scale"].toDouble(0.0);
  const auto centre = readPoint(view["centre"]);
  if (centre) p.view.centre = QPointF(centre->x(), centre->y());
  p.view.preview_mode = view["preview_mode"].toInt(0);
  p.view.opacity = view["opacity"].toDouble(0.5);
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
