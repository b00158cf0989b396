// SPDX-License-Identifier: Apache-2.0
#include "core/render/inverse_cells.h"

#include "core/util/parallel.h"

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <limits>

namespace artcam {
namespace {

constexpr int kNodeIterations = 30;

// Cubic Hermite basis on [0, 1]: values at 0 and 1, then derivatives at 0 and 1.
struct Hermite {
  double h0, h1, h2, h3;
  explicit Hermite(double t) {
    const double t2 = t * t, t3 = t2 * t;
    h0 = 2 * t3 - 3 * t2 + 1;
    h1 = -2 * t3 + 3 * t2;
    h2 = t3 - 2 * t2 + t;
    h3 = t3 - t2;
  }
};

}  // namespace

InverseCells::InverseCells(const NewtonInverse& newton, const RationalMap* seed,
                           FrameSize source_px, FrameSize target_px,
                           const InverseCellsOptions& options)
    : newton_(newton), seed_(seed), source_px_(source_px), target_px_(target_px), options_(options) {
  cells_w_ = std::max(1, (target_px.width + kCell - 1) / kCell);
  cells_h_ = std::max(1, (target_px.height + kCell - 1) / kCell);
  nodes_w_ = cells_w_ + 1;
  nodes_h_ = cells_h_ + 1;
  blocks_w_ = std::max(1, (target_px.width + kBlock - 1) / kBlock);
  blocks_h_ = std::max(1, (target_px.height + kBlock - 1) / kBlock);
  nodes_.assign(static_cast<size_t>(nodes_w_) * static_cast<size_t>(nodes_h_), Node{});
  solveNodes(options.threads);
  crossDerivatives();

  // The reach grows with the source pixels one output pixel spans (minifying filters' taps).
  double scale = 1.0;
  for (const Node& n : nodes_)
    if (n.valid) scale = std::max({scale, n.su.cwiseAbs().maxCoeff() / kCell, n.sv.cwiseAbs().maxCoeff() / kCell});
  reach_px_ = options.reach_px + 4.0 * std::min(scale, 64.0);

  kinds_.assign(static_cast<size_t>(cells_w_) * static_cast<size_t>(cells_h_), kOpen);
  ParallelOptions po;
  po.threads = options.threads;
  po.band_rows = 2;
  parallelForRows(cells_h_, po, [&](int j0, int j1) {
    for (int cy = j0; cy < j1; ++cy)
      for (int cx = 0; cx < cells_w_; ++cx)
        if (hasPatch(cx, cy) && certify(cx, cy))
          kinds_[index(cx, cy, cells_w_)] = patchBeyondReach(cx, cy) ? kEmpty : kCertified;
  });
  if (std::find(kinds_.begin(), kinds_.end(), kOpen) == kinds_.end()) return;
  buildCoverage(options.threads);
  if (!coverage_known_) return;
  for (int cy = 0; cy < cells_h_; ++cy)
    for (int cx = 0; cx < cells_w_; ++cx)
      if (kinds_[index(cx, cy, cells_w_)] == kOpen && !cellCovered(cx, cy))
        kinds_[index(cx, cy, cells_w_)] = kEmpty;
}

bool InverseCells::solveNode(const Eigen::Vector2d& t, const Eigen::Vector2d* start, Node& out) const {
  Eigen::Vector2d s;
  bool ok = start && newton_.solve(t, *start, s, kNodeIterations);
  if (!ok && seed_) {
    Eigen::Vector2d seeded;
    if (seed_->evaluate(t, seeded, nullptr) && seeded.allFinite())
      ok = newton_.solve(t, seeded, s, kNodeIterations);
  }
  if (!ok) ok = newton_.solveFromCentre(t, s, kNodeIterations);
  if (!ok) return false;
  Eigen::Vector2d f;
  Eigen::Matrix2d j;
  if (!newton_.forward().evaluate(s, f, &j)) return false;
  const double det = j.determinant();
  if (!(std::abs(det) > 0.0)) return false;
  const Eigen::Matrix2d a = j.inverse();  // ∂s/∂t at the node (eq 2 inverted)
  if (!a.allFinite()) return false;
  out.s = s;
  out.su = kCell * a.col(0);
  out.sv = kCell * a.col(1);
  out.valid = true;
  return true;
}

void InverseCells::solveNodes(int threads) {
  // Continuation: each node starts from its neighbour's solution stepped by the neighbour's
  // derivative, two or three Newton iterations. The first column runs down the frame, then
  // the rows run across it in parallel.
  for (int j = 0; j < nodes_h_; ++j) {
    const Eigen::Vector2d t(0.0, static_cast<double>(j * kCell));
    Eigen::Vector2d start;
    const Node* above = j > 0 && node(0, j - 1).valid ? &node(0, j - 1) : nullptr;
    if (above) start = above->s + above->sv;
    solveNode(t, above ? &start : nullptr, node(0, j));
  }
  ParallelOptions po;
  po.threads = threads;
  po.band_rows = 2;
  parallelForRows(nodes_h_, po, [&](int j0, int j1) {
    for (int j = j0; j < j1; ++j)
      for (int i = 1; i < nodes_w_; ++i) {
        const Eigen::Vector2d t(static_cast<double>(i * kCell), static_cast<double>(j * kCell));
        const Node& left = node(i - 1, j);
        Eigen::Vector2d start;
        if (left.valid) start = left.s + left.su;
        solveNode(t, left.valid ? &start : nullptr, node(i, j));
      }
  });
  // Nodes stay kCell apart past the frame's far edge (up to kCell − 1 pixels beyond it), so
  // every cell has the same parametrisation; the frame's last cell uses part of it.
}

void InverseCells::crossDerivatives() {
  // kCell² ∂²s/∂x∂y from F(s(t)) = t: ∂A/∂y = −A (∂J/∂y) A with A = J⁻¹, and ∂J/∂y the forward
  // Jacobian's derivative along A's y column, a central difference over ±h output pixels
  // (error ~h² |∂³F|, far below the patch's). Exact to that where a neighbour difference
  // would be first order at the frame's edge.
  constexpr double h = 0.25;
  ParallelOptions po;
  po.threads = options_.threads;
  po.band_rows = 4;
  parallelForRows(nodes_h_, po, [&](int j0, int j1) {
    for (int j = j0; j < j1; ++j)
      for (int i = 0; i < nodes_w_; ++i) {
        Node& n = node(i, j);
        if (!n.valid) continue;
        const Eigen::Matrix2d a = (Eigen::Matrix2d() << n.su, n.sv).finished() / kCell;
        const Eigen::Vector2d dir = h * a.col(1);
        Eigen::Vector2d f;
        Eigen::Matrix2d jp, jm;
        if (!newton_.forward().evaluate(n.s + dir, f, &jp) || !newton_.forward().evaluate(n.s - dir, f, &jm)) {
          n.valid = false;  // a pole within a quarter pixel: no patch here
          continue;
        }
        const Eigen::Matrix2d dj = (jp - jm) / (2.0 * h);
        const Eigen::Matrix2d da = -a * dj * a;
        n.suv = static_cast<double>(kCell) * kCell * da.col(0);
        if (!n.suv.allFinite()) n.valid = false;
      }
  });
}

bool InverseCells::hasPatch(int cx, int cy) const {
  return node(cx, cy).valid && node(cx + 1, cy).valid && node(cx, cy + 1).valid &&
         node(cx + 1, cy + 1).valid;
}

void InverseCells::row(int cx, int y, CellRow& out) const {
  const int cy = std::min(y / kCell, cells_h_ - 1);
  const Hermite hv((y + 0.5 - cy * kCell) / kCell);
  const Node &a = node(cx, cy), &b = node(cx + 1, cy), &c = node(cx, cy + 1), &d = node(cx + 1, cy + 1);
  // Along the cell's left (a, c) and right (b, d) edges at this row: value and ∂/∂u.
  const Eigen::Vector2d f0 = hv.h0 * a.s + hv.h1 * c.s + hv.h2 * a.sv + hv.h3 * c.sv;
  const Eigen::Vector2d f1 = hv.h0 * b.s + hv.h1 * d.s + hv.h2 * b.sv + hv.h3 * d.sv;
  const Eigen::Vector2d d0 = hv.h0 * a.su + hv.h1 * c.su + hv.h2 * a.suv + hv.h3 * c.suv;
  const Eigen::Vector2d d1 = hv.h0 * b.su + hv.h1 * d.su + hv.h2 * b.suv + hv.h3 * d.suv;
  // The cubic through them in u: c0 + u (c1 + u (c2 + u c3)).
  const Eigen::Vector2d c2 = 3.0 * (f1 - f0) - 2.0 * d0 - d1;
  const Eigen::Vector2d c3 = 2.0 * (f0 - f1) + d0 + d1;
  out.x[0] = f0.x(), out.x[1] = d0.x(), out.x[2] = c2.x(), out.x[3] = c3.x();
  out.y[0] = f0.y(), out.y[1] = d0.y(), out.y[2] = c2.y(), out.y[3] = c3.y();
}

Eigen::Vector2d InverseCells::patchAt(int cx, int cy, double u, double v) const {
  const Hermite hu(u), hv(v);
  const Node &a = node(cx, cy), &b = node(cx + 1, cy), &c = node(cx, cy + 1), &d = node(cx + 1, cy + 1);
  const Eigen::Vector2d f0 = hv.h0 * a.s + hv.h1 * c.s + hv.h2 * a.sv + hv.h3 * c.sv;
  const Eigen::Vector2d f1 = hv.h0 * b.s + hv.h1 * d.s + hv.h2 * b.sv + hv.h3 * d.sv;
  const Eigen::Vector2d d0 = hv.h0 * a.su + hv.h1 * c.su + hv.h2 * a.suv + hv.h3 * c.suv;
  const Eigen::Vector2d d1 = hv.h0 * b.su + hv.h1 * d.su + hv.h2 * b.suv + hv.h3 * d.suv;
  return hu.h0 * f0 + hu.h1 * f1 + hu.h2 * d0 + hu.h3 * d1;
}

bool InverseCells::certify(int cx, int cy) const {
  const CentreReference& centre = newton_.centre();
  const double tol = options_.certify_tolerance_px;
  // The edges' midpoints (a cubic Hermite's error along an edge, ∝ u²(1 − u)², peaks there),
  // the centre, and the four points u, v ∈ {1/2 ± 1/√12} where an error in the cross
  // derivatives, ∝ u(1 − u)(1 − 2u) · v(1 − v)(1 − 2v), peaks and the centre sees nothing.
  constexpr double lo = 0.5 - 0.28867513459481287, hi = 0.5 + 0.28867513459481287;
  static constexpr double kPoints[9][2] = {{0.5, 0.0}, {0.5, 1.0}, {0.0, 0.5}, {1.0, 0.5}, {0.5, 0.5},
                                           {lo, lo},   {hi, lo},   {lo, hi},   {hi, hi}};
  for (const auto& uv : kPoints) {
    const Eigen::Vector2d t((cx + uv[0]) * kCell, (cy + uv[1]) * kCell);
    const Eigen::Vector2d p = patchAt(cx, cy, uv[0], uv[1]);
    Eigen::Vector2d f;
    Eigen::Matrix2d j;
    unsigned signs = 0;
    if (!newton_.forward().evaluate(p, f, &j, &signs)) return false;
    const double det = j.determinant();
    if (signs != centre.denominator_signs || (det > 0.0) != centre.det_positive) return false;
    const Eigen::Vector2d r = f - t;
    const Eigen::Vector2d step((j(1, 1) * r.x() - j(0, 1) * r.y()) / det,
                               (j(0, 0) * r.y() - j(1, 0) * r.x()) / det);
    if (!(step.cwiseAbs().maxCoeff() <= tol)) return false;
  }
  return true;
}

bool InverseCells::patchBeyondReach(int cx, int cy) const {
  // The Bézier control net of the bicubic Hermite patch: corners, corners ± derivative / 3,
  // and the inner four from the cross derivatives; the patch lies in its convex hull.
  const Node* n[2][2] = {{&node(cx, cy), &node(cx, cy + 1)}, {&node(cx + 1, cy), &node(cx + 1, cy + 1)}};
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector2d hi = -lo;
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b) {
      const Node& k = *n[a][b];
      const double su = a == 0 ? 1.0 / 3.0 : -1.0 / 3.0, sv = b == 0 ? 1.0 / 3.0 : -1.0 / 3.0;
      const Eigen::Vector2d pts[4] = {k.s, k.s + su * k.su, k.s + sv * k.sv,
                                      k.s + su * k.su + sv * k.sv + su * sv * k.suv};
      for (const Eigen::Vector2d& p : pts) {
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
      }
    }
  const double m = reach_px_ + options_.certify_tolerance_px;
  return hi.x() < -m || hi.y() < -m || lo.x() > source_px_.width + m || lo.y() > source_px_.height + m;
}

void InverseCells::buildCoverage(int threads) {
  // The source frame grown by the reach, as a lattice of quads kLattice source pixels apart.
  constexpr double kLattice = 16.0;
  const double x0 = -reach_px_, y0 = -reach_px_;
  const int qw = static_cast<int>(std::ceil((source_px_.width + 2 * reach_px_) / kLattice));
  const int qh = static_cast<int>(std::ceil((source_px_.height + 2 * reach_px_) / kLattice));
  const int pw = qw + 1, ph = qh + 1;
  std::vector<Eigen::Vector2d> mapped(static_cast<size_t>(pw) * static_cast<size_t>(ph));
  std::vector<unsigned char> ok(mapped.size(), 0);
  const unsigned centre_signs = newton_.centre().denominator_signs;
  ParallelOptions po;
  po.threads = threads;
  po.band_rows = 8;
  parallelForRows(ph, po, [&](int j0, int j1) {
    for (int j = j0; j < j1; ++j)
      for (int i = 0; i < pw; ++i) {
        const Eigen::Vector2d s(std::min(x0 + i * kLattice, source_px_.width + reach_px_),
                                std::min(y0 + j * kLattice, source_px_.height + reach_px_));
        Eigen::Vector2d f;
        Eigen::Matrix2d jac;
        unsigned signs = 0;
        const bool good = newton_.forward().evaluate(s, f, &jac, &signs) && f.allFinite() &&
                          signs == centre_signs;
        mapped[index(i, j, pw)] = f;
        ok[index(i, j, pw)] = good ? 1 : 0;
      }
  });
  // A corner beyond a pole curve: that quad's image is unbounded, claim nothing.
  if (std::find(ok.begin(), ok.end(), 0) != ok.end()) return;
  covered_.assign(static_cast<size_t>(blocks_w_) * static_cast<size_t>(blocks_h_), 0);
  for (int j = 0; j < qh; ++j)
    for (int i = 0; i < qw; ++i) {
      const Eigen::Vector2d& a = mapped[index(i, j, pw)];
      const Eigen::Vector2d& b = mapped[index(i + 1, j, pw)];
      const Eigen::Vector2d& c = mapped[index(i, j + 1, pw)];
      const Eigen::Vector2d& d = mapped[index(i + 1, j + 1, pw)];
      Eigen::Vector2d lo = a.cwiseMin(b).cwiseMin(c).cwiseMin(d);
      Eigen::Vector2d hi = a.cwiseMax(b).cwiseMax(c).cwiseMax(d);
      const double grow = 2.0 + 0.25 * (hi - lo).maxCoeff();
      lo.array() -= grow;
      hi.array() += grow;
      if (hi.x() < 0 || hi.y() < 0 || lo.x() >= target_px_.width || lo.y() >= target_px_.height) continue;
      const int bx0 = std::max(0, static_cast<int>(std::floor(lo.x() / kBlock)));
      const int by0 = std::max(0, static_cast<int>(std::floor(lo.y() / kBlock)));
      const int bx1 = std::min(blocks_w_ - 1, static_cast<int>(std::floor(std::min(hi.x(), 1e9) / kBlock)));
      const int by1 = std::min(blocks_h_ - 1, static_cast<int>(std::floor(std::min(hi.y(), 1e9) / kBlock)));
      for (int by = by0; by <= by1; ++by)
        std::fill_n(covered_.begin() + static_cast<std::ptrdiff_t>(index(bx0, by, blocks_w_)), bx1 - bx0 + 1,
                    static_cast<unsigned char>(1));
    }
  coverage_known_ = true;
}

bool InverseCells::cellCovered(int cx, int cy) const {
  constexpr int per = kCell / kBlock;
  for (int by = cy * per; by < std::min(blocks_h_, (cy + 1) * per); ++by)
    for (int bx = cx * per; bx < std::min(blocks_w_, (cx + 1) * per); ++bx)
      if (covered_[index(bx, by, blocks_w_)]) return true;
  return false;
}

bool InverseCells::covered(int x, int y) const {
  if (!coverage_known_) return true;
  return covered_[index(std::min(x / kBlock, blocks_w_ - 1), std::min(y / kBlock, blocks_h_ - 1), blocks_w_)] != 0;
}

double InverseCells::certifiedShare() const {
  if (kinds_.empty()) return 0.0;
  return static_cast<double>(std::count(kinds_.begin(), kinds_.end(), kCertified)) /
         static_cast<double>(kinds_.size());
}

double InverseCells::emptyShare() const {
  if (kinds_.empty()) return 0.0;
  return static_cast<double>(std::count(kinds_.begin(), kinds_.end(), kEmpty)) /
         static_cast<double>(kinds_.size());
}

}  // namespace artcam
