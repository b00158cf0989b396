// SPDX-License-Identifier: Apache-2.0
// Rendering through a piecewise camera without seams: a mesh warp.
//
// Per-patch gather would need every patch's inverse and a rule for pixels whose preimage
// falls just outside both neighbours (their cameras agree only to seam_gap_px). Instead one
// lattice of source vertices spans all patches; each vertex is mapped forward through every
// patch that holds it and the predictions are averaged, so the mesh is continuous by
// construction, and each target pixel inside a mapped triangle takes its source position by
// barycentric interpolation (piecewise linear in the target; error ~ step²·|∇²f|/8, measured
// in the tests at well under 1/100 px for step 4 on the sample lenses).
#pragma once

#include "core/model/image.h"
#include "core/model/image_view.h"
#include "core/model/piecewise_camera.h"
#include "core/render/warp.h"

namespace artcam {

struct PiecewiseRenderOptions {
  double mesh_step_px = 4.0;  // source lattice spacing
  Filter filter = Filter::Bilinear;
  int threads = 0;            // 0: every core
  bool allow_simd = true;     // the span sampler's SIMD clones (span_sampler.h)
  // The output size; 0×0: the camera's target frame. Another size scales the target frame to it
  // per axis (the output-frame rule of core/pipeline/render.h).
  FrameSize output;
};

struct PiecewiseRenderStats {
  int triangles = 0;
  long long covered_pixels = 0;
};

// The source (premultiplied linear float, as ImageF) seen through the camera, on the target
// frame (or options.output). The result always has an alpha channel (last): coverage times the source's alpha;
// pixels no patch reaches are transparent black, never NaN. The source image may have any
// size: source pixel coordinates of the camera are scaled to it.
ImageF renderPiecewise(const ImageF& source, const PiecewiseCamera& camera,
                       const PiecewiseRenderOptions& options = {},
                       PiecewiseRenderStats* stats = nullptr);

// The same on typed views, the photo as stored (8-bit, 16-bit or float): `out` gives the size
// (options.output is ignored) and has the source's type with its channels, or one more (alpha,
// last) when the source has none, as for warpImage. The mesh is rasterised band by band of
// output rows into source positions, which the gather warp's span sampler reads: the mesh
// decides where, the sampler how, so the filters are the warp's.
void renderPiecewise(const ConstImageView& source, const PiecewiseCamera& camera, const ImageView& out,
                     const PiecewiseRenderOptions& options = {}, PiecewiseRenderStats* stats = nullptr);

// Premultiplied "over": top (with alpha) over bottom, in place on bottom. Sizes must agree;
// bottom's channels other than alpha take top's colour channels in order.
void compositeOver(const ImageF& top, ImageF& bottom);

}  // namespace artcam
