// SPDX-License-Identifier: Apache-2.0
#include "core/fit/refine.h"

#include "core/fit/poles.h"

#include <Eigen/Cholesky>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace artcam {
namespace {

using Params = Eigen::Matrix<double, 18, 1>;
using Normal = Eigen::Matrix<double, 18, 18>;

Params toParams(const Camera& c) {
  Params p;
  for (int i = 0; i < 3; ++i) {
    const Eigen::MatrixXd& q = c.stages()[0].q[i];
    p.segment<6>(6 * i) << q(0, 0), q(0, 1), q(0, 2), q(1, 1), q(1, 2), q(2, 2);
  }
  return p;
}

Eigen::Matrix3d tensor(const Params& p, int i) {
  const auto r = p.segment<6>(6 * i);
  Eigen::Matrix3d q;
  q << r[0], r[1], r[2], r[1], r[3], r[4], r[2], r[4], r[5];
  return q;
}

Camera fromParams(const Camera& like, const Params& p) {
  Camera c = like;
  for (int i = 0; i < 3; ++i) c.stages()[0].q[i] = tensor(p, i);
  return c;
}

using Chi = Eigen::Matrix<double, 6, 1>;

// Monomials with off-diagonals doubled: x Q xᵀ = r · χ (paper eq 10).
Chi chi(double u, double v) {
  Chi c;
  c << u * u, 2 * u * v, 2 * u, v * v, 2 * v, 1.0;
  return c;
}

// Exponents of u^i v^j in each entry of χ and its factor (as in dlt.cpp): every entry of χχᵀ
// is a power of two times one of the 15 monomials u^i v^j, i + j ≤ 4.
constexpr int kChiU[6] = {2, 1, 1, 0, 0, 0};
constexpr int kChiV[6] = {0, 1, 0, 2, 1, 0};
constexpr double kChiFactor[6] = {1, 2, 2, 1, 2, 1};
constexpr int monomialIndex(int i, int j) { return (i + j) * (i + j + 1) / 2 + j; }

using Monomials = Eigen::Matrix<double, 15, 1>;

Monomials monomials(double u, double v) {
  Monomials mono;
  mono[0] = 1.0;
  for (int degree = 1; degree <= 4; ++degree) {
    const int row = degree * (degree + 1) / 2, prev = (degree - 1) * degree / 2;
    for (int j = 0; j < degree; ++j) mono[row + j] = mono[prev + j] * u;
    mono[row + degree] = mono[prev + degree - 1] * v;
  }
  return mono;
}

// Fixed per refinement: the matches' χ and monomials in contiguous arrays.
struct Data {
  std::vector<Chi> chis;
  std::vector<Monomials> monos;
  std::vector<Eigen::Vector2d> dst;
};

// Sum of squared residuals; infinity where a point hits the pole.
double cost(const Params& p, const Data& data) {
  double sum = 0.0;
  for (size_t k = 0; k < data.chis.size(); ++k) {
    const Chi& c = data.chis[k];
    const double z1 = p.segment<6>(0).dot(c);
    const double z2 = p.segment<6>(6).dot(c);
    const double z3 = p.segment<6>(12).dot(c);
    if (z3 == 0.0) return std::numeric_limits<double>::infinity();
    const double rx = z1 / z3 - data.dst[k].x(), ry = z2 / z3 - data.dst[k].y();
    sum += rx * rx + ry * ry;
  }
  return std::isfinite(sum) ? sum : std::numeric_limits<double>::infinity();
}

// Gauss–Newton normal equations JᵀJ, Jᵀr of the reprojection residuals. The rows for one match
// are [χ/z3, 0, -(z1/z3²)χ] and [0, χ/z3, -(z2/z3²)χ], so JᵀJ is made of four weighted sums
// of χχᵀ: [[S(1/z3²), 0, S(-z1/z3³)], [0, S(1/z3²), S(-z2/z3³)], [·, ·, S((z1²+z2²)/z3⁴)]].
// Summing the 15 monomials under four weights costs a quarter of two 18-wide rank updates.
void normalEquations(const Params& p, const Data& data, Normal& jtj, Params& jtr) {
  Eigen::Matrix<double, 15, 4> sums = Eigen::Matrix<double, 15, 4>::Zero();
  Chi g0 = Chi::Zero(), g1 = Chi::Zero(), g2 = Chi::Zero();
  for (size_t k = 0; k < data.chis.size(); ++k) {
    const Chi& c = data.chis[k];
    const double z1 = p.segment<6>(0).dot(c);
    const double z2 = p.segment<6>(6).dot(c);
    const double z3 = p.segment<6>(12).dot(c);
    const double inv = 1.0 / z3;
    const double y1 = z1 * inv, y2 = z2 * inv;
    const double rx = y1 - data.dst[k].x(), ry = y2 - data.dst[k].y();
    const Eigen::Vector4d w(inv * inv, -y1 * inv * inv, -y2 * inv * inv,
                            (y1 * y1 + y2 * y2) * inv * inv);
    sums.noalias() += data.monos[k] * w.transpose();
    g0 += (rx * inv) * c;
    g1 += (ry * inv) * c;
    g2 -= ((y1 * rx + y2 * ry) * inv) * c;
  }
  Eigen::Matrix<double, 6, 6> blocks[4];
  for (int j = 0; j < 6; ++j)
    for (int l = 0; l < 6; ++l) {
      const int idx = monomialIndex(kChiU[j] + kChiU[l], kChiV[j] + kChiV[l]);
      const double factor = kChiFactor[j] * kChiFactor[l];
      for (int a = 0; a < 4; ++a) blocks[a](j, l) = factor * sums(idx, a);
    }
  jtj.setZero();
  jtj.block<6, 6>(0, 0) = blocks[0];
  jtj.block<6, 6>(6, 6) = blocks[0];
  jtj.block<6, 6>(0, 12) = blocks[1];
  jtj.block<6, 6>(12, 0) = blocks[1];
  jtj.block<6, 6>(6, 12) = blocks[2];
  jtj.block<6, 6>(12, 6) = blocks[2];
  jtj.block<6, 6>(12, 12) = blocks[3];
  jtr << g0, g1, g2;
}

}  // namespace

Camera refineReprojection(const Camera& start, const Points& src, const Points& dst,
                          const RefineOptions& options, RefineSummary* summary) {
  Data data;
  const size_t m = static_cast<size_t>(src.cols());
  data.chis.reserve(m);
  data.monos.reserve(m);
  data.dst.reserve(m);
  for (Eigen::Index k = 0; k < src.cols(); ++k) {
    data.chis.push_back(chi(src(0, k), src(1, k)));
    data.monos.push_back(monomials(src(0, k), src(1, k)));
    data.dst.emplace_back(dst(0, k), dst(1, k));
  }
  const double n = static_cast<double>(std::max<size_t>(m, 1));

  Params p = toParams(start).normalized();
  double current = cost(p, data);
  const PoleCheck start_poles = checkDenominator(tensor(p, 2), options.frame_lo, options.frame_hi);
  const bool start_pole_free = start_poles.pole_free;
  // Steps may not bring the pole curve closer to the frame than this (refine.h).
  const double margin_floor = std::min(options.min_pole_margin, start_poles.margin);
  RefineSummary s;
  s.initial_rms = std::sqrt(current / n);
  double lambda = 1e-3;
  s.stop_reason = "iteration limit";
  Normal jtj;
  Params jtr;
  for (int it = 0; it < options.max_iterations; ++it) {
    s.iterations = it + 1;
    normalEquations(p, data, jtj, jtr);
    bool accepted = false;
    for (int tries = 0; tries < 12 && !accepted; ++tries) {
      Normal damped = jtj;
      damped.diagonal() += lambda * (jtj.diagonal().array() + 1e-12).matrix();
      // Damping makes the matrix positive definite; Cholesky is exact and deterministic there.
      const Eigen::LLT<Normal> cholesky(damped);
      if (cholesky.info() != Eigen::Success) {
        lambda *= 8.0;
        continue;
      }
      const Params step = cholesky.solve(-jtr);
      const Params candidate = (p + step).normalized();
      const double next = cost(candidate, data);
      const bool pole_ok = !options.keep_pole_free || !start_pole_free || [&] {
        const PoleCheck c = checkDenominator(tensor(candidate, 2), options.frame_lo, options.frame_hi);
        return c.pole_free && c.margin >= margin_floor;
      }();
      if (next < current && !pole_ok) ++s.pole_rejections;
      if (next < current && pole_ok && candidate.allFinite()) {
        const double gain = (current - next) / std::max(current, 1e-300);
        p = candidate;
        current = next;
        lambda = std::max(lambda / 4.0, 1e-12);
        accepted = true;
        if (gain < options.relative_tolerance) {
          s.stop_reason = "converged";
          it = options.max_iterations;
        }
      } else {
        lambda *= 8.0;
      }
    }
    if (!accepted) {
      s.stop_reason = "no further descent";
      break;
    }
    if (current == 0.0) {
      s.stop_reason = "exact";
      break;
    }
  }
  s.final_rms = std::sqrt(current / n);
  if (summary) *summary = s;
  return fromParams(start, p);
}

}  // namespace artcam
