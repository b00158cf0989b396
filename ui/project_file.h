// SPDX-License-Identifier: Apache-2.0
// The project file: JSON with the photo path, the pairs (photo pixels), the model,
// an optional hand-made camera (as .artcam JSON) and the view state, so a session reopens as
// it was. Saved atomically through QSaveFile (written aside, then renamed).
//
//   { "format": "artcam-studio-project", "version": 1,
//     "photo": "relative/or/absolute/path.png",
//     "model": "auto",
//     "pairs": [ {"source": [x, y], "target": [x, y], "enabled": true}, … ],
//     "camera": { ….artcam document… },          // optional: camera set by hand
//     "view": { "scale": s, "centre": [x, y], "preview_mode": 0, "opacity": 0.5,
//               "canvas": {"mode": "result", "compare_mode": "result", "split": 0.5,
//                          "onion_opacity": 0.5} },  // canvas: optional, defaults as shown
//     "depth": {                                    // optional: depth planes and map (v2)
//       "layers": [ {"name": "Plane 1", "size": [w, h], "mask": "<base64 of run bytes>",
//                    "anchors": [ {"pixel": [x, y], "depth": z}, … ] }, … ],
//       "map": {"path": "depth.exr", "scale": 1, "inverse": false} } }
//
// Versions: a project with depth data is written as version 2, one without as version 1, so an
// older studio (which reads up to 1) refuses a project whose depth it would silently drop, and
// still opens every project it can represent fully. This reader takes 1 and 2. Masks are
// run-length bytes (core/depth/region_mask.h) in base64.
#pragma once

#include "core/fit/fit_image.h"
#include "core/model/status.h"
#include "ui/canvas_view_mode.h"
#include "ui/document.h"

#include <QPointF>
#include <QJsonObject>
#include <QString>

#include <optional>
#include <vector>

namespace artcam::ui {

inline constexpr int kProjectFormatVersion = 2;      // the newest this code reads and writes
inline constexpr int kProjectVersionWithoutDepth = 1;  // written when there is no depth data
inline constexpr char kProjectExtension[] = "artcamproj";

struct ViewState {
  double scale = 0.0;  // 0: fit to window
  QPointF centre;
  int preview_mode = 0;  // the Preview dock's (preview_view.h)
  double opacity = 0.5;
  CanvasViewState canvas;  // the main canvas's photo/result mode
};

// The depth map file a project refers to (loaded by the session, off the GUI thread).
struct DepthMapRef {
  QString path;  // absolute once read
  DepthFileOptions options;
};

struct Project {
  QString photo_path;  // absolute once read
  std::vector<Pair> pairs;
  ModelClass model = ModelClass::Auto;
  std::optional<Camera> manual_camera;
  ViewState view;
  std::vector<DepthPlaneLayer> depth_layers;
  std::optional<DepthMapRef> depth_map;
  // Named parts the studio's modes contribute (e.g. "insertion"), kept as JSON so this file
  // need not know them; written as "parts" only when there are some (version 2).
  QJsonObject parts;
};

// The photo path is written relative to the project's folder when it lies beneath it.
QByteArray projectToJson(const Project& project, const QString& project_path);
Result<Project> parseProject(const QByteArray& json, const QString& project_path);
Result<Project> readProject(const QString& path);
Status writeProject(const QString& path, const Project& project);

}  // namespace artcam::ui
