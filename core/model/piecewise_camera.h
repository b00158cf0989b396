// SPDX-License-Identifier: Apache-2.0
// Piecewise cameras (the paper's §5: refraction through a glass needed
// 6 + 16 patches). One camera per rectangular patch of the SOURCE image, all stored in the
// same normalised frames (the whole source and target sizes), so a patch is just a camera and
// the rectangle of source pixels it answers for.
//
// Patches tile the part of the source the matches cover; they do not overlap except on their
// shared edges, or where their support hulls are apart (a wall and the roof over it, Fig 2).
// Rectangles and support hulls are drawn in the PATCH FRAME: the source frame, unless a homography
// was composed before the piecewise camera (PatchFrame below). Neighbours are fitted on shared
// boundary matches so they agree at the seams (piecewise_fit.h measures how well: seam_gap_px); the
// renderer removes what is left by averaging the neighbours' predictions at shared mesh vertices
// (piecewise_render.h).
#pragma once

#include "core/model/camera.h"

#include <Eigen/Core>

#include <optional>
#include <string>
#include <vector>

namespace artcam {

// Source pixels [x0, x1] × [y0, y1].
struct PatchRect {
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;

  bool contains(const Eigen::Vector2d& p, double margin = 0.0) const {
    return p.x() >= x0 - margin && p.x() <= x1 + margin && p.y() >= y0 - margin &&
           p.y() <= y1 + margin;
  }
  double width() const { return x1 - x0; }
  double height() const { return y1 - y0; }
  Eigen::Vector2d centre() const { return {0.5 * (x0 + x1), 0.5 * (y0 + y1)}; }
};

struct CameraPatch {
  PatchRect rect;
  // Where the patch has data: the convex hull of its own matches (source pixels), counter-
  // clockwise. A patch's camera is trusted only near it: a quadtree cell's corners often lie
  // where no match constrains the fit, and a rational map extrapolated there can run off
  // anywhere. Empty: the whole rectangle.
  std::vector<Eigen::Vector2d> support;
  Camera camera;           // position-only image camera over the whole frames
  std::string model;       // the fitted model class ("quadratic", "homography", …)
  int matches = 0;         // matches inside the rectangle (its own, not the shared margin)
  double rms_px = 0.0;     // residuals of those matches, target pixels
  double max_px = 0.0;
  // The largest held-out residual of those matches (core/piecewise/piecewise_fit.h): what the
  // patch promises between them; negative: not measured.
  double held_out_max_px = -1.0;
  bool within_tolerance = true;  // max_px and held_out_max_px ≤ the fit's threshold
};

// Where the patches' rectangles and support hulls live when a homography H was composed before
// the piecewise camera (compose.h; the paper's §5 canonical view → table → reflection): the
// frame the patches were fitted in, and the map into it from source pixels, column form,
// (x_patch, 1) ∝ patch_from_source · (x_source, 1). The patch cameras read source pixels (H
// folded into each, Q_i ← Hᵀ Q_i H, exact), while the regions they answer for stay the
// rectangles they were fitted on: H⁻¹ of a rectangle is a quadrilateral, which this keeps exact
// instead of approximating. patch_from_source is scaled so that the source frame's centre has a
// positive homogeneous weight; a source point whose weight is not positive lies beyond H's pole
// line and no patch answers for it.
struct PatchFrame {
  FrameSize size;
  Eigen::Matrix3d patch_from_source = Eigen::Matrix3d::Identity();
};

struct PiecewiseCamera {
  FrameSize source_size;
  FrameSize target_size;
  std::vector<CameraPatch> patches;
  // How far beyond a patch's support hull it still answers (patch-frame pixels): about one and a
  // half match spacings, so the hulls of neighbouring patches meet.
  double support_margin_px = 0.0;
  // Empty: the patch frame is the source frame (every fitted camera).
  std::optional<PatchFrame> patch_frame = std::nullopt;

  // The frame the rectangles and hulls are in (the source frame without a patch frame).
  FrameSize patchFrameSize() const { return patch_frame ? patch_frame->size : source_size; }
  // A source pixel in the patch frame; empty beyond the pole line (see PatchFrame).
  std::optional<Eigen::Vector2d> patchPixelFromSourcePixel(const Eigen::Vector2d& source_px) const;
  // A patch-frame pixel in the source frame; empty where it has no finite preimage on the
  // source's side of the pole line.
  std::optional<Eigen::Vector2d> sourcePixelFromPatchPixel(const Eigen::Vector2d& patch_px) const;
  // The box of source pixels patch i can answer for: its rectangle's preimage's bounding box,
  // clipped to the source frame (the rectangle itself without a patch frame; the whole source
  // frame when the rectangle reaches the pole line). Empty (x1 ≤ x0) when no source pixel
  // reaches it.
  PatchRect sourceBox(int patch) const;

  // Index of the patch whose rectangle holds the source pixel (the first one on a shared
  // edge), or -1 outside every patch.
  int patchAt(const Eigen::Vector2d& source_px) const;
  // The PATCH-FRAME point lies in patch i's support hull grown by support_margin_px.
  bool supports(int patch, const Eigen::Vector2d& patch_px) const;
  // The mapped pixel through the patch that holds it; empty outside the patches' supports or
  // at a pole.
  std::optional<Eigen::Vector2d> targetPixelFromSourcePixel(const Eigen::Vector2d& source_px) const;
};

// Convex hull (Andrew's monotone chain), counter-clockwise, no repeated end point.
std::vector<Eigen::Vector2d> convexHull(std::vector<Eigen::Vector2d> points);
// Whether two convex polygons' interiors are at least `gap` apart (touching along an edge or at
// a corner counts as apart for gap 0): some edge direction of either separates them so (the
// separating axis theorem), to 1e-9 of their size. False when either has fewer than 3 corners
// (no hull: the whole rectangle).
bool convexInteriorsApart(const std::vector<Eigen::Vector2d>& a,
                          const std::vector<Eigen::Vector2d>& b, double gap = 0.0);

}  // namespace artcam
