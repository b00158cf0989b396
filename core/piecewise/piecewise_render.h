// SPDX-License-Identifier: Apache-2.0
// Rendering through a piecewise camera without seams: a mesh warp.
//
// Per-patch gather would need every patch's inverse and a rule for pixels whose preimage
// falls just outside both neighbours (their cameras agree only to seam_gap_px). Instead one
// lattice of source vertices spans all patches; each vertex is mapped forward through every
// patch that holds it and the predictions are averaged, so the mesh is continuous by
// construction, and each target pixel inside a mapped triangle takes its source position from
// a quadratic triangle: the barycentric blend of the vertices' sources plus, per edge, the
// bend that puts the edge's midpoint on the exact preimage of its targets' midpoint (shared by
// the two triangles on the edge, so the mesh stays continuous). Linear triangles miss by
// ~step²·|∂²s|/8 (a 24 MP fisheye: ~0.004 px at 4 px); quadratic ones by ~step³, so a lattice
// of 32 px meets 1/256 px where the linear one needed 2 px. The step is chosen by measuring
// (chooseMeshStep), and each band of rows evaluates its triangles' positions row by row
// (a quadratic in x per row) into the warp's span sampler. Where a patch's data ends inside a
// cell (a marked wall's outline, a fitted grid's hull), the cell is drawn through that patch
// and cut at the outline pixel by pixel, so the picture ends at the outline, not at the cells
// wholly inside it.
#pragma once

#include "core/model/image.h"
#include "core/model/image_view.h"
#include "core/model/piecewise_camera.h"
#include "core/render/position_map.h"
#include "core/render/warp.h"

namespace artcam {

struct PiecewiseRenderOptions {
  // The source lattice's spacing in the camera's source pixels; 0: chosen by chooseMeshStep, a
  // step from 64 (32 where the patches leave holes) down to 2 whose measured error is within
  // max_error_px.
  double mesh_step_px = 0.0;
  double max_error_px = 1.0 / 256.0;  // source pixels of the image rendered from
  Filter filter = Filter::Bilinear;
  EdgeMode edge = EdgeMode::Transparent;  // what taps past the source's edge read (filter.h)
  int threads = 0;            // 0: every core
  bool allow_simd = true;     // the span sampler's SIMD clones (span_sampler.h)
  // The AVX-512 clones (the rasteriser's rows and the sampler's) where the CPU has them; off,
  // the AVX2 and portable code gives the same bytes (tests compare).
  bool allow_avx512 = true;
  // The output size; 0×0: the camera's target frame. Another size scales the target frame to it
  // per axis (the output-frame rule of core/pipeline/render.h).
  FrameSize output;
};

struct PiecewiseRenderStats {
  int triangles = 0;
  long long covered_pixels = 0;
  double mesh_step_px = 0.0;
  double error_px = 0.0;  // the step's estimated error (chooseMeshStep)
};

// The mesh's error, and the step that keeps it in bounds. At a point of a triangle the mesh
// gives source position m for target point t̄, and the exact preimage of t̄ lies J⁻¹ (t̄ − f(m))
// away (f the patch's map, J its Jacobian, eq 2). That distance, in pixels of the image
// rendered from, is measured where a quadratic triangle's error peaks (its centroid and its
// edges' quarter points) on every drawn triangle one patch maps, and the largest is the
// mesh's error. The error falls as the step cubed; the automatic step is found by measuring a
// 128-px probe lattice (straight to 32 px where the patches leave holes, along whose edges a
// coarse lattice would leave pixels uncovered), then the step that law predicts at 0.8 of the
// budget (64 px at most), and so on down, until one measures within the budget (2 px at the
// least): near the coarsest that passes, not always it. With a fixed step the measurement is made at it.
struct MeshChoice {
  double step_px = 0.0;
  double error_px = 0.0;
};
MeshChoice chooseMeshStep(const PiecewiseCamera& camera, FrameSize source_image, FrameSize output,
                          const PiecewiseRenderOptions& options = {});

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

// The source position renderPiecewise samples for every output pixel of an `output` render
// from a `source_image` photo (positions in its pixels): the same mesh, step and rasteriser, so
// a map of it reproduces the render exactly. Pixels no triangle covers have no preimage; the
// rest are classified by position_map.h's rule (Preimage::InPhoto or OutsidePhoto). What
// `artcam export-map` writes for a piecewise camera; kernel "piecewise mesh".
PositionMap piecewisePositionMap(const PiecewiseCamera& camera, FrameSize source_image, FrameSize output,
                                 const PiecewiseRenderOptions& options = {},
                                 PiecewiseRenderStats* stats = nullptr);

// Premultiplied "over": top (with alpha) over bottom, in place on bottom. Sizes must agree;
// bottom's channels other than alpha take top's colour channels in order.
void compositeOver(const ImageF& top, ImageF& bottom);

}  // namespace artcam
