// SPDX-License-Identifier: Apache-2.0
// The .artcam file: JSON, versioned, the one reader and the one writer of the camera value
// (core/model/artcam.h). Numbers are written so they read back bit-exactly.
//
//   { "format": "artcam", "version": 1,
//     "blocks": [ {"kind": "position", "size": 3}, … ],
//     "frames": { "source": [w, h], "target": [w, h] },   // pixels; tensors are normalised
//     "stages": [ { "tensors": [ [[…N numbers…] ×N rows] ×N tensors ] }, … ],
//     "layers": [ { "stages": [ … ] }, … ],              // optional: layers after the first
//     "depth_output": "depth" | "blur-variance",         // optional, default "depth"
//     "frame": "sensor" | "upright",                       // optional: the raster it was made
//                                                          // for (core/pipeline/camera_frame.h)
//     "matches": [ {"source": [x, y], "target": [X, Y], "enabled": true}, … ],  // optional
//     "fit": { "model": …, "matches": …, "rms_px": …, "max_px": …, "residuals_px": […],
//              "singular_values": […], "reason": … },                          // optional
//     "support_margin_px": m,                              // optional, with "patches"
//     "patches": [ { "rect": [x0, y0, x1, y1],           // source pixels
//                    "support": [[x, y], …],              // hull of its matches (optional)
//                    "model": "quadratic", "matches": n, "rms_px": …, "max_px": …,
//                    "camera": { format, version, blocks, frames, stages } }, … ] }
//
// A newer version is refused with a clear message; a missing or malformed field is named by
// its JSON path (e.g. "/stages/0/tensors/2/1: expected 3 numbers, found 2"); a JSON syntax
// error by line and column. Unknown fields are ignored (room for additions within version 1).
// What parses but breaks the camera's invariants (validateArtcam: zero stages, overlapping
// patches, patches outside the frame, more than kMaxPatches) is refused on read and on write.
//
// Decisions:
// - One JSON parse per file: layers, patches and their embedded cameras are read from the same
//   tree with their paths.
// - A piecewise camera keeps its single-camera fit at the top level, so the file is still a
//   complete camera for a reader that ignores "patches" (an older build).
// - Tensors are kept exactly as written, symmetric or not: Q and (Q + Qᵀ)/2 are the same
//   camera, and keeping the file's numbers makes read/write round trips bit-exact.
// - Numbers round-trip bit-exactly (shortest round-trip decimal, correctly rounded on read).
//   NaN/inf are refused both ways: JSON cannot hold them, and a literal that overflows
//   (1e999) is refused on read.
// - Frame sizes are whole numbers; [0, 0] for object space. Matches hold 2 or 3 numbers per
//   side, the same for every match; "enabled" defaults to true. In "fit", "model", "matches",
//   "rms_px", "max_px" are required, the lists and "reason" optional.
#pragma once

#include "core/model/artcam.h"
#include "core/model/status.h"

#include <string>
#include <string_view>

namespace artcam {

inline constexpr int kArtcamFormatVersion = 1;

// `name` is used in error messages ("CAM.artcam: /frames/source: expected [w, h]").
Result<Artcam> parseArtcam(std::string_view text, const std::string& name);
Result<Artcam> readArtcam(const std::string& path);
// Throws std::invalid_argument if a number is not finite (writeArtcam reports it instead).
std::string toArtcamJson(const Artcam& camera);
// Validates, then writes atomically: beside the target, flushed, then renamed over it.
Status writeArtcam(const std::string& path, const Artcam& camera);

}  // namespace artcam
