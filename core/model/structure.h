// SPDX-License-Identifier: Apache-2.0
// Structure analysis: which blocks of each Q_i are zero, and what class the geometry is.
// Run once per camera; renderers pick the cheapest exact kernel from it, so
// a scene never pays for what its camera does not need.
//
// A position map is a homography exactly when every position tensor shares one linear factor:
// Q_i = sym(l h_iᵀ) for a common l, so y_i = (x·h_i)/(x·h_n) (eq 1). Affine, translation
// and identity are special homographies.
#pragma once

#include "core/model/camera.h"

#include <Eigen/Core>

#include <string>
#include <vector>

namespace artcam {

enum class GeometryClass { Identity, Translation, Affine, Homography, Rational };

std::string_view geometryClassName(GeometryClass c);

struct StructureOptions {
  // An entry counts as zero below this fraction of the largest entry of its stage.
  double relative_zero = 1e-12;
};

struct CameraStructure {
  // nonzero[s][i][a][b]: Q_i of stage s has a non-zero entry in rows of block a, columns of b.
  std::vector<std::vector<std::vector<std::vector<bool>>>> nonzero;
  // The position outputs depend on other blocks (pc/cp or colour/depth parts): splat, not gather.
  bool geometry_depends_on_attributes = false;
  // Colour or depth outputs differ from the identity map.
  bool attributes_change = false;
  GeometryClass geometry = GeometryClass::Rational;
  // target_from_source in the normalised frames, column form, when geometry <= Homography
  // (k×k for a position block of size k).
  Eigen::MatrixXd homography;
  // Position outputs that are not finite ratios anywhere (an all-zero denominator).
  bool degenerate = false;

  // One line, e.g. "position 3, 1 stage, geometry homography, colour unchanged".
  std::string summary;
};

CameraStructure analyseStructure(const Camera& camera, const StructureOptions& options = {});

// A camera with its structure, analysed once where a render starts (validateArtcam hands the
// layers' analyses out, core/pipeline/render.cpp keeps them) and passed to every renderer below,
// which reads the structure instead of analysing the camera again. Both are borrowed.
struct AnalysedCamera {
  const Camera& camera;
  const CameraStructure& structure;
};

// The real lines l whose products make the symmetric form q, q = sym(l hᵀ) for some h: one
// (rank 1), two (rank 2 with eigenvalues of opposite signs), else none. Eigenvalues within
// `zero` of 0 count as 0.
std::vector<Eigen::VectorXd> realLineFactors(const Eigen::MatrixXd& q, double zero);

// If the k tensors (each k×k, symmetric) share a common real linear factor l, returns the k×k
// matrix H (column form, rows h_iᵀ) with Q_i = sym(l h_iᵀ) up to one common scale; else empty.
std::optional<Eigen::MatrixXd> factorHomography(const std::vector<Eigen::MatrixXd>& q,
                                                double relative_tolerance = 1e-10);

// The tensors of homography H (column form) lifted into quadratic forms with l at infinity:
// Q_i = sym(e_k h_iᵀ) where e_k is the homogeneous element.
std::vector<Eigen::MatrixXd> liftHomography(const Eigen::MatrixXd& h);

}  // namespace artcam
