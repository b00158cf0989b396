// SPDX-License-Identifier: Apache-2.0
// Forward (splat) rendering for ARTcams whose positions depend on colour or depth (pc/cp
// coupling into the position outputs, e.g. the paper's eq 8/9 colour shift): the gather warp
// cannot invert them.
//
// Reconstruction: the source pixel centres, mapped forward one by one with their own colour
// and depth (eq 3, 5), are the vertices of a triangle mesh (two triangles per 2×2 block of
// neighbouring centres), rasterised with their vertices' output attributes interpolated
// linearly (barycentric). docs/architecture.md, "The forward splat", states the rules below.
//
// Sampling, one rule per output pixel. Samples lie on a lattice of 1/(2S) px, vertices snap to
// 1/256 of its step and every inside test is exact integer arithmetic with a top-left fill rule,
// so triangles that share an edge share every sample of it. A triangle of at least ¼ px² is
// read at pixel centres (weight S²), a smaller one at the S×S sub-samples of each pixel
// (weight 1, a box prefilter: no moiré where the map minifies). Coverage: a pixel whose centre
// any triangle covers is covered fully; else it is covered by the fraction of its sub-samples
// minified triangles cover. So an interior pixel is never partly transparent, whatever mix of
// triangle sizes meets there; an identity map returns the source exactly; a smooth magnifying
// map leaves no cracks (the mesh is the map's piecewise-linear interpolant).
// A ring of vertices one pixel outside the source carries transparent colour (placed by the
// nearest source pixel's colour, so colour-driven positions stay defined), which gives the
// same fading border as the gather's "outside is transparent" convention (sampling.h).
//
// Folds. The mesh's orientation is that of a coarse mesh over the whole source; a triangle
// facing the other way is the fold's folded-under layer and is hidden (where the map has degree
// one, every point it covers is covered by two triangles facing the mesh's way, so no hole
// opens; a mirror map simply has the other orientation). Where layers facing the mesh's way
// overlap, per output pixel the front layer alone is shown: where the geometry reads depth the
// nearest (the input depth), else the layer the camera magnifies more (nearer things look
// larger; a positive s_red's expanded red covers what it moves over). Keys within 5 % are one
// layer and average.
//
// Tears. Where neighbouring source samples differ by more than `tear_colour` in a colour channel
// the geometry reads, or by more than the fraction `tear_depth` in depth where it reads depth,
// the edge between them is torn: its triangles still cover their area (so no pinholes), but are
// not interpolated across the jump. Each sample shows one side, interpolated along that side
// alone: the side it lies nearer to (the gap split at its middle) for colour tears, the farther
// side for depth tears (a disocclusion shows what lies behind). Torn triangles lie behind the
// intact mesh. So a hard edge that the camera pulls apart stays a hard edge.
//
// Normalisation and alpha: per output pixel, the front layer's weighted mean premultiplied
// colour times the coverage.
//
// Poles and invalid points: a triangle is dropped when a vertex has no finite position, lands
// beyond the lattice's exact range (about 10⁵ px outside the frame), or the position weights
// q_h of its vertices differ in sign (it would straddle the pole curve).
#pragma once

#include "core/model/camera.h"
#include "core/model/image.h"
#include "core/render/attributed.h"

#include <functional>

namespace artcam {

struct SplatOptions {
  int supersample = 3;  // S: sub-samples per output pixel side, 1..8
  int threads = 0;      // mapping the vertices runs on all cores; rasterising on one
  // Tears (above): a jump of more than this in a premultiplied linear colour channel the
  // geometry reads, or more than this fraction of the depth where it reads depth.
  double tear_colour = 0.1;
  double tear_depth = 0.05;
  std::function<bool(double)> progress;  // return false to cancel
};

struct SplatSummary {
  bool cancelled = false;
  long long transparent_pixels = 0;
  long long dropped_triangles = 0;  // invalid vertex or straddling a pole
  long long folded_triangles = 0;   // facing against the mesh: hidden fold layers
  long long torn_triangles = 0;     // across a colour or depth jump the geometry reads
};

// `rgba`: premultiplied RGBA (rgbaFromImage); `depth` as renderAttributed takes it (may be
// null unless the camera has a depth block). Output of out_px pixels.
AttributedImage splatImage(const ImageF& rgba, const ImageF* depth, const Camera& camera,
                           FrameSize out_px, const SplatOptions& options = {},
                           SplatSummary* summary = nullptr);

}  // namespace artcam
