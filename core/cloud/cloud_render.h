// SPDX-License-Identifier: Apache-2.0
// Object-space rendering: forward map, project, z-buffered splat.
//
// A cloud goes through a chain: zero or more 3D ARTcams (effects_3d.h, fitted object cameras),
// each mapping (X, Y, Z, 1) [| colour] to moved points, then one projecting camera
// (projective_cameras.h, glc.h) whose outputs are (u, v, nearness, 1) with (u, v) in the
// normalised frame of the output image (frames.h). Every camera must have a 4-element position
// block; a colour block, where present, receives the point's premultiplied colour (opaque
// white for uncoloured clouds) and its output colour is carried on; a depth block gets (0, 1).
//
// Splats: each point becomes a flat disc, z-buffered by nearness (larger wins; ties go to the
// earlier point, so the result does not depend on the thread count). Its radius is the image of
// one point spacing h: the chain is evaluated at P and P + h·e_k (k = x, y, z) and the disc
// covers splat_scale × the longest of the three image steps. Sizes therefore follow distance
// (perspective) and the local stretch of every camera in the chain, and a dense cloud renders
// without holes: neighbours h apart land less than a diameter apart. The background is
// transparent (alpha 0); output pixels are linear premultiplied RGBA (ImageF).
//
// Points that do not map (non-finite, a zero homogeneous weight), have nearness ≤ 0 (behind
// the camera) or alpha 0 are dropped and counted.
#pragma once

#include "core/cameras/projective_cameras.h"
#include "core/cloud/point_cloud.h"
#include "core/model/camera.h"
#include "core/model/image.h"

#include <functional>
#include <vector>

namespace artcam {

// Whole: every point once. Rgb: the paper's layers (Fig 4, mis-registered prints): the cloud is
// rendered three times, carrying only its red, green or blue channel through the chain, each
// layer with its own z-buffer, and channel k of the result comes from layer k (alpha: the
// largest of the three). Chromatic aberration needs it.
enum class RenderLayers { Whole, Rgb };

struct CloudRenderOptions {
  int width = 512;
  int height = 512;
  double point_spacing = 0.0;  // object units; 0: estimatePointSpacing of the input cloud
  double splat_scale = 0.75;   // disc radius over the longest image step of one spacing
  double max_splat_px = 48.0;  // near poles the step explodes: cap it
  RenderLayers layers = RenderLayers::Whole;
  int threads = 0;                       // 0: all cores
  std::function<bool(double)> progress;  // as ParallelOptions::progress; false cancels
};

struct CloudRenderSummary {
  size_t points = 0;   // input points (× 3 for Rgb layers)
  size_t drawn = 0;    // splats that reached the z-buffer
  size_t dropped = 0;  // unmapped, behind the camera or transparent
  double point_spacing = 0.0;
  double render_ms = 0.0;  // projection + splatting, no file I/O
  bool cancelled = false;
  double pointsPerSecond() const;
};

// Throws std::invalid_argument if a camera lacks a 4-element position block.
ImageF renderCloud(const PointCloud& cloud, const std::vector<Camera>& effects, const Camera& view,
                   const CloudRenderOptions& options = {}, CloudRenderSummary* summary = nullptr);

// The cloud after the 3D cameras of a chain (for `artcam render -o OUT.ply`): positions
// divided, colours premultiplied; points that do not map are removed (their count returned in
// `dropped` when given).
PointCloud applyCameras(const PointCloud& cloud, const std::vector<Camera>& effects,
                        int threads = 0, size_t* dropped = nullptr);

// The default view of a cloud: looking at the centre of its bounds from the direction
// (4, 3, -5) (y up) at 2.8 × its bounding radius, so three faces of a box show (Fig 1).
CameraPose defaultViewPose(const CloudBounds& bounds);
// A pinhole at `pose` whose focal fits every point of `cloud` in front of it into a
// width×height image with `margin` to spare (at least 1.0).
PinholeParams framingPinhole(const PointCloud& cloud, const CameraPose& pose, int width, int height,
                             double margin = 1.08);

}  // namespace artcam
