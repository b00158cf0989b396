// SPDX-License-Identifier: Apache-2.0
// The colour samples in a project file (Project::parts["colour"]) and their CSV export.
//
//   { "radius": 4, "reference": "/abs/reference.tif",
//     "samples": [ {"source": [x, y], "reference": [x, y], "enabled": true}, … ],
//     "colour_block": { ….artcam document of the fitted colour camera… } }   // optional
//
// The reference photo's pixels are not stored: the file is read again when the project opens.
// The CSV is what `artcam fit --block colour` reads (core/io/matches_csv.h): the header
// `src_r,src_g,src_b,dst_r,dst_g,dst_b` (plus `enabled` when a sample is disabled), linear
// light, %.17g, written atomically.
#pragma once

#include "core/model/camera.h"
#include "core/model/fit_record.h"
#include "core/model/status.h"
#include "ui/colour/colour_samples.h"

#include <QJsonObject>

#include <optional>
#include <string>
#include <vector>

namespace artcam::ui {

struct ColourProjectPart {
  ColourSampleState state;  // reference stays null: only its path is kept
  std::optional<Camera> colour_block;
};

// Empty when there is nothing to keep (no samples, no reference, no colour block).
QJsonObject colourPartToJson(const ColourSampleState& state, const std::optional<Camera>& block);
// `where` prefixes messages ("p.artcamproj: /parts/colour").
Result<ColourProjectPart> colourPartFromJson(const QJsonObject& json, const std::string& where);


}  // namespace artcam::ui
