// SPDX-License-Identifier: Apache-2.0
// Depth of field (the paper's §3): a spatially varying Gaussian whose sigma is a
// camera stage of depth.
//
// The camera, over [position 3 | colour 4 | depth 2], keeps position and colour and maps depth
// to the blur VARIANCE in normalised units² (frames.h: the larger image side spans 2). The
// paper's §3 makes σ proportional to depth and notes that "under ARTcam control the changes can
// be non-linear"; both are one stage, the output d/d_h of eqs (1)/(5) on the depth block:
//   σ²(d) = (d Q_d dᵀ) / (d Q_h dᵀ) = k²·(d − f)² / ((1 − γ)·f + γ·d)²,
// a ratio of quadratics in (d, 1). γ = thin_lens:
// - γ = 1, thin lens: σ = k·|d − f|/d, the circle of confusion A·|z − z_f|/z — zero at the
//   focus depth f, k at infinity, k·(f/d − 1) in front (proportional to |1/f − 1/d|);
// - γ = 0, linear: σ = k·|d − f|/f, proportional to the distance from the focal plane, with the
//   thin lens's slope k/f at the focus but growing without bound behind it;
// - between, the denominator blends the two (still positive for d > 0);
// - f = 0 with γ = 0: σ = k·d, blur proportional to depth — the paper's own form (the
//   denominator is then d_h² = 1, and k is σ per depth unit). A thin lens focused at 0 would
//   blur every depth alike, so f = 0 requires γ = 0.
// A pixel without depth (d = 0, a hole of the depth file) gets σ = k/(1 − γ): the thin lens's
// 0/0 is not finite and the renderer leaves it sharp.
// In output pixels σ_px = √σ² · max(w, h)/2.
//
// Halo rule (both blurs): a sample y contributes to output pixel x only if σ_y ≥ halo_ratio·σ_x.
// A sharp foreground (σ ≈ 0) in front of a blurred background therefore does not smear into
// it (the background's blur must not see what stands in front of it), while a blurred
// foreground still spreads over its surroundings. halo_ratio = 0 is the plain varying blur.
//
// exactBlur: per output pixel, the Gaussian of its own σ, truncated at 3σ, normalised by the
// weights of the samples it uses (inside the image, passing the halo rule): O(σ²) per pixel.
// stackBlur (fast): blurs at levels σ_0 = 0 < σ_1 = first_level < … (ratio `level_ratio`), each separable
// and masked by the halo rule at that level; each pixel blends its two bracketing levels with
// the weight that matches its variance: t = (σ² − σ_L²)/(σ_{L+1}² − σ_L²).
// blur_stack.cpp says how it stays fast at 24 Mpix (coarse levels on shrunk copies, fine levels
// band by band over the columns that need them, one blending pass).
#pragma once

#include "core/model/camera.h"
#include "core/model/image.h"

#include <functional>

namespace artcam {

struct DepthOfFieldParams {
  double focus = 2.0;  // depth in focus, f (same unit as the depth image); 0: σ = k·d (γ = 0)
  double blur = 0.01;  // k: σ at infinite depth (thin lens), normalised units (× max(w, h)/2 px)
  double thin_lens = 1.0;  // γ in [0, 1]: 1 thin lens σ ∝ |d − f|/d, 0 linear σ ∝ |d − f|/f
};
Camera depthOfFieldCamera(const DepthOfFieldParams& p, FrameSize source, FrameSize target);

// σ in output pixels from the camera's depth output (the variance, attributed.h's depth image).
ImageF sigmaPixelsFromVariance(const ImageF& variance, double max_sigma_px = 64.0);

struct BlurOptions {
  double halo_ratio = 0.5;
  double level_ratio = 1.41421356237;  // stackBlur: σ_{L+1}/σ_L
  double min_sigma = 0.3;              // below this a pixel is left sharp (both blurs)
  double first_level = 0.5;            // stackBlur: σ_1; below it pixels blend with the sharp image
  // stackBlur: levels of σ ≥ this blur a 2× (4×, …) box-shrunk copy, keeping σ ≥ this/2 there.
  double shrink_from_sigma = 2.0;
  int threads = 0;
  std::function<bool(double)> progress;  // return false to cancel (empty result)
};

// `rgba`: premultiplied RGBA (4 channels); `sigma_px`: 1 channel of the same size.
ImageF exactBlur(const ImageF& rgba, const ImageF& sigma_px, const BlurOptions& options = {});
ImageF stackBlur(const ImageF& rgba, const ImageF& sigma_px, const BlurOptions& options = {});

}  // namespace artcam
