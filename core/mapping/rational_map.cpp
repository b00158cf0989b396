// SPDX-License-Identifier: Apache-2.0
#include "core/mapping/rational_map.h"

#include "core/model/frames.h"
#include "core/util/cpu_features.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace artcam {

RationalMap::RationalMap(const Camera& camera, FrameSize source_px, FrameSize target_px) {
  const BlockLayout& layout = camera.layout();
  const int p = layout.find(BlockKind::Position);
  if (p < 0 || layout.blocks[p].size != 3)
    throw std::invalid_argument("a pixel map needs a camera with a 2D position block (u, v, 1)");
  if (!source_px.isImage() || !target_px.isImage())
    throw std::invalid_argument("a pixel map needs positive source and target sizes");
  Camera c = camera;
  // A stage's three position forms share one scale (eq 1 is a ratio): bring the largest entry
  // to 1 before the frame changes, so tensors written at 1e-300 or 1e300 neither underflow nor
  // overflow in the products that follow.
  {
    const int off0 = layout.offsets[p];
    for (Stage& st : c.stages()) {
      double scale = 0.0;
      for (int i = 0; i < 3; ++i) scale = std::max(scale, st.q[static_cast<size_t>(off0 + i)].cwiseAbs().maxCoeff());
      if (scale > 0.0 && std::isfinite(scale))
        for (int i = 0; i < 3; ++i) st.q[static_cast<size_t>(off0 + i)] /= scale;
    }
  }
  c.setFrames(source_px, target_px);
  // Row-vector input x_n = x_p N_colᵀ, so H_row = N_colᵀ (frames.h); outputs mix by P_col.
  changeInputFrame(c, p, normalizedFromPixelMatrix(source_px).transpose());
  changeOutputFrame(c, p, pixelFromNormalizedMatrix(target_px));
  c.symmetrize();  // the gradient 2 Q x below assumes symmetric storage (eq 10)
  const int off = layout.offsets[p];
  for (const Stage& st : c.stages()) {
    std::vector<Eigen::Matrix3d> q;
    for (int i = 0; i < 3; ++i) q.emplace_back(st.q[off + i].block(off, off, 3, 3));
    stages_.push_back(std::move(q));
  }
  if (stages_.size() == 1)
    for (int i = 0; i < 3; ++i) {
      const Eigen::Matrix3d& m = stages_[0][static_cast<size_t>(i)];
      single_[i] = {m(0, 0), 2 * m(0, 1), 2 * m(0, 2), m(1, 1), 2 * m(1, 2), m(2, 2)};
    }
}

bool RationalMap::evaluateSingle(const Eigen::Vector2d& source, Eigen::Vector2d& target,
                                 Eigen::Matrix2d* jacobian, unsigned* denominator_signs) const {
  const double u = source.x(), v = source.y();
  const Form &f0 = single_[0], &f1 = single_[1], &f2 = single_[2];
  const auto value = [&](const Form& f) { return (f.a * u + f.b * v + f.c) * u + (f.d * v + f.e) * v + f.f; };
  const double den = value(f2);
  if (!(std::abs(den) > 0.0)) return false;
  const double inv = 1.0 / den;
  const double x = value(f0) * inv, y = value(f1) * inv;
  if (!std::isfinite(x) || !std::isfinite(y)) return false;
  if (jacobian) {
    // d(n_i / n_3) = (∇n_i − y_i ∇n_3) / n_3 (eq 2).
    const double du = 2 * f2.a * u + f2.b * v + f2.c, dv = f2.b * u + 2 * f2.d * v + f2.e;
    Eigen::Matrix2d j;
    j << (2 * f0.a * u + f0.b * v + f0.c - x * du) * inv, (f0.b * u + 2 * f0.d * v + f0.e - x * dv) * inv,
        (2 * f1.a * u + f1.b * v + f1.c - y * du) * inv, (f1.b * u + 2 * f1.d * v + f1.e - y * dv) * inv;
    if (!j.allFinite()) return false;
    *jacobian = j;
  }
  target = Eigen::Vector2d(x, y);
  if (denominator_signs) *denominator_signs = den < 0.0 ? 1u : 0u;
  return true;
}

bool RationalMap::jacobianDerivative(const Eigen::Vector2d& source, const Eigen::Vector2d& direction,
                                     Eigen::Matrix2d& out) const {
  if (stages_.size() != 1) return false;
  const double u = source.x(), v = source.y(), wu = direction.x(), wv = direction.y();
  // Per form n: its value, gradient (n_u, n_v), and the gradient's and the value's derivative
  // along w (the Hessian is constant: 2a, b, 2d).
  struct Along {
    double n, nu, nv, dn, dnu, dnv;
  };
  const auto along = [&](const Form& f) {
    const double nu = 2 * f.a * u + f.b * v + f.c, nv = f.b * u + 2 * f.d * v + f.e;
    return Along{(f.a * u + f.b * v + f.c) * u + (f.d * v + f.e) * v + f.f, nu, nv,
                 nu * wu + nv * wv, 2 * f.a * wu + f.b * wv, f.b * wu + 2 * f.d * wv};
  };
  const Along x = along(single_[0]), y = along(single_[1]), d = along(single_[2]);
  if (!(std::abs(d.n) > 0.0)) return false;
  const double inv = 1.0 / d.n;
  // With F = n / D: G_k = (n_k − F D_k) / D, and along w
  // dG_k = (dn_k − dF D_k − F dD_k − G_k dD) / D, dF = G · w.
  const auto row = [&](const Along& n, double* g, double* dg) {
    const double f = n.n * inv;
    g[0] = (n.nu - f * d.nu) * inv;
    g[1] = (n.nv - f * d.nv) * inv;
    const double df = g[0] * wu + g[1] * wv;
    dg[0] = (n.dnu - df * d.nu - f * d.dnu - g[0] * d.dn) * inv;
    dg[1] = (n.dnv - df * d.nv - f * d.dnv - g[1] * d.dn) * inv;
  };
  double g[2], dx[2], dy[2];
  row(x, g, dx);
  row(y, g, dy);
  out << dx[0], dx[1], dy[0], dy[1];
  return out.allFinite();
}

bool RationalMap::evaluateBatch(const double* u, const double* v, Batch& out) const {
  if (stages_.size() != 1) return false;
  batchDispatched(single_, u, v, out);
  return true;
}

namespace {

// evaluateSingle's arithmetic over kBatch points, without its branches, so that it vectorises;
// compiled twice, for the x86-64 baseline and for AVX2 (four doubles a lane), the same
// operations in the same order and no FMA in either, so both give the same bits.
[[gnu::always_inline]] inline void batchBody(const RationalMap::Form* forms, const double* __restrict u,
                                             const double* __restrict v, RationalMap::Batch& out) {
  const RationalMap::Form f0 = forms[0], f1 = forms[1], f2 = forms[2];
  for (int i = 0; i < RationalMap::kBatch; ++i) {
    const double uu = u[i], vv = v[i];
    const double den = (f2.a * uu + f2.b * vv + f2.c) * uu + (f2.d * vv + f2.e) * vv + f2.f;
    const double inv = 1.0 / den;
    const double x = ((f0.a * uu + f0.b * vv + f0.c) * uu + (f0.d * vv + f0.e) * vv + f0.f) * inv;
    const double y = ((f1.a * uu + f1.b * vv + f1.c) * uu + (f1.d * vv + f1.e) * vv + f1.f) * inv;
    const double du = 2 * f2.a * uu + f2.b * vv + f2.c, dv = f2.b * uu + 2 * f2.d * vv + f2.e;
    out.x[i] = x;
    out.y[i] = y;
    out.j00[i] = (2 * f0.a * uu + f0.b * vv + f0.c - x * du) * inv;
    out.j01[i] = (f0.b * uu + 2 * f0.d * vv + f0.e - x * dv) * inv;
    out.j10[i] = (2 * f1.a * uu + f1.b * vv + f1.c - y * du) * inv;
    out.j11[i] = (f1.b * uu + 2 * f1.d * vv + f1.e - y * dv) * inv;
    out.den[i] = den;
  }
}

#if defined(__x86_64__)
__attribute__((target("avx2"))) void batchAvx2(const RationalMap::Form* forms, const double* u,
                                               const double* v, RationalMap::Batch& out) {
  batchBody(forms, u, v, out);
}
#endif

}  // namespace

void RationalMap::batchDispatched(const Form* forms, const double* u, const double* v, Batch& out) {
#if defined(__x86_64__)
  if (cpuHasAvx2()) return batchAvx2(forms, u, v, out);
#endif
  batchBody(forms, u, v, out);
}

bool RationalMap::evaluate(const Eigen::Vector2d& source, Eigen::Vector2d& target,
                           Eigen::Matrix2d* jacobian, unsigned* denominator_signs) const {
  if (stages_.size() == 1) return evaluateSingle(source, target, jacobian, denominator_signs);
  Eigen::Vector2d y = source;
  Eigen::Matrix2d jac = Eigen::Matrix2d::Identity();
  unsigned signs = 0;
  for (size_t s = 0; s < stages_.size(); ++s) {
    const std::vector<Eigen::Matrix3d>& q = stages_[s];
    const Eigen::Vector3d x(y.x(), y.y(), 1.0);
    const Eigen::Vector3d q0 = q[0] * x, q1 = q[1] * x, q2 = q[2] * x;
    const double den = x.dot(q2);
    // An exact zero or a denominator so small the ratio overflows both mean "on the pole".
    if (!(std::abs(den) > 0.0)) return false;
    const double inv = 1.0 / den;
    const Eigen::Vector2d out(x.dot(q0) * inv, x.dot(q1) * inv);
    if (!out.allFinite()) return false;
    if (den < 0.0) signs |= 1u << s;
    if (jacobian) {
      // d(n_i / n_3) = (∇n_i − y_i ∇n_3) / n_3 with ∇(x Q xᵀ) = 2 (Q x) for symmetric Q (eq 2).
      Eigen::Matrix2d j;
      j.row(0) = 2.0 * inv * (q0.head<2>() - out.x() * q2.head<2>()).transpose();
      j.row(1) = 2.0 * inv * (q1.head<2>() - out.y() * q2.head<2>()).transpose();
      jac = (j * jac).eval();
    }
    y = out;
  }
  if (jacobian) {
    if (!jac.allFinite()) return false;
    *jacobian = jac;
  }
  target = y;
  if (denominator_signs) *denominator_signs = signs;
  return true;
}

RowQuadratics::RowQuadratics(const std::vector<Eigen::Matrix3d>& q, int y, int x0) {
  const double v = y + 0.5;
  const double u = x0 + 0.5;
  for (int i = 0; i < 3; ++i) {
    const Eigen::Matrix3d& m = q[i];
    // n(u) = m00 u² + 2 m01 u v + 2 m02 u + m11 v² + 2 m12 v + m22 for symmetric m.
    value_[i] = m(0, 0) * u * u + 2.0 * m(0, 1) * u * v + 2.0 * m(0, 2) * u + m(1, 1) * v * v +
                2.0 * m(1, 2) * v + m(2, 2);
    delta_[i] = m(0, 0) * (2.0 * u + 1.0) + 2.0 * m(0, 1) * v + 2.0 * m(0, 2);
    second_[i] = 2.0 * m(0, 0);
  }
}

bool RowQuadratics::current(Eigen::Vector2d& out) const {
  if (!(std::abs(value_[2]) > 0.0)) return false;
  const Eigen::Vector2d r(value_[0] / value_[2], value_[1] / value_[2]);
  if (!r.allFinite()) return false;
  out = r;
  return true;
}

void RowQuadratics::advance() {
  for (int i = 0; i < 3; ++i) {
    value_[i] += delta_[i];
    delta_[i] += second_[i];
  }
}

}  // namespace artcam
