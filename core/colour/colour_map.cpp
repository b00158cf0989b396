// SPDX-License-Identifier: Apache-2.0
#include "core/colour/colour_map.h"

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace artcam {

std::string_view colourModelName(ColourModel model) {
  switch (model) {
    case ColourModel::Auto: return "auto";
    case ColourModel::Linear: return "linear";
    case ColourModel::Affine: return "affine";
    case ColourModel::RootPolynomial: return "root-polynomial";
    case ColourModel::Quadratic: return "quadratic";
  }
  return "unknown";
}

std::optional<ColourModel> colourModelFromName(std::string_view name) {
  for (ColourModel m : {ColourModel::Auto, ColourModel::Linear, ColourModel::Affine,
                        ColourModel::RootPolynomial, ColourModel::Quadratic})
    if (name == colourModelName(m)) return m;
  return std::nullopt;
}

int minimumColourSamples(ColourModel model) {
  switch (model) {
    case ColourModel::Linear: return 3;
    case ColourModel::Affine: return 4;
    case ColourModel::RootPolynomial: return 6;
    case ColourModel::Quadratic: return 13;  // 4 × 10 unknowns, up to scale: ⌈39 / 3⌉
    case ColourModel::Auto: return 3;
  }
  return 3;
}

bool isQuadraticForm(ColourModel model) { return model != ColourModel::RootPolynomial; }

Eigen::VectorXd colourTerms(ColourModel model, const Eigen::Vector3d& rgb) {
  const double r = rgb.x(), g = rgb.y(), b = rgb.z();
  const auto root = [](double p) { return std::sqrt(std::max(p, 0.0)); };
  switch (model) {
    case ColourModel::Linear: return rgb;
    case ColourModel::Affine: return Eigen::Vector4d(r, g, b, 1.0);
    case ColourModel::RootPolynomial: {
      Eigen::VectorXd t(6);
      t << r, g, b, root(r * g), root(g * b), root(r * b);
      return t;
    }
    case ColourModel::Quadratic:
    case ColourModel::Auto: break;
  }
  throw std::invalid_argument("colourTerms: the quadratic model has no linear terms");
}

std::optional<Eigen::Vector3d> ColourMap::apply(const Eigen::Vector3d& rgb) const {
  Eigen::Vector3d out;
  if (model == ColourModel::Quadratic) {
    const Eigen::Vector4d c(rgb.x(), rgb.y(), rgb.z(), 1.0);
    const double w = c.dot(q[3] * c);
    if (w == 0.0) return std::nullopt;
    for (int i = 0; i < 3; ++i) out[i] = c.dot(q[i] * c) / w;  // eq 3, 5
  } else {
    out = m * colourTerms(model, rgb);
  }
  if (!out.allFinite()) return std::nullopt;
  return out;
}

QuadraticRange quadraticRangeOverBox(const Eigen::Matrix4d& q, const Eigen::Vector3d& lo,
                                     const Eigen::Vector3d& hi) {
  const Eigen::Matrix4d s = 0.5 * (q + q.transpose());
  const Eigen::Matrix3d a = s.topLeftCorner<3, 3>();
  const Eigen::Vector3d b = s.topRightCorner<3, 1>();
  const auto value = [&](const Eigen::Vector3d& x) {
    const Eigen::Vector4d c(x.x(), x.y(), x.z(), 1.0);
    return c.dot(s * c);
  };
  QuadraticRange range{std::numeric_limits<double>::infinity(),
                       -std::numeric_limits<double>::infinity()};
  // Each coordinate is fixed at lo (0), at hi (1) or free (2): 27 faces of every dimension.
  for (int code = 0; code < 27; ++code) {
    int state[3] = {code % 3, (code / 3) % 3, code / 9};
    Eigen::Vector3d x;
    int free_index[3], nfree = 0;
    for (int k = 0; k < 3; ++k) {
      if (state[k] == 2) free_index[nfree++] = k;
      else x[k] = state[k] == 0 ? lo[k] : hi[k];
    }
    if (nfree > 0) {
      // Stationary along the free coordinates: A_ff x_f = -(A_fc x_c + b_f).
      Eigen::MatrixXd aff(nfree, nfree);
      Eigen::VectorXd rhs(nfree);
      for (int i = 0; i < nfree; ++i) {
        const int fi = free_index[i];
        rhs[i] = -b[fi];
        for (int k = 0; k < 3; ++k)
          if (state[k] != 2) rhs[i] -= a(fi, k) * x[k];
        for (int j = 0; j < nfree; ++j) aff(i, j) = a(fi, free_index[j]);
      }
      const Eigen::FullPivLU<Eigen::MatrixXd> lu(aff);
      // A singular face is linear along some direction: its extremes lie on its boundary,
      // which the lower-dimensional faces cover.
      if (!lu.isInvertible()) continue;
      const Eigen::VectorXd xf = lu.solve(rhs);
      bool inside = true;
      for (int i = 0; i < nfree; ++i) {
        const int fi = free_index[i];
        inside = inside && xf[i] > lo[fi] && xf[i] < hi[fi];
        x[fi] = xf[i];
      }
      if (!inside) continue;
    }
    const double v = value(x);
    range.least = std::min(range.least, v);
    range.greatest = std::max(range.greatest, v);
  }
  return range;
}

Camera colourCamera(const ColourMap& map, FrameSize frame) {
  if (!isQuadraticForm(map.model))
    throw std::invalid_argument("a root-polynomial colour map is not a quadratic form and has no "
                                "ARTcam; fit a linear, affine or quadratic one");
  constexpr int n = 7, unit = 2, colour = 3;  // x = [u, v, 1 | a·r, a·g, a·b, a]
  Stage stage;
  const auto unitVector = [](int i) { return Eigen::VectorXd::Unit(n, i); };
  for (int i = 0; i < 3; ++i) stage.q.push_back(symmetricOuter(unitVector(i), unitVector(unit)));
  for (int i = 0; i < 4; ++i) {
    Eigen::MatrixXd qi = Eigen::MatrixXd::Zero(n, n);
    if (map.model == ColourModel::Quadratic) {
      qi.block<4, 4>(colour, colour) = 0.5 * (map.q[i] + map.q[i].transpose());
    } else {
      // h_i over (a·r, a·g, a·b, a): the map's row, its offset on alpha; alpha passes through.
      Eigen::VectorXd h = Eigen::VectorXd::Zero(n);
      if (i < 3) {
        h.segment<3>(colour) = map.m.row(i).head<3>().transpose();
        if (map.model == ColourModel::Affine) h[colour + 3] = map.m(i, 3);
      } else {
        h[colour + 3] = 1.0;
      }
      qi = symmetricOuter(unitVector(unit), h);
    }
    stage.q.push_back(std::move(qi));
  }
  return Camera({Block{BlockKind::Position, 3}, Block{BlockKind::Colour, 4}}, {std::move(stage)},
                frame, frame);
}

}  // namespace artcam
