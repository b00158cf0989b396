// SPDX-License-Identifier: Apache-2.0
// Colour transforms fitted from colour samples, the candidates of colour
// calibration by model selection (the paper's §4.1 and [LH07]), simplest first:
//
//   linear          dst = M (r, g, b)ᵀ                      3×3,  9 parameters
//   affine          dst = M (r, g, b, 1)ᵀ                   3×4, 12
//   root-polynomial dst = M (r, g, b, √rg, √gb, √rb)ᵀ       3×6, 18 (Finlayson, Mackiewicz &
//                   Hurlbert 2015, degree 2: exposure-invariant, NOT a quadratic form)
//   quadratic       dst_i = c Q_i cᵀ / c Q_4 cᵀ, c = (r, g, b, 1), four symmetric 4×4: the full
//                   rational quadratic of eq 1/3 on the colour block, 39 parameters up to scale
//
// Colours are linear-light RGB (colour_difference.h). Only the quadratic forms (linear, affine,
// quadratic) can be written as an ARTcam (colourCamera); root-polynomial terms √(rg) are not
// quadratic in c, which is why it is a candidate for comparison only.
#pragma once

#include "core/model/camera.h"

#include <Eigen/Core>

#include <array>
#include <optional>
#include <string_view>

namespace artcam {

enum class ColourModel { Auto, Linear, Affine, RootPolynomial, Quadratic };

std::string_view colourModelName(ColourModel model);
std::optional<ColourModel> colourModelFromName(std::string_view name);
// Fewest samples that determine the model (3 equations per sample): 3, 4, 6, 13.
int minimumColourSamples(ColourModel model);
// The model is a quadratic form in the premultiplied colour, so an ARTcam can hold it.
bool isQuadraticForm(ColourModel model);

// Linear: (r, g, b); affine: (r, g, b, 1); root-polynomial: (r, g, b, √rg, √gb, √rb) with
// negative products taken as 0 under the root (out-of-gamut data must not give NaN).
Eigen::VectorXd colourTerms(ColourModel model, const Eigen::Vector3d& rgb);

struct ColourMap {
  ColourModel model = ColourModel::Linear;
  Eigen::MatrixXd m;                 // linear, affine, root-polynomial: dst = m · colourTerms
  std::array<Eigen::Matrix4d, 4> q;  // quadratic: dst_i = c q_i cᵀ / c q_3 cᵀ, c = (r, g, b, 1)

  // Empty where the quadratic's denominator vanishes or the result is not finite.
  std::optional<Eigen::Vector3d> apply(const Eigen::Vector3d& rgb) const;
};

// Least and greatest value of c q cᵀ (c = (r, g, b, 1)) over the box lo ≤ (r, g, b) ≤ hi,
// found exactly: a quadratic's extremes over a box lie at a stationary point of the interior,
// of a face or of an edge, or at a corner, so 27 small linear solves find them all.
struct QuadraticRange {
  double least = 0.0;
  double greatest = 0.0;
};
QuadraticRange quadraticRangeOverBox(const Eigen::Matrix4d& q, const Eigen::Vector3d& lo,
                                     const Eigen::Vector3d& hi);

// The ARTcam that applies `map` to every pixel: blocks [position (u, v, 1) | colour (a·r, a·g,
// a·b, a)], geometry the identity on `frame` (so the renderer takes its colour-only path), and
// the colour block (eq 6/7):
// - linear, affine: the pc part, z_ci = p_3 · (c · h_i) — linear in premultiplied colour, so
//   output alpha = input alpha;
// - quadratic: the cc part, z_ci = c Q_i cᵀ, homogeneous of degree 2 in c, so the colour
//   z_ci / z_c4 does not depend on alpha. Output alpha is z_c4 = a² · c̄ Q_4 c̄ᵀ: the caller
//   scales the tensors so that c̄ Q_4 c̄ᵀ ≥ 1 over the colours it cares about, which keeps
//   opaque pixels opaque after clamping (fit_colour.h does); translucent ones get a² or more.
// Throws std::invalid_argument for root-polynomial maps (not a quadratic form).
Camera colourCamera(const ColourMap& map, FrameSize frame);

}  // namespace artcam
