// Piecewise cameras in .artcam files (DESIGN §5: "stages or patches of tensors").
//
//   { …an ordinary .artcam document: the single camera fitted to all the matches…,
//     "support_margin_px": m,                               // how far beyond a hull
//     "patches": [ { "rect": [x0, y0, x1, y1],            // source pixels
//                    "support": [[x, y], …],               // hull of its matches (optional)
//                    "model": "quadratic", "matches": n, "rms_px": …, "max_px": …,
//                    "camera": { …an embedded .artcam document… } }, … ] }
//
// Decision: the top level stays a complete version-1 document holding the single-camera fit,
// so every reader of plain .artcam files (older builds, `artcam info`, the studio's import)
// still opens the file and gets the best single camera; "patches" is an addition within
// version 1, which readers that do not know it ignore.
#pragma once

#include "core/io/artcam_file.h"
#include "core/model/status.h"
#include "core/model/piecewise_camera.h"

#include <optional>
#include <string>
#include <string_view>

namespace artcam {

struct PiecewiseDocument {
  ArtcamDocument whole;                   // the single camera (and matches, fit record)
  std::optional<PiecewiseCamera> pieces;  // empty: a plain .artcam file
};

Result<PiecewiseDocument> readPiecewiseFile(const std::string& path);
// The same on text in memory; `name` stands for the file in messages.
Result<PiecewiseDocument> parsePiecewiseJson(std::string_view text, const std::string& name);
Status writePiecewiseFile(const std::string& path, const PiecewiseDocument& document);

}  // namespace artcam
