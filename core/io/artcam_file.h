// The .artcam file (DESIGN §5): JSON, versioned, numbers written so they read back bit-exactly.
//
//   { "format": "artcam", "version": 1,
//     "blocks": [ {"kind": "position", "size": 3}, … ],
//     "frames": { "source": [w, h], "target": [w, h] },   // pixels; tensors are normalised
//     "stages": [ { "tensors": [ [[…N numbers…] ×N rows] ×N tensors ] }, … ],
//     "matches": [ {"source": [x, y], "target": [X, Y], "enabled": true}, … ],  // optional
//     "fit": { "model": …, "matches": …, "rms_px": …, "max_px": …, "residuals_px": […],
//              "singular_values": […], "reason": … } }                            // optional
//
// A newer version is refused with a clear message; a missing or malformed field is named by
// its JSON path (e.g. "/stages/0/tensors/2/1: expected 3 numbers, found 2").
#pragma once

#include "core/model/camera.h"
#include "core/model/fit_record.h"
#include "core/model/status.h"

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace artcam {

inline constexpr int kArtcamFormatVersion = 1;

struct ArtcamDocument {
  Camera camera;
  std::vector<PointMatch> matches;
  std::optional<FitRecord> fit;
};

// `name` is used in error messages ("CAM.artcam: /frames/source: expected [w, h]").
Result<ArtcamDocument> parseArtcamJson(std::string_view text, const std::string& name);
Result<ArtcamDocument> readArtcamFile(const std::string& path);
std::string toArtcamJson(const ArtcamDocument& document);
// Atomic: written beside the target, flushed, then renamed over it.
Status writeArtcamFile(const std::string& path, const ArtcamDocument& document);

}  // namespace artcam
