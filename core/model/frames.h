// SPDX-License-Identifier: Apache-2.0
// Frames and frame changes (docs/architecture.md, "Frames and pixels").
//
// - Pixel centres are at i + 0.5; (0, 0) is the top-left corner of the top-left pixel, y down.
// - The normalised frame of a w×h image: u_n = (u - w/2) / s, v_n = (v - h/2) / s,
//   s = max(w, h) / 2. Tensors are stored in it so a camera made on a preview applies unchanged
//   to the full-resolution original.
// - Matrices named *_row act on ROW vectors (x' = x M), the paper's convention for inputs;
//   matrices named *_col act on column vectors (y' = A y), used for outputs.
// - Input side: substituting x ← x H_row gives Q_i ← H_row Q_i H_rowᵀ (the paper's §5 rule
//   written for row vectors).
// - Output side: a change y' = A_col y of an output block mixes its tensors,
//   Q'_i = Σ_j A_ij Q_j over the block's elements.
#pragma once

#include "core/model/camera.h"

#include <Eigen/Core>

namespace artcam {

Eigen::Vector2d normalizedFromPixel(FrameSize frame, const Eigen::Vector2d& pixel);
Eigen::Vector2d pixelFromNormalized(FrameSize frame, const Eigen::Vector2d& normalized);

// Homogeneous 3×3 versions, column-vector form: x_n = N * x_p.
Eigen::Matrix3d normalizedFromPixelMatrix(FrameSize frame);
Eigen::Matrix3d pixelFromNormalizedMatrix(FrameSize frame);

// Q_i ← H Q_i Hᵀ for every tensor of every stage's FIRST stage input, where H_row (k×k) acts on
// the row sub-vector of block `block` (k = its size). Later stages see outputs, not inputs.
void changeInputFrame(Camera& camera, int block, const Eigen::MatrixXd& h_row);
// Q'_i = Σ_j A_ij Q_j over the elements of output block `block`, in the LAST stage.
void changeOutputFrame(Camera& camera, int block, const Eigen::MatrixXd& a_col);

// The camera re-expressed for images that hold a region of its frames rather than the frames
// themselves: source pixels are those of `source_size` pixels whose top-left corner lies at
// (source_x, source_y) of the camera's source frame (an OpenEXR's data window in its display
// window: overscan, or a crop), and likewise target pixels. The position block's input and
// output frames change (eq 3's tensors, the §5 rule above), the frames become the regions' sizes;
// a camera without a position block only changes frames. Every stage but the first's inputs and
// the last's outputs is untouched.
void reframeToRegions(Camera& camera, double source_x, double source_y, FrameSize source_size,
                      double target_x, double target_y, FrameSize target_size);

// The 2D position block re-expressed with pixel coordinates on both sides (for renderers and
// peers that think in pixels): 3 tensors such that target_pixel = z / z_3 for z = x_p Q xᵀ_p.
std::vector<Eigen::Matrix3d> positionTensorsInPixels(const Camera& camera);

}  // namespace artcam
