// SPDX-License-Identifier: Apache-2.0
#include "core/effects/aerial.h"

#include <Eigen/SVD>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace artcam {

double normalisedLogDepth(double depth, double near, double far) {
  return std::log(depth / near) / std::log(far / near);
}

namespace {

// Monomials (δ², δ, 1) of a quadratic form on (δ, 1): x Q xᵀ = q00 δ² + 2 q01 δ + q11.
Eigen::Matrix2d formFromCoefficients(double a, double b, double c) {
  Eigen::Matrix2d q;
  q << a, 0.5 * b, 0.5 * b, c;
  return q;
}

double evalForm(const Eigen::Matrix2d& q, double d) {
  const Eigen::Vector2d x(d, 1.0);
  return x.dot(q * x);
}

}  // namespace

LogDepthFit fitLogDepth(double near, double far, int samples) {
  if (!(near > 0.0) || !(far > near) || !std::isfinite(far))
    throw std::invalid_argument("aerial perspective needs 0 < near < far (got near " +
                                std::to_string(near) + ", far " + std::to_string(far) + ")");
  samples = std::max(samples, 16);
  // Normalised variable δ ∈ [−1, 1], d = mid + half·δ, spaced evenly in log depth so the
  // near range, where the log bends most, is not under-sampled.
  const double mid = 0.5 * (near + far), half = 0.5 * (far - near);
  Eigen::VectorXd delta(samples), target(samples);
  for (int i = 0; i < samples; ++i) {
    const double d = near * std::pow(far / near, static_cast<double>(i) / (samples - 1));
    delta[i] = (d - mid) / half;
    target[i] = normalisedLogDepth(d, near, far);
  }
  // Unknowns (a, b, c | e, f, g): num − l·den = 0, null space by SVD; then re-weight each row by
  // 1/den of the previous solution so the residual approaches the true error (SK iteration).
  Eigen::VectorXd weight = Eigen::VectorXd::Ones(samples);
  Eigen::VectorXd h;
  for (int iteration = 0; iteration < 8; ++iteration) {
    Eigen::MatrixXd m(samples, 6);
    for (int i = 0; i < samples; ++i) {
      const double t = delta[i], l = target[i], w = weight[i];
      m.row(i) << w * t * t, w * t, w, -w * l * t * t, -w * l * t, -w * l;
    }
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(m, Eigen::ComputeFullV);
    h = svd.matrixV().col(5);
    for (int i = 0; i < samples; ++i) {
      const double den = h[3] * delta[i] * delta[i] + h[4] * delta[i] + h[5];
      weight[i] = 1.0 / std::abs(den);
    }
    weight /= weight.maxCoeff();
  }
  const Eigen::Matrix2d num_delta = formFromCoefficients(h[0], h[1], h[2]);
  const Eigen::Matrix2d den_delta = formFromCoefficients(h[3], h[4], h[5]);
  // Back to (d, 1): the row (δ, 1) = (d, 1)·M with M = [[1/half, 0], [−mid/half, 1]], so
  // Q_d = M Q_δ Mᵀ (frames.h's input-side rule for row vectors).
  Eigen::Matrix2d m;
  m << 1.0 / half, 0.0, -mid / half, 1.0;
  LogDepthFit fit;
  fit.numerator = m * num_delta * m.transpose();
  fit.denominator = m * den_delta * m.transpose();
  // Dense check in depth, including the sign of the denominator (no pole inside the range).
  const int check = 4096;
  double sum2 = 0.0;
  int sign = 0;
  for (int i = 0; i < check; ++i) {
    const double d = near + (far - near) * i / (check - 1.0);
    const double den = evalForm(fit.denominator, d);
    const int s = den > 0 ? 1 : den < 0 ? -1 : 0;
    if (s == 0 || (sign != 0 && s != sign))
      throw std::invalid_argument("the log-depth fit has a pole inside [near, far]");
    sign = s;
    const double e = evalForm(fit.numerator, d) / den - normalisedLogDepth(d, near, far);
    fit.max_error = std::max(fit.max_error, std::abs(e));
    sum2 += e * e;
  }
  fit.rms_error = std::sqrt(sum2 / check);
  // A positive denominator keeps the chain's rehomogenised depth weight positive.
  if (sign < 0) {
    fit.numerator = -fit.numerator;
    fit.denominator = -fit.denominator;
  }
  return fit;
}

Camera aerialPerspectiveCamera(const AerialParams& p, FrameSize source, FrameSize target,
                               LogDepthFit* fit_out) {
  if (!(p.strength >= 0.0 && p.strength <= 1.0))
    throw std::invalid_argument("aerial perspective strength must be in [0, 1]");
  if (!p.haze.allFinite()) throw std::invalid_argument("aerial perspective haze must be finite");
  const LogDepthFit fit = fitLogDepth(p.near, p.far);
  if (fit_out) *fit_out = fit;
  // Elements: u v w | r g b a | d dh.
  constexpr int kU = 0, kW = 2, kR = 3, kA = 6, kD = 7, kDh = 8, kN = 9;
  const auto e = [](int i) { return Eigen::VectorXd::Unit(kN, i); };
  const std::vector<Block> blocks = {Block{BlockKind::Position, 3}, Block{BlockKind::Colour, 4},
                                     Block{BlockKind::Depth, 2}};
  Stage log_stage;  // stage 1: position and colour unchanged, depth → l
  for (int i = kU; i < kD; ++i) log_stage.q.push_back(symmetricOuter(e(i), e(kW)));
  for (const Eigen::Matrix2d* q : {&fit.numerator, &fit.denominator}) {
    Eigen::MatrixXd full = Eigen::MatrixXd::Zero(kN, kN);
    full.block<2, 2>(kD, kD) = *q;
    log_stage.q.push_back(full);
  }
  Stage haze_stage;  // stage 2: c' = c·(1 − t·l) + t·l·a·haze (depth × colour coupling)
  for (int i = kU; i < kR; ++i) haze_stage.q.push_back(symmetricOuter(e(i), e(kW)));
  const double t = p.strength;
  for (int k = 0; k < 3; ++k)
    haze_stage.q.push_back(symmetricOuter(e(kR + k), e(kDh) - t * e(kD)) +
                           t * p.haze[k] * symmetricOuter(e(kA), e(kD)));
  haze_stage.q.push_back(symmetricOuter(e(kA), e(kDh)));
  haze_stage.q.push_back(symmetricOuter(e(kD), e(kW)));
  haze_stage.q.push_back(symmetricOuter(e(kDh), e(kW)));
  return Camera(blocks, {log_stage, haze_stage}, source, target);
}

}  // namespace artcam
