// Gather warp of an image through a position camera (DESIGN §3).
//
// For each output pixel centre (x + 0.5, y + 0.5) the source point is found through the
// inverse map: exact for identity/translation/affine/homography cameras (from the structure
// analysis), otherwise seeded by a fitted inverse camera and refined per pixel by Newton with
// a residual check. Pixels with no preimage (outside the source, folded, beyond the pole
// curve x Q_n xᵀ = 0) are transparent: all channels 0 and alpha 0. Never NaN.
//
// Frames: the camera's tensors are normalised, so the source image may be any resolution of
// the photo the camera was made on, and the output any resolution of its target frame.
#pragma once

#include "core/model/camera.h"
#include "core/model/image.h"

#include <functional>
#include <string>

namespace artcam {

enum class Filter { Nearest, Bilinear, Bicubic };
std::string_view filterName(Filter filter);
std::optional<Filter> filterFromName(std::string_view name);

struct WarpOptions {
  Filter filter = Filter::Bilinear;
  int width = 0;   // output size; 0×0: the camera's target frame size
  int height = 0;
  int threads = 0;  // 0: all cores
  // Called between tiles with the fraction done; return false to cancel.
  std::function<bool(double)> progress;
  // Newton: a pixel whose forward-mapped preimage misses its centre by more than this
  // (output pixels) has no preimage.
  double residual_tolerance_px = 1e-3;
};

struct WarpSummary {
  bool cancelled = false;
  std::string kernel;          // "identity", "affine", "homography", "rational", …
  long long transparent_pixels = 0;
  double render_ms = 0.0;
};

// The output has the source's channels, plus an alpha channel if the source had none.
ImageF warpImage(const ImageF& source, const Camera& camera, const WarpOptions& options = {},
                 WarpSummary* summary = nullptr);

}  // namespace artcam
