// SPDX-License-Identifier: Apache-2.0
// What the main canvas shows: the photo, the warped result, a wipe between them, or the result
// over the photo (onion skin). The result is in the target frame, which for studio documents is
// the photo's frame (same pixel size), so every mode draws into the same image rectangle with
// the same ViewTransform; zoom, pan, the loupe and the pairs never move when the mode changes.
// The canvas's decisions about editing in each mode are in canvas.h.
#pragma once

#include <algorithm>
#include <cmath>
#include <optional>
#include <string_view>

namespace artcam::ui {

enum class CanvasViewMode { Photo = 0, Result = 1, Split = 2, Onion = 3 };

struct CanvasViewState {
  // Result by default: the warped photo is what the user is making (Photoshop shows the
  // result and toggles to the original with `\`).
  CanvasViewMode mode = CanvasViewMode::Result;
  // Where `\` goes back to from Photo: the last mode that showed the result.
  CanvasViewMode compare_mode = CanvasViewMode::Result;
  // Split: the wipe's divider as a fraction of the canvas WIDGET's width (not of the image), so
  // it stays on screen at any zoom and pan. Photo left of it, result right.
  double split = 0.5;
  // Onion: the result's opacity over the photo, [0, 1].
  double onion_opacity = 0.5;

  bool operator==(const CanvasViewState&) const = default;
};

// `\`: Photo ↔ the last mode that showed the result ("before/after").
inline CanvasViewState toggledBeforeAfter(CanvasViewState s) {
  if (s.mode == CanvasViewMode::Photo) {
    s.mode = s.compare_mode;
  } else {
    s.compare_mode = s.mode;
    s.mode = CanvasViewMode::Photo;
  }
  return s;
}

// Sets the mode, remembering a result-showing mode for `\`.
inline CanvasViewState withMode(CanvasViewState s, CanvasViewMode mode) {
  s.mode = mode;
  if (mode != CanvasViewMode::Photo) s.compare_mode = mode;
  return s;
}

inline double clampedFraction(double f) { return std::isnan(f) ? 0.5 : std::clamp(f, 0.0, 1.0); }

// Names used in project files ("view": {"canvas": {"mode": "result", …}}).
inline const char* canvasViewModeName(CanvasViewMode m) {
  switch (m) {
    case CanvasViewMode::Photo:
      return "photo";
    case CanvasViewMode::Result:
      return "result";
    case CanvasViewMode::Split:
      return "split";
    case CanvasViewMode::Onion:
      return "onion";
  }
  return "result";
}

inline std::optional<CanvasViewMode> canvasViewModeFromName(std::string_view name) {
  for (CanvasViewMode m : {CanvasViewMode::Photo, CanvasViewMode::Result, CanvasViewMode::Split,
                           CanvasViewMode::Onion})
    if (name == canvasViewModeName(m)) return m;
  return std::nullopt;
}

}  // namespace artcam::ui
