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
// its JSON path (e.g. "/stages/0/tensors/2/1: expected 3 numbers, found 2"); a JSON syntax
// error by line and column. Unknown fields are ignored (room for additions within version 1).
//
// Decisions:
// - Tensors are kept exactly as written, symmetric or not: Q and (Q + Qᵀ)/2 are the same camera
//   (DESIGN §1), and keeping the file's numbers makes read/write round trips bit-exact.
// - Numbers round-trip bit-exactly (shortest round-trip decimal, correctly rounded on read).
//   NaN/inf are refused both ways: JSON cannot hold them, and a literal that overflows
//   (1e999) is refused on read.
// - Frame sizes are whole numbers; [0, 0] for object space. Matches hold 2 or 3 numbers per
//   side, the same for every match; "enabled" defaults to true. In "fit", "model", "matches",
//   "rms_px", "max_px" are required, the lists and "reason" optional.
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
// Throws std::invalid_argument if a number is not finite (writeArtcamFile reports it instead).
std::string toArtcamJson(const ArtcamDocument& document);
// Atomic: written beside the target, flushed, then renamed over it.
Status writeArtcamFile(const std::string& path, const ArtcamDocument& document);

// Attributed cameras (issue 6), optional fields of version 1 that older readers ignore:
//   "layers": [ { "stages": [ … ] }, … ]   more cameras with the main camera's blocks and frames;
//                                          the picture is the sum of every layer's colour
//                                          (render/attributed.h renderLayers; the paper's Fig 4)
//   "depth_output": "depth" | "blur-variance"
//                                          what the depth output means: a depth, or the blur
//                                          variance of depth of field (effects/depth_of_field.h)
// Kept apart from ArtcamDocument so the existing aggregate stays as it is.
struct ArtcamExtras {
  std::vector<Camera> layers;  // beyond document.camera
  std::string depth_output = "depth";
};
struct ArtcamEffectFile {
  ArtcamDocument document;
  ArtcamExtras extras;
  // document.camera followed by the extra layers.
  std::vector<Camera> allLayers() const;
};
Result<ArtcamEffectFile> parseArtcamEffectJson(std::string_view text, const std::string& name);
Result<ArtcamEffectFile> readArtcamEffectFile(const std::string& path);
std::string toArtcamJson(const ArtcamDocument& document, const ArtcamExtras& extras);
Status writeArtcamFile(const std::string& path, const ArtcamDocument& document,
                       const ArtcamExtras& extras);

}  // namespace artcam
