// SPDX-License-Identifier: Apache-2.0
// The studio's side of the project file: core's reader and writer (core/project/studio_project.h,
// the one that `artcam export` uses too) with the studio's types — QString paths, the document's
// pairs, straight lines and depth layers, and the view state and mode parts as Qt JSON. Saved
// atomically. Every field of core's project passes through both ways: one left out here would be
// dropped by the next save of a project opened in the studio.
//
// The view state ("view") is read here, because only the studio uses it:
//   { "scale": s, "centre": [x, y], "preview_mode": 0, "opacity": 0.5,
//     "canvas": {"mode": "result", "compare_mode": "result", "split": 0.5,
//                "onion_opacity": 0.5} }     // canvas: optional, defaults as shown
// Values no studio writes are refused rather than turned into a broken view.
#pragma once

#include "core/fit/fit_image.h"
#include "core/model/status.h"
#include "core/project/studio_project.h"
#include "ui/canvas_view_mode.h"
#include "ui/document.h"

#include <QPointF>
#include <QJsonObject>
#include <QString>

#include <optional>
#include <vector>

namespace artcam::ui {

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
  // The size the pairs, lines and masks were made on: written from the photo, read back as
  // core's projectPhotoSize (recorded, else the masks' or the hand-set camera's); none: unknown.
  std::optional<FrameSize> photo_size;
  std::vector<Pair> pairs;
  std::vector<LineTrace> lines;  // finished lines only: the open one is not saved
  ModelClass model = ModelClass::Auto;
  LineModel line_model = LineModel::Auto;
  std::optional<Artcam> manual_camera;
  std::vector<EffectStep> effects;
  ViewState view;
  std::vector<DepthPlaneLayer> depth_layers;
  std::optional<DepthMapRef> depth_map;
  // The second image the compositing effects read (absolute once read; loaded by the session).
  std::optional<QString> second_path;
  std::string finish;  // marks after the render, "" for none
  // Named parts the studio's modes contribute (e.g. "insertion"), kept as JSON so this file
  // need not know them; written as "parts" only when there are some (version 2).
  QJsonObject parts;
};

// The photo path is written relative to the project's folder when it lies beneath it.
QByteArray projectToJson(const Project& project, const QString& project_path);
Result<Project> parseProject(const QByteArray& json, const QString& project_path);
Result<Project> readProject(const QString& path);
Status writeProject(const QString& path, const Project& project);
// A photo of `photo` pixels at `photo_path` in place of the project's: a one-line refusal
// naming the project (`project_path`), the photo and both sizes when project.photo_size differs.
Status checkPhotoSize(const Project& project, FrameSize photo, const QString& photo_path,
                      const QString& project_path);

}  // namespace artcam::ui
