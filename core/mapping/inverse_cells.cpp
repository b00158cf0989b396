// SPDX-License-Identifier: Apache-2.0
#include "core/mapping/inverse_cells.h"

#include "core/util/parallel.h"

#include <Eigen/LU>

#include <algorithm>
#include <array>
#include <cstring>
#include <atomic>
#include <cmath>
#include <limits>
#include <memory>
#include <type_traits>

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
  node_count_ = static_cast<size_t>(nodes_w_) * static_cast<size_t>(nodes_h_);
  static_assert(std::is_trivially_destructible_v<Node> && alignof(Node) <= 64);
  node_storage_ = takeScratch(sizeof(Node) * node_count_);
  nodes_ = static_cast<Node*>(node_storage_.data());
  std::uninitialized_fill_n(nodes_, node_count_, Node{});
  // Coverage first: the nodes of cells no part of the source frame reaches are never solved
  // (beyond a fold, a node without a preimage costs every Newton start in turn).
  buildCoverage(options.threads);
  // Nodes every other kCell first, and 2 × 2 cells certified as one (certifySupers): where
  // that holds, the nodes between are the patch's own (deriveNodes), with no Newton solve, and
  // the four cells no certification of their own. The rest are solved and certified one by one.
  solveNodes(options.threads, 2);
  crossDerivatives();
  certifySupers(options.threads);
  deriveNodes(options.threads);
  solveNodes(options.threads, 1);
  crossDerivatives();

  kinds_.assign(static_cast<size_t>(cells_w_) * static_cast<size_t>(cells_h_), kOpen);
  poly_storage_ = takeScratch(sizeof(CellPoly) * kinds_.size());
  polys_ = static_cast<CellPoly*>(poly_storage_.data());
  // Neighbouring cells share an edge and, along it, their patches (the edge's two nodes alone
  // define it): each edge midpoint is checked once here, not once by each cell.
  const double tol = options_.certify_tolerance_px;
  std::vector<unsigned char> across(node_count_, 0), down(node_count_, 0);
  ParallelOptions po;
  po.threads = options.threads;
  po.band_rows = 2;
  // An edge only cells of certified pairs of cells share needs no check.
  const auto alone = [&](int cx, int cy) {
    return cx >= 0 && cy >= 0 && cx < cells_w_ && cy < cells_h_ && !inSuper(cx, cy);
  };
  parallelForRows(nodes_h_, po, [&](int j0, int j1) {
    const Hermite mid(0.5);
    for (int j = j0; j < j1; ++j)
      for (int i = 0; i < nodes_w_; ++i) {
        const Node& a = node(i, j);
        if (!a.valid) continue;
        if (i + 1 < nodes_w_ && node(i + 1, j).valid && (alone(i, j - 1) || alone(i, j))) {
          const Node& b = node(i + 1, j);
          const Eigen::Vector2d p = mid.h0 * a.s + mid.h1 * b.s + mid.h2 * a.su + mid.h3 * b.su;
          across[index(i, j, nodes_w_)] = pointCertifies(p, Eigen::Vector2d((i + 0.5) * kCell, j * kCell), tol);
        }
        if (j + 1 < nodes_h_ && node(i, j + 1).valid && (alone(i - 1, j) || alone(i, j))) {
          const Node& c = node(i, j + 1);
          const Eigen::Vector2d p = mid.h0 * a.s + mid.h1 * c.s + mid.h2 * a.sv + mid.h3 * c.sv;
          down[index(i, j, nodes_w_)] = pointCertifies(p, Eigen::Vector2d(i * kCell, (j + 0.5) * kCell), tol);
        }
      }
  });
  parallelForRows(cells_h_, po, [&](int j0, int j1) {
    for (int cy = j0; cy < j1; ++cy)
      for (int cx = 0; cx < cells_w_; ++cx) {
        Kind& k = kinds_[index(cx, cy, cells_w_)];
        if (coverage_known_ && !cellCovered(cx, cy)) k = kEmpty;
        else if (inSuper(cx, cy)) k = patchBeyondReach(cellCorners(cx, cy)) ? kEmpty : kCertified;
        else if (hasPatch(cx, cy) && across[index(cx, cy, nodes_w_)] && across[index(cx, cy + 1, nodes_w_)] &&
                 down[index(cx, cy, nodes_w_)] && down[index(cx + 1, cy, nodes_w_)] &&
                 certify(cellCorners(cx, cy), cx * kCell, cy * kCell, kCell, tol, false))
          k = patchBeyondReach(cellCorners(cx, cy)) ? kEmpty : kCertified;
        if (k == kCertified) polyOf(cellCorners(cx, cy), polys_[index(cx, cy, cells_w_)]);
      }
  });
  coverOpenCells(options.threads);
  if (options.subdivide) refineOpenCells(options.threads);
}

bool InverseCells::solveNode(const Eigen::Vector2d& t, const Eigen::Vector2d* start, Node& out) const {
  Eigen::Vector2d s;
  Eigen::Matrix2d j;
  bool ok = start && newton_.solve(t, *start, s, kNodeIterations, &j);
  if (!ok && seed_) {
    Eigen::Vector2d seeded;
    if (seed_->evaluate(t, seeded, nullptr) && seeded.allFinite())
      ok = newton_.solve(t, seeded, s, kNodeIterations, &j);
  }
  if (!ok) ok = newton_.solveFromCentre(t, s, kNodeIterations, &j);
  return ok && finishNode(s, j, kCell, out);
}

bool InverseCells::finishNode(const Eigen::Vector2d& s, const Eigen::Matrix2d& j, double size, Node& out) const {
  const double det = j.determinant();
  if (!(std::abs(det) > 0.0)) return false;
  const Eigen::Matrix2d a = j.inverse();  // ∂s/∂t at the node (eq 2 inverted)
  if (!a.allFinite()) return false;
  out.s = s;
  out.su = size * a.col(0);
  out.sv = size * a.col(1);
  out.valid = true;
  return true;
}

void InverseCells::solveNodes(int threads, int stride) {
  // A node is needed when a cell it bounds may show something.
  const auto needed = [&](int i, int j) {
    if (!coverage_known_) return true;
    for (int cy = std::max(0, j - 1); cy <= std::min(cells_h_ - 1, j); ++cy)
      for (int cx = std::max(0, i - 1); cx <= std::min(cells_w_ - 1, i); ++cx)
        if (cellCovered(cx, cy)) return true;
    return false;
  };
  // Continuation: each node starts from the last solved node of its row (or, in the first
  // column, of the column) stepped by that node's derivative, two or three Newton iterations.
  // The first column runs down the frame, then the rows run across it in parallel.
  // `stride` 2: the nodes of even rows and columns only; 1: every node not yet valid (solved
  // or derived), each from the last valid one before it.
  int last = -1;
  for (int j = 0; j < nodes_h_; j += stride) {
    if (node(0, j).valid) {
      last = j;
      continue;
    }
    if (!needed(0, j)) continue;
    const Eigen::Vector2d t(0.0, static_cast<double>(j * kCell));
    Eigen::Vector2d start;
    if (last >= 0) start = node(0, last).s + (j - last) * node(0, last).sv;
    if (solveNode(t, last >= 0 ? &start : nullptr, node(0, j))) last = j;
  }
  ParallelOptions po;
  po.threads = threads;
  po.band_rows = 2;
  parallelForRows((nodes_h_ + stride - 1) / stride, po, [&](int r0, int r1) {
    for (int j = r0 * stride; j < r1 * stride && j < nodes_h_; j += stride) {
      int prev = node(0, j).valid ? 0 : -1;
      for (int i = stride; i < nodes_w_; i += stride) {
        if (node(i, j).valid) {
          prev = i;
          continue;
        }
        if (!needed(i, j)) continue;
        const Eigen::Vector2d t(static_cast<double>(i * kCell), static_cast<double>(j * kCell));
        Eigen::Vector2d start;
        if (prev >= 0) start = node(prev, j).s + (i - prev) * node(prev, j).su;
        if (solveNode(t, prev >= 0 ? &start : nullptr, node(i, j))) prev = i;
      }
    }
  });
  // Nodes stay kCell apart past the frame's far edge (up to kCell − 1 pixels beyond it), so
  // every cell has the same parametrisation; the frame's last cell uses part of it.
}

void InverseCells::crossDerivative(Node& n, double size) const {
  // size² ∂²s/∂x∂y from F(s(t)) = t: ∂A/∂y = −A (∂J/∂y) A with A = J⁻¹, and ∂J/∂y the forward
  // Jacobian's derivative along A's y column: analytic for a one-stage map (one pass over its
  // forms, where the difference below costs two evaluations), else a central difference over
  // ±h output pixels (error ~h² |∂³F|, far below the patch's). Exact to that where a
  // neighbour difference would be first order at the frame's edge.
  constexpr double h = 0.25;
  // Column by column: the comma initialiser of two vectors goes through a dynamic-size block
  // assignment that is not inlined.
  Eigen::Matrix2d a;
  a.col(0) = n.su / size;
  a.col(1) = n.sv / size;
  Eigen::Matrix2d dj;
  if (!newton_.forward().jacobianDerivative(n.s, a.col(1), dj)) {
    const Eigen::Vector2d dir = h * a.col(1);
    Eigen::Vector2d f;
    Eigen::Matrix2d jp, jm;
    if (!newton_.forward().evaluate(n.s + dir, f, &jp) ||
        !newton_.forward().evaluate(n.s - dir, f, &jm)) {
      n.valid = false;  // a pole within a quarter pixel: no patch here
      return;
    }
    dj = (jp - jm) / (2.0 * h);
  }
  const Eigen::Matrix2d da = -a * dj * a;
  n.suv = size * size * da.col(0);
  n.cross = true;
  if (!n.suv.allFinite()) n.valid = false;
}

void InverseCells::crossDerivatives() {
  ParallelOptions po;
  po.threads = options_.threads;
  po.band_rows = 4;
  parallelForRows(nodes_h_, po, [&](int j0, int j1) {
    for (int j = j0; j < j1; ++j)
      for (int i = 0; i < nodes_w_; ++i)
        if (node(i, j).valid && !node(i, j).cross) crossDerivative(node(i, j), kCell);
  });
}

void InverseCells::certifySupers(int threads) {
  supers_w_ = cells_w_ / 2;
  supers_h_ = cells_h_ / 2;
  supers_.assign(static_cast<size_t>(supers_w_) * static_cast<size_t>(supers_h_), 0);
  ParallelOptions po;
  po.threads = threads;
  po.band_rows = 1;
  parallelForRows(supers_h_, po, [&](int b0, int b1) {
    for (int b = b0; b < b1; ++b)
      for (int a = 0; a < supers_w_; ++a) {
        const int cx = 2 * a, cy = 2 * b;
        if (coverage_known_ && !cellCovered(cx, cy) && !cellCovered(cx + 1, cy) && !cellCovered(cx, cy + 1) &&
            !cellCovered(cx + 1, cy + 1))
          continue;  // four empty cells
        Node n[4];
        if (!superCorners(a, b, n)) continue;
        // At half the tolerance, as the quadtree's squares (inverse_subcells.cpp): the error
        // between the checked points of the larger square may exceed what they show a little.
        supers_[index(a, b, supers_w_)] = certify({&n[0], &n[1], &n[2], &n[3]}, cx * kCell, cy * kCell, 2 * kCell,
                                                  0.5 * options_.certify_tolerance_px)
                                              ? 1
                                              : 0;
      }
  });
}

bool InverseCells::superCorners(int a, int b, Node out[4]) const {
  const Node* n[4] = {&node(2 * a, 2 * b), &node(2 * a + 2, 2 * b), &node(2 * a, 2 * b + 2),
                      &node(2 * a + 2, 2 * b + 2)};
  for (int k = 0; k < 4; ++k) {
    if (!n[k]->valid) return false;
    out[k] = *n[k];  // derivatives per two cells
    out[k].su *= 2.0;
    out[k].sv *= 2.0;
    out[k].suv *= 4.0;
  }
  return true;
}

void InverseCells::deriveNodes(int threads) {
  // Node (i, j) of a certified pair of cells, the patch's value and derivatives at local
  // (u, v) ∈ {0, ½, 1}² of it (per cell: half and a quarter of the pair's). On an edge the
  // patch and its derivatives there are the edge's two nodes' alone (the Hermite weights of
  // the far ones are exactly 0), so both pairs that share it give the same bits.
  ParallelOptions po;
  po.threads = threads;
  po.band_rows = 2;
  parallelForRows(nodes_h_, po, [&](int j0, int j1) {
    for (int j = j0; j < j1; ++j)
      for (int i = 0; i < nodes_w_; ++i) {
        Node& out = node(i, j);
        if (out.valid || (i % 2 == 0 && j % 2 == 0)) continue;  // solved, or a pair's corner
        // The pairs that hold it (one or two along each axis: pair a spans nodes 2a … 2a + 2),
        // the first certified.
        for (int b = std::max(0, (j - 1) / 2); b <= std::min(supers_h_ - 1, j / 2) && !out.valid; ++b)
          for (int a = std::max(0, (i - 1) / 2); a <= std::min(supers_w_ - 1, i / 2) && !out.valid; ++a) {
            if (!supers_[index(a, b, supers_w_)]) continue;
            Node n[4];
            superCorners(a, b, n);
            patchNode({&n[0], &n[1], &n[2], &n[3]}, 0.5 * (i - 2 * a), 0.5 * (j - 2 * b), out);
          }
      }
  });
}

void InverseCells::patchNode(const Corners& n, double u, double v, Node& out) {
  const Node &a = *n.a, &b = *n.b, &c = *n.c, &d = *n.d;
  const Hermite hu(u), hv(v);
  // The Hermite basis's derivatives at t.
  const auto slope = [](double t) {
    return std::array<double, 4>{6 * t * t - 6 * t, -6 * t * t + 6 * t, 3 * t * t - 4 * t + 1, 3 * t * t - 2 * t};
  };
  const std::array<double, 4> du = slope(u), dv = slope(v);
  // Along the left (a, c) and right (b, d) edges at v: values and ∂/∂u, then their ∂/∂v.
  const Eigen::Vector2d f0 = hv.h0 * a.s + hv.h1 * c.s + hv.h2 * a.sv + hv.h3 * c.sv;
  const Eigen::Vector2d f1 = hv.h0 * b.s + hv.h1 * d.s + hv.h2 * b.sv + hv.h3 * d.sv;
  const Eigen::Vector2d d0 = hv.h0 * a.su + hv.h1 * c.su + hv.h2 * a.suv + hv.h3 * c.suv;
  const Eigen::Vector2d d1 = hv.h0 * b.su + hv.h1 * d.su + hv.h2 * b.suv + hv.h3 * d.suv;
  const Eigen::Vector2d f0v = dv[0] * a.s + dv[1] * c.s + dv[2] * a.sv + dv[3] * c.sv;
  const Eigen::Vector2d f1v = dv[0] * b.s + dv[1] * d.s + dv[2] * b.sv + dv[3] * d.sv;
  const Eigen::Vector2d d0v = dv[0] * a.su + dv[1] * c.su + dv[2] * a.suv + dv[3] * c.suv;
  const Eigen::Vector2d d1v = dv[0] * b.su + dv[1] * d.su + dv[2] * b.suv + dv[3] * d.suv;
  out.s = hu.h0 * f0 + hu.h1 * f1 + hu.h2 * d0 + hu.h3 * d1;
  out.su = 0.5 * (du[0] * f0 + du[1] * f1 + du[2] * d0 + du[3] * d1);
  out.sv = 0.5 * (hu.h0 * f0v + hu.h1 * f1v + hu.h2 * d0v + hu.h3 * d1v);
  out.suv = 0.25 * (du[0] * f0v + du[1] * f1v + du[2] * d0v + du[3] * d1v);
  out.cross = true;
  out.valid = out.s.allFinite() && out.su.allFinite() && out.sv.allFinite() && out.suv.allFinite();
}

bool InverseCells::inSuper(int cx, int cy) const {
  const int a = cx / 2, b = cy / 2;
  return a < supers_w_ && b < supers_h_ && supers_[index(a, b, supers_w_)] != 0 && hasPatch(cx, cy);
}

bool InverseCells::hasPatch(int cx, int cy) const {
  return node(cx, cy).valid && node(cx + 1, cy).valid && node(cx, cy + 1).valid &&
         node(cx + 1, cy + 1).valid;
}

// Along the patch's left (a, c) and right (b, d) edges at local v: the value and ∂/∂u.
void InverseCells::edgesAt(const Corners& n, double v, Eigen::Vector2d& f0, Eigen::Vector2d& f1,
                           Eigen::Vector2d& d0, Eigen::Vector2d& d1) {
  const Hermite hv(v);
  const Node &a = *n.a, &b = *n.b, &c = *n.c, &d = *n.d;
  f0 = hv.h0 * a.s + hv.h1 * c.s + hv.h2 * a.sv + hv.h3 * c.sv;
  f1 = hv.h0 * b.s + hv.h1 * d.s + hv.h2 * b.sv + hv.h3 * d.sv;
  d0 = hv.h0 * a.su + hv.h1 * c.su + hv.h2 * a.suv + hv.h3 * c.suv;
  d1 = hv.h0 * b.su + hv.h1 * d.su + hv.h2 * b.suv + hv.h3 * d.suv;
}

void InverseCells::rowOf(const Corners& n, double v, CellRow& out) {
  Eigen::Vector2d f0, f1, d0, d1;
  edgesAt(n, v, f0, f1, d0, d1);
  // The cubic through them in u: c0 + u (c1 + u (c2 + u c3)).
  const Eigen::Vector2d c2 = 3.0 * (f1 - f0) - 2.0 * d0 - d1;
  const Eigen::Vector2d c3 = 2.0 * (f0 - f1) + d0 + d1;
  out.x[0] = f0.x(), out.x[1] = d0.x(), out.x[2] = c2.x(), out.x[3] = c3.x();
  out.y[0] = f0.y(), out.y[1] = d0.y(), out.y[2] = c2.y(), out.y[3] = c3.y();
}

void InverseCells::polyOf(const Corners& n, CellPoly& out) {
  // rowOf in the power basis of v: the Hermite basis functions' coefficients (1, v, v², v³)
  // blend the edges' values and derivatives; the row cubic's coefficients are linear in those.
  static constexpr double kH[4][4] = {{1, 0, -3, 2}, {0, 0, 3, -2}, {0, 1, -2, 1}, {0, 0, -1, 1}};
  const Node &a = *n.a, &b = *n.b, &c = *n.c, &d = *n.d;
  const Eigen::Vector2d anchor(static_cast<float>(a.s.x()), static_cast<float>(a.s.y()));
  out.anchor_x = static_cast<float>(anchor.x());
  out.anchor_y = static_cast<float>(anchor.y());
  for (int l = 0; l < 4; ++l) {
    const double h0 = kH[0][l], h1 = kH[1][l], h2 = kH[2][l], h3 = kH[3][l];
    // The anchor enters the values only through the constant term (h0 + h1 = 1 at l = 0).
    const Eigen::Vector2d base = l == 0 ? anchor : Eigen::Vector2d::Zero();
    const Eigen::Vector2d f0 = h0 * a.s + h1 * c.s + h2 * a.sv + h3 * c.sv - base;
    const Eigen::Vector2d f1 = h0 * b.s + h1 * d.s + h2 * b.sv + h3 * d.sv - base;
    const Eigen::Vector2d d0 = h0 * a.su + h1 * c.su + h2 * a.suv + h3 * c.suv;
    const Eigen::Vector2d d1 = h0 * b.su + h1 * d.su + h2 * b.suv + h3 * d.suv;
    const Eigen::Vector2d k[4] = {f0, d0, 3.0 * (f1 - f0) - 2.0 * d0 - d1, 2.0 * (f0 - f1) + d0 + d1};
    for (int i = 0; i < 4; ++i) {
      out.p[l][i] = static_cast<float>(k[i].x());
      out.p[l][4 + i] = static_cast<float>(k[i].y());
    }
  }
}

void InverseCells::row(int cx, int y, CellRow& out) const {
  const int cy = std::min(y / kCell, cells_h_ - 1);
  rowOf(cellCorners(cx, cy), (y + 0.5 - cy * kCell) / kCell, out);
}

Eigen::Vector2d InverseCells::patchAt(const Corners& n, double u, double v) {
  Eigen::Vector2d f0, f1, d0, d1;
  edgesAt(n, v, f0, f1, d0, d1);
  const Hermite hu(u);
  return hu.h0 * f0 + hu.h1 * f1 + hu.h2 * d0 + hu.h3 * d1;
}

namespace {

// The certification test at one point whose forward map f and Jacobian j the caller has:
// one Newton step δ = J⁻¹ (f − t) within `tol` on each axis, the Jacobian's determinant of the
// centre's sign (the centre's fold; the pole side is the caller's). False for NaN, as on the
// pole.
bool stepCertifies(double fx, double fy, double j00, double j01, double j10, double j11,
                   const Eigen::Vector2d& t, bool det_positive, double tol) {
  const double det = j00 * j11 - j01 * j10;
  const double rx = fx - t.x(), ry = fy - t.y();
  const double stepx = (j11 * rx - j01 * ry) / det, stepy = (j00 * ry - j10 * rx) / det;
  return (det > 0.0) == det_positive && std::abs(stepx) <= tol && std::abs(stepy) <= tol;
}

}  // namespace

bool InverseCells::pointCertifies(const Eigen::Vector2d& p, const Eigen::Vector2d& t, double tol) const {
  const CentreReference& centre = newton_.centre();
  Eigen::Vector2d f;
  Eigen::Matrix2d j;
  unsigned signs = 0;
  if (!newton_.forward().evaluate(p, f, &j, &signs)) return false;
  return signs == centre.denominator_signs &&
         stepCertifies(f.x(), f.y(), j(0, 0), j(0, 1), j(1, 0), j(1, 1), t, centre.det_positive, tol);
}

bool InverseCells::certify(const Corners& n, double x0, double y0, double size, double tol,
                           bool edges) const {
  // The edges' midpoints (a cubic Hermite's error along an edge, ∝ u²(1 − u)², peaks there),
  // the centre, and the four points u, v ∈ {1/2 ± 1/√12} where an error in the cross
  // derivatives, ∝ u(1 − u)(1 − 2u) · v(1 − v)(1 − 2v), peaks and the centre sees nothing.
  // Grouped by v, so each row of points interpolates the patch's edges once.
  constexpr double lo = 0.5 - 0.28867513459481287, hi = 0.5 + 0.28867513459481287;
  struct PointRow {
    double v;
    int count;
    double u[3];
  };
  static constexpr PointRow kRows[5] = {{0.0, 1, {0.5, 0, 0}},
                                        {1.0, 1, {0.5, 0, 0}},
                                        {0.5, 3, {0.5, 0.0, 1.0}},
                                        {lo, 2, {lo, hi, 0}},
                                        {hi, 2, {lo, hi, 0}}};
  // The points first, then one batch of forward evaluations (RationalMap::evaluateBatch):
  // the nine Newton steps share its passes instead of paying one evaluation each.
  double pu[RationalMap::kBatch], pv[RationalMap::kBatch], tu[RationalMap::kBatch], tv[RationalMap::kBatch];
  int m = 0;
  for (const PointRow& row : kRows) {
    if (!edges && (row.v == 0.0 || row.v == 1.0)) continue;
    Eigen::Vector2d f0, f1, d0, d1;
    edgesAt(n, row.v, f0, f1, d0, d1);
    // Without the edges, the middle row's points on them (u = 0, 1) are left out too.
    const int count = !edges && row.v == 0.5 ? 1 : row.count;
    for (int k = 0; k < count; ++k, ++m) {
      const double u = row.u[k];
      const Hermite hu(u);
      const Eigen::Vector2d p = hu.h0 * f0 + hu.h1 * f1 + hu.h2 * d0 + hu.h3 * d1;
      pu[m] = p.x();
      pv[m] = p.y();
      tu[m] = x0 + u * size;
      tv[m] = y0 + row.v * size;
    }
  }
  RationalMap::Batch b;
  for (int k = m; k < RationalMap::kBatch; ++k) pu[k] = pu[0], pv[k] = pv[0];
  if (!newton_.forward().evaluateBatch(pu, pv, b)) {
    for (int k = 0; k < m; ++k)
      if (!pointCertifies(Eigen::Vector2d(pu[k], pv[k]), Eigen::Vector2d(tu[k], tv[k]), tol)) return false;
    return true;
  }
  // pointCertifies' tests on the batch (one stage: its denominator's sign is the pole test).
  const CentreReference& centre = newton_.centre();
  const bool den_negative = (centre.denominator_signs & 1u) != 0;
  for (int k = 0; k < m; ++k)
    if ((b.den[k] < 0.0) != den_negative ||
        !stepCertifies(b.x[k], b.y[k], b.j00[k], b.j01[k], b.j10[k], b.j11[k], {tu[k], tv[k]},
                       centre.det_positive, tol))
      return false;
  return true;
}

bool InverseCells::patchBeyondReach(const Corners& corners) const {
  // The patch passes through its corners: one within reach and the patch is not beyond it
  // (so the hull below is built only near the edge of what the frame reaches).
  const double m = reach_px_ + options_.certify_tolerance_px;
  const Eigen::Vector2d& first = corners.a->s;
  if (first.x() >= -m && first.y() >= -m && first.x() <= source_px_.width + m && first.y() <= source_px_.height + m)
    return false;
  // The Bézier control net of the bicubic Hermite patch: corners, corners ± derivative / 3,
  // and the inner four from the cross derivatives; the patch lies in its convex hull.
  const Node* n[2][2] = {{corners.a, corners.c}, {corners.b, corners.d}};
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
  return hi.x() < -m || hi.y() < -m || lo.x() > source_px_.width + m || lo.y() > source_px_.height + m;
}

bool InverseCells::latticeQuadBox(const Eigen::Vector2d* mapped, int pw, int i, int j,
                                  Eigen::Vector2d& lo, Eigen::Vector2d& hi) const {
  quadBox(mapped[index(i, j, pw)], mapped[index(i + 1, j, pw)], mapped[index(i, j + 1, pw)],
          mapped[index(i + 1, j + 1, pw)], lo, hi);
  return !(hi.x() < 0 || hi.y() < 0 || lo.x() >= target_px_.width || lo.y() >= target_px_.height);
}

void InverseCells::buildCoverage(int threads) {
  // The source frame grown by the largest reach, as a lattice of quads kLattice source pixels
  // apart, mapped forward with the Jacobian. The reach follows from the inverse's scale
  // (source pixels per output pixel) in and near the frame: minifying filters reach further.
  constexpr double kMaxScale = 64.0;
  const double margin = options_.reach_px + 4.0 * kMaxScale;
  const int qw = static_cast<int>(std::ceil((source_px_.width + 2 * margin) / kLattice));
  const int qh = static_cast<int>(std::ceil((source_px_.height + 2 * margin) / kLattice));
  const int pw = qw + 1, ph = qh + 1;
  const auto at = [&](int i, int j) {
    return Eigen::Vector2d(-margin + i * kLattice, -margin + j * kLattice);
  };
  const size_t points = static_cast<size_t>(pw) * static_cast<size_t>(ph);
  const size_t blocks = static_cast<size_t>(blocks_w_) * static_cast<size_t>(blocks_h_);
  const size_t quads = static_cast<size_t>(qw) * static_cast<size_t>(qh);
  const size_t cells = static_cast<size_t>(cells_w_) * static_cast<size_t>(cells_h_);
  const auto lines = [](size_t bytes) { return (bytes + 63) / 64 * 64; };
  const size_t points_bytes = lines(points * sizeof(Eigen::Vector2d));
  const size_t quads_bytes = lines(quads * sizeof(QuadBlocks));
  coverage_storage_ = takeScratch(points_bytes + quads_bytes + lines(points) + lines(cells) + blocks);
  unsigned char* const storage = static_cast<unsigned char*>(coverage_storage_.data());
  Eigen::Vector2d* const mapped = reinterpret_cast<Eigen::Vector2d*>(storage);  // every point written below
  QuadBlocks* const quad_blocks = reinterpret_cast<QuadBlocks*>(storage + points_bytes);  // every quad, likewise
  unsigned char* const ok = storage + points_bytes + quads_bytes;                         // every point, likewise
  unsigned char* const covered_cells = ok + lines(points);
  unsigned char* const covered = covered_cells + lines(cells);  // cleared by coverOpenCells
  std::vector<double> band_scale(static_cast<size_t>(ph), 1.0);
  const unsigned centre_signs = newton_.centre().denominator_signs;
  const double near = 2.0 * kCell;
  ParallelOptions po;
  po.threads = threads;
  po.band_rows = 8;
  const RationalMap& forward = newton_.forward();
  parallelForRows(ph, po, [&](int j0, int j1) {
    // A one-stage map (all but chains) in batches along the row: evaluateBatch is
    // evaluateSingle's arithmetic without its branches, so the same numbers for less than
    // point by point.
    RationalMap::Batch batch;
    double bu[RationalMap::kBatch], bv[RationalMap::kBatch];
    for (int j = j0; j < j1; ++j) {
      // The row's largest scale in a register, stored once: a store a point into band_scale,
      // whose cache lines neighbouring bands share, would have the threads contend for them.
      double row_scale = 1.0;
      for (int i0 = 0; i0 < pw; i0 += RationalMap::kBatch) {
        const int count = std::min(RationalMap::kBatch, pw - i0);
        for (int b = 0; b < RationalMap::kBatch; ++b) {
          const Eigen::Vector2d s = at(i0 + std::min(b, count - 1), j);
          bu[b] = s.x();
          bv[b] = s.y();
        }
        const bool batched = forward.evaluateBatch(bu, bv, batch);
        for (int b = 0; b < count; ++b) {
          const int i = i0 + b;
          const Eigen::Vector2d s(bu[b], bv[b]);
          Eigen::Vector2d f;
          Eigen::Matrix2d jac;
          unsigned signs = 0;
          bool good;
          if (batched) {
            // evaluateSingle's tests: a denominator that is not zero, a finite target and Jacobian.
            f = Eigen::Vector2d(batch.x[b], batch.y[b]);
            jac << batch.j00[b], batch.j01[b], batch.j10[b], batch.j11[b];
            signs = batch.den[b] < 0.0 ? 1u : 0u;
            good = std::abs(batch.den[b]) > 0.0 && f.allFinite() && jac.allFinite();
          } else {
            good = forward.evaluate(s, f, &jac, &signs);
          }
          good = good && signs == centre_signs;
          mapped[index(i, j, pw)] = f;
          // 1: the centre's side of the pole curves and its fold; 2: beyond a fold.
          const double det = jac.determinant();
          ok[index(i, j, pw)] = good ? ((det > 0.0) == newton_.centre().det_positive ? 1 : 2) : 0;
          if (good && s.x() > -near && s.y() > -near && s.x() < source_px_.width + near &&
              s.y() < source_px_.height + near) {
            const double scale = std::abs(det) > 0.0 ? (jac.inverse()).cwiseAbs().maxCoeff() : kMaxScale;
            row_scale = std::max(row_scale, std::isfinite(scale) ? scale : kMaxScale);
          }
        }
      }
      band_scale[static_cast<size_t>(j)] = row_scale;
    }
  });
  const double scale = std::min(kMaxScale, *std::max_element(band_scale.begin(), band_scale.end()));
  reach_px_ = options_.reach_px + 4.0 * scale;
  int i0 = 0, i1 = -1, j0 = 0, j1 = -1;  // the quads within reach
  reachableQuads(margin, qw, qh, i0, i1, j0, j1);
  if (frameInsideImage(mapped, ok, pw, i0, i1, j0, j1)) return;  // every block covered: no coverage needed
  std::memset(covered_cells, 0, cells);
  // The quads in bands of rows on every thread. Each marks the cells its box touches and
  // keeps its blocks for coverOpenCells. The blocks by truncation, not floor (a call at this
  // build's baseline ISA): the box meets the output, so hi ≥ 0, and lo is clamped to 0 first,
  // where the two agree.
  const double width = target_px_.width, height = target_px_.height;
  std::atomic<bool> unbounded{false};
  parallelForRows(qh, po, [&](int ja, int jb) {
    constexpr int per = kCell / kBlock;
    for (int j = ja; j < jb && !unbounded.load(std::memory_order_relaxed); ++j) {
      QuadBlocks* const row = &quad_blocks[index(0, j, qw)];
      std::fill(row, row + qw, QuadBlocks{});
      if (j < j0 || j > j1) continue;  // only quads within the reach of the frame
      const Eigen::Vector2d* const top = &mapped[index(0, j, pw)];
      const Eigen::Vector2d* const bottom = top + pw;
      const unsigned char* const ok_top = &ok[index(0, j, pw)];
      const unsigned char* const ok_bottom = ok_top + pw;
      for (int i = i0; i <= i1; ++i) {
        // A corner beyond a pole curve: the quad's image is unbounded, claim nothing.
        if (!ok_top[i] || !ok_top[i + 1] || !ok_bottom[i] || !ok_bottom[i + 1]) {
          unbounded.store(true, std::memory_order_relaxed);
          return;
        }
        Eigen::Vector2d lo, hi;
        quadBox(top[i], top[i + 1], bottom[i], bottom[i + 1], lo, hi);
        if (hi.x() < 0 || hi.y() < 0 || lo.x() >= width || lo.y() >= height) continue;
        const QuadBlocks q{lo.x() <= 0.0 ? 0 : static_cast<int>(lo.x() / kBlock),
                           lo.y() <= 0.0 ? 0 : static_cast<int>(lo.y() / kBlock),
                           std::min(blocks_w_ - 1, static_cast<int>(std::min(hi.x(), 1e9) / kBlock)),
                           std::min(blocks_h_ - 1, static_cast<int>(std::min(hi.y(), 1e9) / kBlock))};
        row[i] = q;
        // Bands mark concurrently; every write stores the same 1.
        for (int cy = q.y0 / per; cy <= q.y1 / per; ++cy)
          for (int cx = q.x0 / per; cx <= q.x1 / per; ++cx) {
            std::atomic_ref<unsigned char> cell(covered_cells[index(cx, cy, cells_w_)]);
            if (!cell.load(std::memory_order_relaxed)) cell.store(1, std::memory_order_relaxed);
          }
      }
    }
  });
  if (unbounded.load()) return;
  covered_cells_ = covered_cells;
  covered_ = covered;
  quad_blocks_ = quad_blocks;
  coverage_known_ = true;
  lattice_margin_ = margin;
  lattice_w_ = qw;
  lattice_h_ = qh;
  lattice_mapped_ = mapped;
}

bool InverseCells::latticeReaches(int k, double margin, double size) const {
  const double lo = -margin + k * kLattice, hi = lo + kLattice;
  return !(hi < -reach_px_ || lo > size + reach_px_);
}

void InverseCells::reachableQuads(double margin, int qw, int qh, int& i0, int& i1, int& j0, int& j1) const {
  i0 = 0, i1 = qw - 1, j0 = 0, j1 = qh - 1;
  while (i0 <= i1 && !latticeReaches(i0, margin, source_px_.width)) ++i0;
  while (i1 >= i0 && !latticeReaches(i1, margin, source_px_.width)) --i1;
  while (j0 <= j1 && !latticeReaches(j0, margin, source_px_.height)) ++j0;
  while (j1 >= j0 && !latticeReaches(j1, margin, source_px_.height)) --j1;
}

bool InverseCells::frameInsideImage(const Eigen::Vector2d* mapped, const unsigned char* ok,
                                    int pw, int i0, int i1, int j0, int j1) const {
  if (i0 > i1 || j0 > j1) return false;
  const Eigen::Vector2d& centre = newton_.centre().target;
  if (!(centre.x() >= 0.0 && centre.y() >= 0.0 && centre.x() < target_px_.width && centre.y() < target_px_.height))
    return false;
  for (int j = j0; j <= j1 + 1; ++j)
    for (int i = i0; i <= i1 + 1; ++i)
      if (ok[index(i, j, pw)] != 1) return false;  // a pole curve or a fold within reach
  for (int j = j0; j <= j1; ++j)
    for (int i = i0; i <= i1; ++i) {
      if (j != j0 && j != j1 && i != i0 && i != i1) continue;  // the ring of quads only
      Eigen::Vector2d lo, hi;
      if (latticeQuadBox(mapped, pw, i, j, lo, hi)) return false;  // the boundary's image meets the output
    }
  return true;
}

bool InverseCells::cellCovered(int cx, int cy) const { return covered_cells_[index(cx, cy, cells_w_)] != 0; }

void InverseCells::coverOpenCells(int threads) {
  if (!coverage_known_ || std::find(kinds_.begin(), kinds_.end(), kOpen) == kinds_.end()) return;
  const size_t blocks = static_cast<size_t>(blocks_w_) * static_cast<size_t>(blocks_h_);
  std::memset(covered_, 0, blocks);
  ParallelOptions po;
  po.threads = threads;
  po.band_rows = 8;
  parallelForRows(lattice_h_, po, [&](int j0, int j1) {
    constexpr int per = kCell / kBlock;
    for (int j = j0; j < j1; ++j)
      for (int i = 0; i < lattice_w_; ++i) {
        const QuadBlocks& q = quad_blocks_[index(i, j, lattice_w_)];
        // The quad's blocks in each open cell its box touches (none when x0 > x1).
        for (int cy = q.y0 / per; cy <= q.y1 / per && q.x0 <= q.x1; ++cy)
          for (int cx = q.x0 / per; cx <= q.x1 / per; ++cx) {
            if (kind(cx, cy) != kOpen) continue;
            // Bands mark concurrently; every write stores the same 1.
            for (int by = std::max(q.y0, cy * per); by <= std::min(q.y1, cy * per + per - 1); ++by) {
              unsigned char* row = &covered_[index(0, by, blocks_w_)];
              for (int bx = std::max(q.x0, cx * per); bx <= std::min(q.x1, cx * per + per - 1); ++bx)
                std::atomic_ref<unsigned char>(row[bx]).store(1, std::memory_order_relaxed);
            }
          }
      }
  });
}

void InverseCells::coveredRun(int x, int y, int n, unsigned char* out) const {
  if (!coverage_known_) {
    std::fill(out, out + n, static_cast<unsigned char>(1));
    return;
  }
  const unsigned char* blocks = &covered_[index(0, std::min(y / kBlock, blocks_h_ - 1), blocks_w_)];
  const int cx = std::min(x / kCell, cells_w_ - 1), cy = std::min(y / kCell, cells_h_ - 1);
  const unsigned char* fine =
      refined(cx, cy) ? refinedAt(cx, cy).covered + std::min((y - cy * kCell) / kFine, kFines - 1) * kFines : nullptr;
  for (int i = 0; i < n; ++i) {
    const int px = x + i;
    const bool block = blocks[std::min(px / kBlock, blocks_w_ - 1)] != 0;
    out[i] = block && (!fine || fine[std::min((px - cx * kCell) / kFine, kFines - 1)] != 0) ? 1 : 0;
  }
}

double InverseCells::certifiedShare() const {
  if (kinds_.empty()) return 0.0;
  double cells = static_cast<double>(std::count(kinds_.begin(), kinds_.end(), kCertified));
  for (int k = 0; k < refined_count_; ++k)
    cells += static_cast<double>(std::count(std::begin(refined_[k].kinds), std::end(refined_[k].kinds), kCertified)) /
             (kSubs * kSubs);
  return cells / static_cast<double>(kinds_.size());
}

double InverseCells::emptyShare() const {
  if (kinds_.empty()) return 0.0;
  double cells = static_cast<double>(std::count(kinds_.begin(), kinds_.end(), kEmpty));
  for (int k = 0; k < refined_count_; ++k)
    cells += static_cast<double>(std::count(std::begin(refined_[k].kinds), std::end(refined_[k].kinds), kEmpty)) /
             (kSubs * kSubs);
  return cells / static_cast<double>(kinds_.size());
}

}  // namespace artcam
