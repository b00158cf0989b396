// SPDX-License-Identifier: Apache-2.0
// The Insertion mode's state in a project file (Project::parts["insertion"]): grid matches,
// region, board, squares, max error, the graphic's path and placement. The graphic's pixels
// are not stored: the file is read again when the project opens.
//
//   { "board": [w, h], "squares": n, "max_error_px": e,
//     "matches": [ {"board": [x, y], "photo": [x, y]}, … ],
//     "region": [[x, y], …], "graphic": "/abs/path.png", "placement": {"origin": [x, y], "width": w} }
#pragma once

#include "core/model/status.h"
#include "ui/matting/insertion_model.h"

#include <QJsonObject>

namespace artcam::ui {

// Empty when there is nothing to keep (no matches, no region, no graphic).
QJsonObject insertionToJson(const InsertionState& state);
// `where` prefixes messages ("project.artcamproj: /parts/insertion"). graphic stays null.
Result<InsertionState> insertionFromJson(const QJsonObject& json, const std::string& where);

}  // namespace artcam::ui
