// SPDX-License-Identifier: Apache-2.0
// InverseCells' open cells (inverse_cells.h): subcells certified by the cells' rule, and
// coverage at kFine pixels where the edge of what the camera sees crosses them.
#include "core/mapping/inverse_cells.h"

#include "core/util/parallel.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <iterator>
#include <new>
#include <type_traits>

namespace artcam {
namespace {

// A subcell's node starts from its cell's patch or a neighbour two or three steps away; one that
// needs more has no preimage nearby, and its subcells take the per-pixel path.
constexpr int kSubIterations = 8;

// Lattice quads split kSplit × kSplit for the open cells' coverage (kLattice / kSplit source
// pixels a side; coverFine).
constexpr int kSplit = 2;

}  // namespace

bool InverseCells::hasSubPatch(int cx, int cy, int sx, int sy) const {
  const Refined& r = refinedAt(cx, cy);
  const int size = r.side[sy * kSubs + sx], qx = sx / size * size, qy = sy / size * size;
  const int w = kSubs + 1;
  return r.nodes[qy * w + qx].valid && r.nodes[qy * w + qx + size].valid &&
         r.nodes[(qy + size) * w + qx].valid && r.nodes[(qy + size) * w + qx + size].valid;
}

void InverseCells::subRow(int cx, int sx, int y, SubRow& out) const {
  const int cy = std::min(y / kCell, cells_h_ - 1);
  const int sy = std::min((y - cy * kCell) / kSub, kSubs - 1);
  const Refined& r = refinedAt(cx, cy);
  // The square that decided the subcell: squares of the quadtree are aligned to their size.
  const int size = r.side[sy * kSubs + sx], qx = sx / size * size, qy = sy / size * size;
  Node n[4];
  r.square(qx, qy, size, n);
  out.size = size * kSub;
  out.x0 = cx * kCell + qx * kSub;
  rowOf({&n[0], &n[1], &n[2], &n[3]}, (y + 0.5 - cy * kCell - qy * kSub) / out.size, out.cubic);
}

InverseCells::SubSquare InverseCells::subSquare(int cx, int cy, int sx, int sy) const {
  const Refined& r = refinedAt(cx, cy);
  const int size = r.side[sy * kSubs + sx], qx = sx / size * size, qy = sy / size * size;
  return {&square_polys_[static_cast<size_t>(r.poly_base + r.poly[sy * kSubs + sx])], cx * kCell + qx * kSub,
          cy * kCell + qy * kSub, size * kSub};
}

void InverseCells::refineOpenCells(int threads) {
  refined_index_.assign(kinds_.size(), -1);
  int count = 0;
  for (size_t k = 0; k < kinds_.size(); ++k)
    if (kinds_[k] == kOpen) refined_index_[k] = count++;
  if (count == 0) {
    refined_index_.clear();
    return;
  }
  // Left uninitialised here and set up by the cells in parallel: a strong barrel refines a
  // third of its cells, ~13 MB that one thread would otherwise zero and first touch alone.
  static_assert(std::is_trivially_destructible_v<Refined> && alignof(Refined) <= 64);  // a scratch block's
  refined_storage_ = takeScratch(sizeof(Refined) * static_cast<size_t>(count));
  refined_ = static_cast<Refined*>(refined_storage_.data());
  refined_count_ = count;
  std::vector<std::array<int, 2>> cells;
  cells.reserve(static_cast<size_t>(count));
  for (int cy = 0; cy < cells_h_; ++cy)
    for (int cx = 0; cx < cells_w_; ++cx)
      if (refined(cx, cy)) cells.push_back({cx, cy});
  ParallelOptions po;
  po.threads = threads;
  po.band_rows = 16;
  // Finer coverage only where a node of the cell has no preimage: elsewhere the edge of what
  // the camera sees is at least a cell away (coverage is a bound, so all covered is safe).
  std::atomic<bool> any_fine{false};
  parallelForRows(count, po, [&](int k0, int k1) {
    for (int k = k0; k < k1; ++k) {
      const auto [cx, cy] = cells[static_cast<size_t>(k)];
      Refined& r = *new (&refined_[static_cast<size_t>(k)]) Refined;  // its nodes not yet valid
      r.fine = coverage_known_ && !hasPatch(cx, cy);
      if (r.fine) any_fine.store(true, std::memory_order_relaxed);
      std::fill(std::begin(r.covered), std::end(r.covered), r.fine ? 0 : 1);
    }
  });
  if (any_fine.load()) coverFine(threads);
  // Uninitialised: each cell writes its own squares' patches there.
  static_assert(std::is_trivially_default_constructible_v<CellPoly> && alignof(CellPoly) <= 64);
  square_storage_ = takeScratch(sizeof(CellPoly) * static_cast<size_t>(count) * kSubs * kSubs);
  square_polys_ = static_cast<CellPoly*>(square_storage_.data());
  std::atomic<int> next_poly{0};
  po.band_rows = 1;
  parallelForRows(static_cast<int>(cells.size()), po, [&](int k0, int k1) {
    for (int k = k0; k < k1; ++k) {
      const auto [cx, cy] = cells[static_cast<size_t>(k)];
      refineCell(cx, cy, refined_[static_cast<size_t>(refined_index_[index(cx, cy, cells_w_)])], next_poly);
    }
  });
}

void InverseCells::coverFine(int threads) {
  // The open cells' coverage at kFine pixels: each lattice quad whose box (buildCoverage's)
  // reaches a cell that needs it, split into kSplit² quads of kLattice / kSplit = 16 source
  // pixels mapped forward, each marking the blocks within a margin of its corners' polygon
  // (markFineQuad). The margin: an edge's image sags from its chord by |∂²F| h² / 8, which
  // the split points' second differences measure (twice over), and a fold inside the quad
  // bulges its image by a term of the same order (the strong barrel's: 0.03 px at 16 px),
  // within the half pixel added for any map smooth at that scale. A split point beyond a pole
  // curve falls back to the whole quad's box. Not quads of 8 pixels: they mark as tightly
  // but are four times as many to map.
  ParallelOptions po;
  po.threads = threads;
  po.band_rows = 4;
  parallelForRows(lattice_h_, po, [&](int j0, int j1) {
    for (int j = j0; j < j1; ++j)
      for (int i = 0; i < lattice_w_; ++i) coverQuadFine(i, j);
  });
}

void InverseCells::coverQuadFine(int i, int j) {
  if (!latticeReaches(i, lattice_margin_, source_px_.width) || !latticeReaches(j, lattice_margin_, source_px_.height))
    return;
  Eigen::Vector2d lo, hi;
  if (!latticeQuadBox(lattice_mapped_, lattice_w_ + 1, i, j, lo, hi)) return;
  const int cx0 = std::max(0, static_cast<int>(std::floor(lo.x() / kCell)));
  const int cy0 = std::max(0, static_cast<int>(std::floor(lo.y() / kCell)));
  const int cx1 =
      std::min(cells_w_ - 1, static_cast<int>(std::floor(std::min(hi.x(), 1e9) / kCell)));
  const int cy1 =
      std::min(cells_h_ - 1, static_cast<int>(std::floor(std::min(hi.y(), 1e9) / kCell)));
  bool touches = false;
  for (int cy = cy0; cy <= cy1 && !touches; ++cy)
    for (int cx = cx0; cx <= cx1 && !touches; ++cx)
      touches = refined(cx, cy) && refinedAt(cx, cy).fine;
  if (!touches) return;
  const unsigned centre_signs = newton_.centre().denominator_signs;
  const Eigen::Vector2d lo_s(-lattice_margin_ + i * kLattice, -lattice_margin_ + j * kLattice);
  Eigen::Vector2d fine[(kSplit + 1) * (kSplit + 1)];
  for (int v = 0; v <= kSplit; ++v)
    for (int u = 0; u <= kSplit; ++u) {
      Eigen::Vector2d& f = fine[v * (kSplit + 1) + u];
      unsigned signs = 0;
      if (!newton_.forward().evaluate(lo_s + (kLattice / kSplit) * Eigen::Vector2d(u, v), f,
                                      nullptr, &signs) ||
          signs != centre_signs || !f.allFinite()) {
        markFine(lo, hi);
        return;
      }
    }
  // How far a quad's image strays from its corners' polygon: a segment of length L in the
  // quad bows from its chord by at most |∂²F along it| L² / 8, and the longest, a diagonal of
  // √2 h, gives (|∂²F/∂u²|, |∂²F/∂v²| and |∂²F/∂u∂v| at most, over the quad) · h² / 4. The split
  // points' second differences are those derivatives times h² (largest over the lattice quad).
  double pure = 0.0, mixed = 0.0;
  constexpr int w = kSplit + 1;
  for (int v = 0; v <= kSplit; ++v)
    for (int u = 0; u <= kSplit; ++u) {
      const int k = v * w + u;
      if (u > 0 && u < kSplit)
        pure = std::max(pure, (fine[k - 1] - 2.0 * fine[k] + fine[k + 1]).norm());
      if (v > 0 && v < kSplit)
        pure = std::max(pure, (fine[k - w] - 2.0 * fine[k] + fine[k + w]).norm());
      if (u < kSplit && v < kSplit)
        mixed = std::max(mixed, (fine[k + w + 1] - fine[k + 1] - fine[k + w] + fine[k])
                                    .norm());
    }
  const double grow = 0.5 + (pure + mixed) / 4.0;
  for (int v = 0; v < kSplit; ++v)
    for (int u = 0; u < kSplit; ++u) {
      const auto at = [&](int du, int dv) -> const Eigen::Vector2d& {
        return fine[(v + dv) * (kSplit + 1) + u + du];
      };
      markFineQuad({at(0, 0), at(1, 0), at(1, 1), at(0, 1)}, grow);
    }
}

void InverseCells::markFineQuad(const std::array<Eigen::Vector2d, 4>& q, double grow) {
  Eigen::Vector2d lo = q[0].cwiseMin(q[1]).cwiseMin(q[2]).cwiseMin(q[3]);
  Eigen::Vector2d hi = q[0].cwiseMax(q[1]).cwiseMax(q[2]).cwiseMax(q[3]);
  // The quad's image as the corners' polygon where it is convex: each edge's line moved out
  // by `grow` bounds it (the mitred offset holds the polygon grown by that distance). A thin
  // quad along a curve, whose box (the fallback) spreads diagonally, then marks only the blocks
  // along it (on the strong barrel, boxes would reach 7 px beyond its fold circle, all of it
  // per-pixel work in which every Newton start fails).
  double cross[4];
  for (int k = 0; k < 4; ++k) {
    const Eigen::Vector2d e0 = q[(k + 1) % 4] - q[k], e1 = q[(k + 2) % 4] - q[(k + 1) % 4];
    cross[k] = e0.x() * e1.y() - e0.y() * e1.x();
  }
  const bool ccw = cross[0] > 0 && cross[1] > 0 && cross[2] > 0 && cross[3] > 0;
  const bool cw = cross[0] < 0 && cross[1] < 0 && cross[2] < 0 && cross[3] < 0;
  if (!ccw && !cw) {  // folded or degenerate: the box, as the whole lattice quad's
    const double fgrow = grow + 0.25 * (hi - lo).maxCoeff();
    lo.array() -= fgrow;
    hi.array() += fgrow;
    return markFine(lo, hi);
  }
  lo.array() -= grow;
  hi.array() += grow;
  int fx0, fy0, fx1, fy1;
  if (!fineBlocks(lo, hi, fx0, fy0, fx1, fy1)) return;
  // Per edge: unit outward normal n and offset c, a point p outside by n·p − c. A block of
  // kFine pixels is marked when, for every edge, its pixel centre nearest that edge's outside
  // lies within `grow` (a bound: the nearest centre may differ from edge to edge). Along a row
  // of blocks (centre y = py) edge k then bounds the centre's x: x ≤ at + slope · py where
  // its normal points right, x ≥ … where left (a horizontal edge bounds py instead). No edge
  // has length 0: both its cross products would be 0, which the convexity test refuses.
  double at[4], slope[4];
  bool upper[4];
  double lo_always = -1e300, hi_always = 1e300;  // from horizontal edges: py's own bounds
  for (int k = 0; k < 4; ++k) {
    const Eigen::Vector2d e = q[(k + 1) % 4] - q[k];
    const double len = e.norm();
    const double nx = (ccw ? e.y() : -e.y()) / len, ny = (ccw ? -e.x() : e.x()) / len;
    const double c = nx * q[k].x() + ny * q[k].y() + grow +
                     0.5 * (kFine - 1) * (std::abs(nx) + std::abs(ny));
    upper[k] = nx >= 0.0;
    at[k] = nx != 0.0 ? c / nx : 1e300;
    slope[k] = nx != 0.0 ? -ny / nx : 0.0;
    if (nx == 0.0) {  // a horizontal edge bounds the row instead: ny · py ≤ c
      if (ny > 0.0) hi_always = std::min(hi_always, c / ny);
      else lo_always = std::max(lo_always, c / ny);
    }
  }
  for (int fy = fy0; fy <= fy1; ++fy) {
    const double py = fy * kFine + 0.5 * kFine;  // the row's blocks' centre
    if (py < lo_always - 1e-9 || py > hi_always + 1e-9) continue;
    double px_lo = -1e300, px_hi = 1e300;
    for (int k = 0; k < 4; ++k) {
      const double bound = at[k] + slope[k] * py;
      if (upper[k]) px_hi = std::min(px_hi, bound);
      else px_lo = std::max(px_lo, bound);
    }
    if (!(px_lo <= px_hi)) continue;
    // Blocks whose centre (fx + ½) · kFine lies in [px_lo, px_hi], widened by a hair against
    // rounding.
    const double b_lo = std::ceil((px_lo - 1e-9) / kFine - 0.5);
    const double b_hi = std::floor((px_hi + 1e-9) / kFine - 0.5);
    markFineRow(fy, b_lo > fx0 ? static_cast<int>(b_lo) : fx0, b_hi < fx1 ? static_cast<int>(b_hi) : fx1);
  }
}

bool InverseCells::fineBlocks(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi, int& fx0, int& fy0,
                              int& fx1, int& fy1) const {
  if (hi.x() < 0 || hi.y() < 0 || lo.x() >= target_px_.width || lo.y() >= target_px_.height) return false;
  // Clamped before the conversion: near a pole a box's far side can pass any int.
  fx0 = std::max(0, static_cast<int>(std::floor(lo.x() / kFine)));
  fy0 = std::max(0, static_cast<int>(std::floor(lo.y() / kFine)));
  fx1 = std::min(cells_w_ * kFines - 1, static_cast<int>(std::floor(std::min(hi.x(), 1e9) / kFine)));
  fy1 = std::min(cells_h_ * kFines - 1, static_cast<int>(std::floor(std::min(hi.y(), 1e9) / kFine)));
  return true;
}

void InverseCells::markFine(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi) {
  int fx0, fy0, fx1, fy1;
  if (!fineBlocks(lo, hi, fx0, fy0, fx1, fy1)) return;
  for (int fy = fy0; fy <= fy1; ++fy) markFineRow(fy, fx0, fx1);
}

void InverseCells::markFineRow(int fy, int a, int b) {
  const int cy = fy / kFines;
  for (int cx = a / kFines; a <= b && cx <= b / kFines; ++cx) {
    if (!refined(cx, cy)) continue;
    Refined& r = refined_[static_cast<size_t>(refined_index_[index(cx, cy, cells_w_)])];
    if (!r.fine) continue;
    unsigned char* row = r.covered + (fy - cy * kFines) * kFines - cx * kFines;
    // Bands of lattice rows mark concurrently; every write stores the same 1.
    for (int fx = std::max(a, cx * kFines); fx <= std::min(b, (cx + 1) * kFines - 1); ++fx)
      std::atomic_ref<unsigned char>(row[fx]).store(1, std::memory_order_relaxed);
  }
}

bool InverseCells::solveSubNode(int cx, int cy, int i, int j, Refined& r) const {
  constexpr int w = kSubs + 1;
  Node& n = r.nodes[j * w + i];
  if ((i == 0 || i == kSubs) && (j == 0 || j == kSubs)) {
    const Node& c = node(cx + i / kSubs, cy + j / kSubs);
    if (c.valid) {
      const double scale = static_cast<double>(kSub) / kCell;
      n = c;
      n.su *= scale;
      n.sv *= scale;
      n.suv *= scale * scale;
      return true;
    }
  }
  // Starts: the cell's patch (close wherever the cell only narrowly failed to certify), the
  // nearest solved node to the left or above stepped by its derivative, the seed. A node that
  // fails costs only its subcells, which take the per-pixel path.
  const Eigen::Vector2d t(cx * kCell + i * kSub, cy * kCell + j * kSub);
  Eigen::Vector2d s;
  Eigen::Matrix2d jac;  // the forward Jacobian at s
  bool ok =
      hasPatch(cx, cy) && newton_.solve(t,
                                        patchAt(cellCorners(cx, cy), static_cast<double>(i) / kSubs,
                                                static_cast<double>(j) / kSubs),
                                        s, kSubIterations, &jac);
  for (int k = i - 1; k >= 0 && !ok; --k)
    if (const Node& m = r.nodes[j * w + k]; m.valid) {
      ok = newton_.solve(t, m.s + (i - k) * m.su, s, kSubIterations, &jac);
      break;
    }
  for (int k = j - 1; k >= 0 && !ok; --k)
    if (const Node& m = r.nodes[k * w + i]; m.valid) {
      ok = newton_.solve(t, m.s + (j - k) * m.sv, s, kSubIterations, &jac);
      break;
    }
  Eigen::Vector2d seeded;
  if (!ok && seed_ && seed_->evaluate(t, seeded, nullptr) && seeded.allFinite())
    ok = newton_.solve(t, seeded, s, kSubIterations, &jac);
  if (!ok || !finishNode(s, jac, kSub, n)) return false;
  crossDerivative(n, kSub);
  return n.valid;
}

void InverseCells::refineCell(int cx, int cy, Refined& r, std::atomic<int>& next_poly) const {
  constexpr int w = kSubs + 1;
  static_assert(kSubs * kSubs == 64 && kSub / kFine == 4, "a cell's subcells fit a 64-bit mask");
  // Bit sy · kSubs + sx: subcell (sx, sy) may show something (any of its kFine blocks is
  // covered). Read once here: the quadtree and the nodes ask about a subcell many times.
  std::uint64_t covered = ~std::uint64_t{0};
  if (r.fine) {
    covered = 0;
    for (int sy = 0; sy < kSubs; ++sy)
      for (int sx = 0; sx < kSubs; ++sx) {
        std::uint32_t any = 0;
        for (int fy = sy * 4; fy < sy * 4 + 4; ++fy) {
          std::uint32_t four;
          std::memcpy(&four, &r.covered[fy * kFines + sx * 4], 4);
          any |= four;
        }
        if (any) covered |= std::uint64_t{1} << (sy * kSubs + sx);
      }
  }
  // The subcells of the square (qx, qy) of side `size`, as bits of `covered`.
  const auto square_bits = [](int qx, int qy, int size) {
    const std::uint64_t row = ((std::uint64_t{1} << size) - 1) << qx;
    std::uint64_t bits = 0;
    for (int sy = qy; sy < qy + size; ++sy) bits |= row << (sy * kSubs);
    return bits;
  };
  // A node is needed when a subcell it bounds may show something.
  bool tried[w * w] = {};
  const auto solve = [&](int i, int j) {
    if (tried[j * w + i]) return;
    tried[j * w + i] = true;
    const int sx = std::max(0, i - 1), sy = std::max(0, j - 1);
    const int nx = std::min(kSubs - 1, i) - sx + 1, ny = std::min(kSubs - 1, j) - sy + 1;
    std::uint64_t around = 0;
    for (int k = 0; k < ny; ++k) around |= ((std::uint64_t{1} << nx) - 1) << ((sy + k) * kSubs + sx);
    if (covered & around) solveSubNode(cx, cy, i, j, r);
  };
  // A quadtree below the cell, which has just failed: its quadrants (kCell / 2 pixels) first,
  // each certified by the same rule; a square that fails is cut into four, down to subcells of
  // kSub pixels, and only the subcells that fail run the per-pixel path. At half the cells'
  // tolerance: a square certifies where its parent just failed, so its error between the
  // checked points sits nearer the tolerance than most cells' does: on the strong barrel, at
  // the cells' tolerance its worst certified subcell pixel exceeds that tolerance, at half it
  // does not, and a smaller one only leaves more of the frame to the per-pixel path
  // (tests/core/mapping/test_inverse_cells.cpp checks every certified subcell pixel).
  const double tol = options_.certify_tolerance_px / 2.0;
  CellPoly local[kSubs * kSubs];  // the certified squares' patches, in the order made
  int polys = 0;
  const auto decide = [&](int qx, int qy, int size, Kind k) {
    for (int sy = qy; sy < qy + size; ++sy)
      for (int sx = qx; sx < qx + size; ++sx) {
        r.kinds[sy * kSubs + sx] = k;
        r.side[sy * kSubs + sx] = static_cast<unsigned char>(size);
      }
  };
  const auto refine = [&](const auto& self, int qx, int qy, int size) -> void {
    if (!(covered & square_bits(qx, qy, size))) return decide(qx, qy, size, kEmpty);
    for (int j = qy; j <= qy + size; j += size)
      for (int i = qx; i <= qx + size; i += size) solve(i, j);
    Node n[4];
    r.square(qx, qy, size, n);
    const Corners c{&n[0], &n[1], &n[2], &n[3]};
    if (n[0].valid && n[1].valid && n[2].valid && n[3].valid &&
        certify(c, cx * kCell + qx * kSub, cy * kCell + qy * kSub, size * kSub, tol)) {
      if (patchBeyondReach(c)) return decide(qx, qy, size, kEmpty);
      for (int sy = qy; sy < qy + size; ++sy)
        for (int sx = qx; sx < qx + size; ++sx) r.poly[sy * kSubs + sx] = static_cast<unsigned char>(polys);
      polyOf(c, local[polys++]);
      return decide(qx, qy, size, kCertified);
    }
    if (size == 1) return decide(qx, qy, 1, kOpen);
    const int half = size / 2;
    for (int dy = 0; dy < 2; ++dy)
      for (int dx = 0; dx < 2; ++dx) self(self, qx + dx * half, qy + dy * half, half);
  };
  for (int dy = 0; dy < 2; ++dy)
    for (int dx = 0; dx < 2; ++dx) refine(refine, dx * kSubs / 2, dy * kSubs / 2, kSubs / 2);
  if (polys == 0) return;
  r.poly_base = next_poly.fetch_add(polys, std::memory_order_relaxed);
  std::copy(local, local + polys, &square_polys_[static_cast<size_t>(r.poly_base)]);
}

}  // namespace artcam
