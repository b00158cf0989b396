// SPDX-License-Identifier: Apache-2.0
// Forward (splat) rendering for ARTcams whose positions depend on colour or depth (pc/cp
// coupling into the position outputs, e.g. the paper's eq 8/9 colour shift): the gather warp
// cannot invert them.
//
// Reconstruction: the source pixel centres, mapped forward one by one with their own colour
// and depth (eq 3, 5), are the vertices of a triangle mesh (two triangles per 2×2 block of
// neighbouring centres). Each triangle is rasterised with its vertices' output attributes
// interpolated linearly (barycentric): a triangle of at least ¼ output pixel is read at
// pixel centres (weight S²), a smaller one at S×S sub-samples per output pixel (weight 1). So:
// - no cracks: neighbouring triangles share edges whatever the map does to them, so a smooth
//   magnifying map leaves no holes (the mesh is the map's piecewise-linear interpolant);
// - no moiré where the map minifies: every triangle covering a sub-sample contributes, and
//   the S×S sub-samples are averaged (a box prefilter over the output pixel);
// - no extra blur where it does not: an identity map returns the source exactly;
// - the same reconstruction as the gather's bilinear filter for geometry-only cameras (linear
//   on triangles vs bilinear on quads), so the two agree where both apply.
// A ring of vertices one pixel outside the source carries transparent colour (placed by the
// nearest source pixel's colour, so colour-driven positions stay defined), which gives the
// same fading border as the gather's "outside is transparent" convention (sampling.h).
//
// Normalisation and alpha: per output pixel, with C the weighted sum of the interpolated
// premultiplied colours over the covering (sample, triangle) pairs and n their weight, the pixel is
// C / max(n, S²): a pixel half covered gets half the alpha (alpha from coverage); folds, where
// several layers of the mesh land on one sub-sample, average instead of adding up.
//
// Poles and invalid points: a triangle is dropped when a vertex has no finite position or the
// position weights q_h of its vertices differ in sign (it would straddle the pole curve and
// stretch across the frame).
#pragma once

#include "core/model/camera.h"
#include "core/model/image.h"
#include "core/render/attributed.h"

#include <functional>

namespace artcam {

struct SplatOptions {
  int supersample = 3;  // S: sub-samples per output pixel side, 1..8
  int threads = 0;      // mapping the vertices runs on all cores; rasterising on one
  std::function<bool(double)> progress;  // return false to cancel
};

struct SplatSummary {
  bool cancelled = false;
  long long transparent_pixels = 0;
  long long dropped_triangles = 0;  // invalid vertex or straddling a pole
};

// `rgba`: premultiplied RGBA (rgbaFromImage); `depth` as renderAttributed takes it (may be
// null unless the camera has a depth block). Output of out_px pixels.
AttributedImage splatImage(const ImageF& rgba, const ImageF* depth, const Camera& camera,
                           FrameSize out_px, const SplatOptions& options = {},
                           SplatSummary* summary = nullptr);

}  // namespace artcam
