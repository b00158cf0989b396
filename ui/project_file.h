// The project file (DESIGN §5): JSON with the photo path, the pairs (photo pixels), the model,
// an optional hand-made camera (as .artcam JSON) and the view state, so a session reopens as
// it was. Saved atomically through QSaveFile (written aside, then renamed).
//
//   { "format": "artcam-studio-project", "version": 1,
//     "photo": "relative/or/absolute/path.png",
//     "model": "auto",
//     "pairs": [ {"source": [x, y], "target": [x, y], "enabled": true}, … ],
//     "camera": { ….artcam document… },          // optional: camera set by hand
//     "view": { "scale": s, "centre": [x, y], "preview_mode": 0, "opacity": 0.5 } }
#pragma once

#include "core/fit/fit_image.h"
#include "core/model/status.h"
#include "ui/document.h"

#include <QPointF>
#include <QString>

#include <optional>
#include <vector>

namespace artcam::ui {

inline constexpr int kProjectFormatVersion = 1;
inline constexpr char kProjectExtension[] = "artcamproj";

struct ViewState {
  double scale = 0.0;  // 0: fit to window
  QPointF centre;
  int preview_mode = 0;
  double opacity = 0.5;
};

struct Project {
  QString photo_path;  // absolute once read
  std::vector<Pair> pairs;
  ModelClass model = ModelClass::Auto;
  std::optional<Camera> manual_camera;
  ViewState view;
};

// The photo path is written relative to the project's folder when it lies beneath it.
QByteArray projectToJson(const Project& project, const QString& project_path);
Result<Project> parseProject(const QByteArray& json, const QString& project_path);
Result<Project> readProject(const QString& path);
Status writeProject(const QString& path, const Project& project);

}  // namespace artcam::ui
