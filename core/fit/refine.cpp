#include "core/fit/refine.h"

#include "core/fit/poles.h"

#include <Eigen/Cholesky>

#include <cmath>
#include <limits>

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

// Monomials with off-diagonals doubled: x Q xᵀ = r · χ (paper eq 10).
Eigen::Matrix<double, 6, 1> chi(const Eigen::VectorXd& s) {
  const double u = s[0], v = s[1];
  Eigen::Matrix<double, 6, 1> c;
  c << u * u, 2 * u * v, 2 * u, v * v, 2 * v, 1.0;
  return c;
}

// Sum of squared residuals; infinity where a point hits the pole.
double cost(const Params& p, const std::vector<Eigen::Matrix<double, 6, 1>>& chis,
            const std::vector<Eigen::VectorXd>& dst) {
  double sum = 0.0;
  for (size_t k = 0; k < chis.size(); ++k) {
    const double z1 = p.segment<6>(0).dot(chis[k]);
    const double z2 = p.segment<6>(6).dot(chis[k]);
    const double z3 = p.segment<6>(12).dot(chis[k]);
    if (z3 == 0.0) return std::numeric_limits<double>::infinity();
    const double rx = z1 / z3 - dst[k][0], ry = z2 / z3 - dst[k][1];
    sum += rx * rx + ry * ry;
  }
  return std::isfinite(sum) ? sum : std::numeric_limits<double>::infinity();
}

}  // namespace

Camera refineReprojection(const Camera& start, const std::vector<Eigen::VectorXd>& src,
                          const std::vector<Eigen::VectorXd>& dst, const RefineOptions& options,
                          RefineSummary* summary) {
  std::vector<Eigen::Matrix<double, 6, 1>> chis;
  chis.reserve(src.size());
  for (const Eigen::VectorXd& s : src) chis.push_back(chi(s));
  const double n = static_cast<double>(std::max<size_t>(src.size(), 1));

  Params p = toParams(start).normalized();
  double current = cost(p, chis, dst);
  const bool start_pole_free =
      checkDenominator(tensor(p, 2), options.frame_lo, options.frame_hi).pole_free;
  RefineSummary s;
  s.initial_rms = std::sqrt(current / n);
  double lambda = 1e-3;
  s.stop_reason = "iteration limit";
  for (int it = 0; it < options.max_iterations; ++it) {
    s.iterations = it + 1;
    Normal jtj = Normal::Zero();
    Params jtr = Params::Zero();
    Eigen::Matrix<double, 1, 18> row;
    for (size_t k = 0; k < chis.size(); ++k) {
      const auto& c = chis[k];
      const double z3 = p.segment<6>(12).dot(c);
      for (int i = 0; i < 2; ++i) {
        const double zi = p.segment<6>(6 * i).dot(c);
        const double r = zi / z3 - dst[k][i];
        row.setZero();
        row.segment<6>(6 * i) = c.transpose() / z3;
        row.segment<6>(12) = -(zi / (z3 * z3)) * c.transpose();
        jtj.selfadjointView<Eigen::Upper>().rankUpdate(row.transpose());
        jtr += row.transpose() * r;
      }
    }
    jtj.triangularView<Eigen::StrictlyLower>() = jtj.transpose();
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
      const double next = cost(candidate, chis, dst);
      const bool pole_ok =
          !options.keep_pole_free || !start_pole_free ||
          checkDenominator(tensor(candidate, 2), options.frame_lo, options.frame_hi).pole_free;
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
