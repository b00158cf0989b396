// SPDX-License-Identifier: Apache-2.0
#include "core/model/structure.h"

#include <Eigen/Eigenvalues>
#include <Eigen/QR>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace artcam {

std::string_view geometryClassName(GeometryClass c) {
  switch (c) {
    case GeometryClass::Identity: return "identity";
    case GeometryClass::Translation: return "translation";
    case GeometryClass::Affine: return "affine";
    case GeometryClass::Homography: return "homography";
    case GeometryClass::Rational: return "rational";
  }
  return "unknown";
}

namespace {

// Solves Q ≈ sym(l hᵀ) for h in least squares; returns the relative residual.
double fitFactor(const Eigen::MatrixXd& q, const Eigen::VectorXd& l, Eigen::VectorXd& h) {
  const int k = static_cast<int>(l.size());
  // vec(sym(l hᵀ)) = M h with M[(r,c), j] = (l_r δ_cj + l_c δ_rj) / 2.
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(k * k, k);
  Eigen::VectorXd rhs(k * k);
  for (int r = 0; r < k; ++r)
    for (int c = 0; c < k; ++c) {
      const int row = r * k + c;
      m(row, c) += 0.5 * l[r];
      m(row, r) += 0.5 * l[c];
      rhs[row] = q(r, c);
    }
  h = m.colPivHouseholderQr().solve(rhs);
  return (m * h - rhs).norm();
}

GeometryClass classifyHomography(Eigen::MatrixXd& h, double tol) {
  const int k = static_cast<int>(h.rows());
  const double w = h(k - 1, k - 1);
  const double scale = h.cwiseAbs().maxCoeff();
  if (std::abs(w) <= tol * scale) return GeometryClass::Homography;
  h /= w;
  if (h.row(k - 1).head(k - 1).cwiseAbs().maxCoeff() > tol * h.cwiseAbs().maxCoeff())
    return GeometryClass::Homography;
  const Eigen::MatrixXd linear = h.topLeftCorner(k - 1, k - 1);
  if ((linear - Eigen::MatrixXd::Identity(k - 1, k - 1)).cwiseAbs().maxCoeff() > tol)
    return GeometryClass::Affine;
  if (h.col(k - 1).head(k - 1).cwiseAbs().maxCoeff() > tol) return GeometryClass::Translation;
  return GeometryClass::Identity;
}

bool isIdentityOutput(const Stage& stage, const BlockLayout& layout, int block, double tol) {
  const int off = layout.offsets[block];
  const int n = layout.dimension;
  const Eigen::VectorXd unit = Eigen::VectorXd::Unit(n, layout.unitIndex());
  // Colour weights are alpha and must not be scaled; depth is projective, any common scale.
  double common = 1.0;
  if (!weightIsAlpha(layout.blocks[block].kind)) {
    const int h = layout.homogeneousIndex(block);
    common = stage.q[h](h, layout.unitIndex()) * 2.0;
    if (h == layout.unitIndex()) common = stage.q[h](h, h);
    if (common == 0.0) return false;
  }
  for (int i = off; i < off + layout.blocks[block].size; ++i) {
    const Eigen::MatrixXd expected = common * symmetricOuter(Eigen::VectorXd::Unit(n, i), unit);
    if ((stage.q[i] - expected).cwiseAbs().maxCoeff() > tol * std::abs(common)) return false;
  }
  return true;
}

}  // namespace

std::vector<Eigen::VectorXd> realLineFactors(const Eigen::MatrixXd& q, double zero) {
  // q = λ₁ e₁e₁ᵀ + λ₂ e₂e₂ᵀ (rank ≤ 2): with a = √|λ₁| e₁, b = √|λ₂| e₂ and opposite signs,
  // ±(aaᵀ − bbᵀ) = ±sym((a + b)(a − b)ᵀ); rank 1 is the line e₁ twice.
  const int k = static_cast<int>(q.rows());
  if (k < 2) return {};
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(q);
  std::vector<int> order(k);
  for (int i = 0; i < k; ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    return std::abs(eig.eigenvalues()[a]) > std::abs(eig.eigenvalues()[b]);
  });
  const double l1 = eig.eigenvalues()[order[0]];
  if (std::abs(l1) <= zero) return {};
  for (int i = 2; i < k; ++i)
    if (std::abs(eig.eigenvalues()[order[i]]) > zero) return {};  // rank > 2
  const Eigen::VectorXd e1 = eig.eigenvectors().col(order[0]);
  const double l2 = eig.eigenvalues()[order[1]];
  if (std::abs(l2) <= zero) return {e1};
  if (l1 * l2 > 0) return {};  // a pair of complex lines: no real factor
  const Eigen::VectorXd a = std::sqrt(std::abs(l1)) * e1;
  const Eigen::VectorXd b = std::sqrt(std::abs(l2)) * eig.eigenvectors().col(order[1]);
  return {(a + b).normalized(), (a - b).normalized()};
}

std::optional<Eigen::MatrixXd> factorHomography(const std::vector<Eigen::MatrixXd>& q,
                                                double relative_tolerance) {
  const int k = static_cast<int>(q.size());
  double scale = 0.0;
  for (const Eigen::MatrixXd& m : q) scale = std::max(scale, m.cwiseAbs().maxCoeff());
  if (scale == 0.0 || k < 2) return std::nullopt;
  const double tol = relative_tolerance * scale;

  // Candidate factors l come from the denominator, which must be a product of real lines.
  for (const Eigen::VectorXd& l : realLineFactors(q.back(), tol)) {
    Eigen::MatrixXd h(k, k);
    bool ok = true;
    for (int i = 0; i < k && ok; ++i) {
      Eigen::VectorXd row;
      ok = fitFactor(q[i], l, row) <= tol * k;
      h.row(i) = row.transpose();
    }
    if (ok && std::abs(h.determinant()) > 0.0) return h;
  }
  return std::nullopt;
}

std::vector<Eigen::MatrixXd> liftHomography(const Eigen::MatrixXd& h) {
  const int k = static_cast<int>(h.rows());
  const Eigen::VectorXd infinity = Eigen::VectorXd::Unit(k, k - 1);
  std::vector<Eigen::MatrixXd> q;
  for (int i = 0; i < k; ++i) q.push_back(symmetricOuter(infinity, h.row(i).transpose()));
  return q;
}

CameraStructure analyseStructure(const Camera& camera, const StructureOptions& options) {
  CameraStructure out;
  const BlockLayout& layout = camera.layout();
  const int nb = static_cast<int>(layout.blocks.size());
  const int p = layout.find(BlockKind::Position);

  for (const Stage& stage : camera.stages()) {
    double scale = 0.0;
    for (const Eigen::MatrixXd& m : stage.q) scale = std::max(scale, m.cwiseAbs().maxCoeff());
    const double zero = options.relative_zero * scale;
    auto& pattern = out.nonzero.emplace_back();
    for (const Eigen::MatrixXd& m : stage.q) {
      auto& per_output = pattern.emplace_back(nb, std::vector<bool>(nb, false));
      for (int a = 0; a < nb; ++a)
        for (int b = 0; b < nb; ++b)
          per_output[a][b] = m.block(layout.offsets[a], layout.offsets[b], layout.blocks[a].size,
                                     layout.blocks[b].size)
                                 .cwiseAbs()
                                 .maxCoeff() > zero;
    }
    for (int b = 0; b < nb; ++b) {
      if (b == p) continue;
      // Attributes change unless the stage maps the block to itself with no coupling.
      if (!isIdentityOutput(stage, layout, b, options.relative_zero)) out.attributes_change = true;
    }
    if (p >= 0) {
      const int off = layout.offsets[p];
      for (int i = off; i < off + layout.blocks[p].size; ++i)
        for (int a = 0; a < nb; ++a)
          for (int b = 0; b < nb; ++b)
            if (pattern[i][a][b] && (a != p || b != p))
              out.geometry_depends_on_attributes = true;
    }
  }

  if (p >= 0) {
    const int k = layout.blocks[p].size;
    const int off = layout.offsets[p];
    Eigen::MatrixXd total = Eigen::MatrixXd::Identity(k, k);
    bool all_homographies = !out.geometry_depends_on_attributes;
    for (const Stage& stage : camera.stages()) {
      std::vector<Eigen::MatrixXd> pp;
      for (int i = off; i < off + k; ++i) pp.push_back(stage.q[i].block(off, off, k, k));
      // Degenerate only when the denominator is zero in every block: eq 8/9 cameras divide by
      // p3·c4, which lives in the position–colour coupling, not in pp.
      if (stage.q[off + k - 1].cwiseAbs().maxCoeff() == 0.0) out.degenerate = true;
      if (!all_homographies) continue;
      const auto h = factorHomography(pp, 1e-10);
      if (!h) {
        all_homographies = false;
        continue;
      }
      total = (*h * total).eval();
      total /= total.cwiseAbs().maxCoeff();
    }
    if (all_homographies && !out.degenerate) {
      out.homography = total;
      out.geometry = classifyHomography(out.homography, 1e-12);
    }
  }

  std::ostringstream s;
  for (int b = 0; b < nb; ++b)
    s << (b ? " + " : "") << blockKindName(layout.blocks[b].kind) << " " << layout.blocks[b].size;
  s << ", " << camera.stages().size() << (camera.stages().size() == 1 ? " stage" : " stages");
  if (p >= 0) {
    s << ", geometry " << geometryClassName(out.geometry);
    if (out.geometry_depends_on_attributes) s << " driven by attributes";
    if (out.degenerate) s << " (degenerate: zero denominator)";
  }
  if (nb > 1) s << (out.attributes_change ? ", attributes change" : ", attributes unchanged");
  out.summary = s.str();
  return out;
}

}  // namespace artcam
