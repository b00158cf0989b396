// SPDX-License-Identifier: Apache-2.0
// The rational kernel's inverse map at memory speed for any camera: the exact inverse solved at
// the nodes of a target grid (every kCell output pixels), with its Jacobian, and one bicubic
// Hermite patch per cell between them, so a certified cell costs a cubic along the row (three
// multiply-adds per coordinate) per pixel, whatever the lens.
//
// Hermite: corner values and first derivatives make the patch exact to fourth order, its error
// ~ G⁴/384 · |∂⁴s| (a fisheye's inverse, which bilinear misses by ~0.1 px at 32 px, is met to
// ~1e-6 px there, 16 × that at 64 px). The first derivatives are exact (the inverse of the
// forward Jacobian, eq 2, at the solved node); the cross derivative is the central difference
// of the neighbouring nodes' derivatives (its error enters at the same fourth order).
//
// Certification: at a cell's centre, its four edge midpoints and the four points where a cross-
// derivative error peaks, one Newton step from the patch's value (r = F(p) − t, δ = J⁻¹ r) must
// be within the tolerance and each point lie on the source centre's side of every pole curve
// and of the fold (inverse.h); the nine points go through RationalMap::evaluateBatch at once.
// The tolerance, 1/4096 px by default, is a sixteenth of the 1/256 px budget, leaving room for
// the error between the checked points and float rounding; the tests check every pixel.
//
// Cells of 64 pixels: building is per cell, and at 64 a mild lens still certifies almost all of
// its frame. Nodes are solved every other cell first and each 2 × 2 pair of cells is certified
// as one square (at half the tolerance); where it certifies, its five inner nodes are read off
// its patch instead of solved (on an edge the patch is the edge's two nodes' alone, so the
// pairs sharing it agree), else its cells are solved and certified one by one.
//
// No preimage, known without a solve: a certified cell whose Bézier control points' box lies
// beyond the source frame grown by the filters' reach; elsewhere, blocks of kBlock pixels that no
// quad of the forward-mapped source lattice touches (its corners' box grown by a quarter of its
// size), marked per cell first and then per block only in open cells, the only ones that read
// them. No coverage is claimed when a quad's corner lies beyond a pole curve (an unbounded
// image), and none is marked when the frame lies inside the lattice's image (frameInsideImage).
// Folds follow inverse.h's rule: a patch interpolates only between nodes on the source centre's
// side, and a cell the fold crosses fails to certify.
//
// Open cells are split: near a fold the inverse goes like √d, so a patch's error grows as
// d^(−7/2) and cells fail far inside a strong barrel's fold circle. Each open cell is a quadtree
// of squares from kCell / 2 down to kSub pixels, with their own nodes (a few Newton steps from
// the cell's patch or a neighbour), certified at half the tolerance (a square certifies where its
// parent just failed) and keeping a float patch as a cell does; only subcells near a fold or pole
// run the per-pixel path (tests/core/mapping/test_inverse_cells.cpp). A central map
// (central_inverse.h) builds no quadtree (subdivide = false): its closed-form inverse is cheaper.
// Open cells where the camera's visible edge crosses get coverage at kFine pixels from lattice
// quads split to 16 source pixels (their corners' polygon grown by half a pixel and the edges'
// sag), so pixels just beyond a fold, which no Newton start can solve, are transparent at once.
#pragma once

#include "core/model/frames.h"
#include "core/mapping/inverse.h"
#include "core/util/scratch.h"

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <atomic>
#include <memory>
#include <vector>

namespace artcam {

struct InverseCellsOptions {
  double certify_tolerance_px = 1.0 / 4096.0;
  // How far beyond the source frame a preimage may lie and still reach the output through a
  // filter's taps (source pixels), before the scale term below: bicubic reaches 2 px.
  double reach_px = 4.0;
  // Split open cells into subcells (false: the per-pixel path runs on every open cell's pixel).
  bool subdivide = true;
  int threads = 0;
};

// Cell cx's patch along one output row: s(u) = c[0] + u (c[1] + u (c[2] + u c[3])), per axis,
// at u = (x + 0.5 − cx · kCell) / kCell.
struct CellRow {
  double x[4], y[4];
};

// A certified cell's patch in float, made once when the cell certifies so that a span's rows
// cost no double Hermite blend per cell and row: the patch minus `anchor` (its first node's
// position rounded to float) in the power basis of the cell's local (u, v) ∈ [0, 1]²,
//   s(u, v) = anchor + Σ_k u^k Σ_l v^l p[l][k]  (x in lanes 0–3, y in lanes 4–7).
// A row's cubic in u is then one Horner step in v per power over eight lanes. Only the offset
// from the anchor (a cell's stretch, ~64 px: its rounding ~4e-6 px) is a float sum; adding
// the anchor rounds once, as any float position does (half an ulp ≤ 2.4e-4 px at 6000 px).
struct alignas(32) CellPoly {
  float p[4][8];
  float anchor_x, anchor_y;
};

class InverseCells {
 public:
  static constexpr int kCell = 64;  // output pixels per cell side; divides kSpanPixels
  static constexpr int kBlock = 8;  // output pixels per coverage block side
  static constexpr int kSub = 8;    // output pixels per subcell side in an open cell
  static constexpr int kSubs = kCell / kSub;
  static constexpr int kFine = 2;  // output pixels per coverage block side in an open cell
  static constexpr int kFines = kCell / kFine;

  enum Kind : unsigned char {
    kOpen = 0,       // per-pixel path (the patch as its start when hasPatch)
    kCertified = 1,  // the patch, unchecked
    kEmpty = 2,      // no pixel has a preimage within reach: transparent
  };

  // `seed` (output px → source px, may be null) starts node solves the neighbours cannot.
  InverseCells(const NewtonInverse& newton, const RationalMap* seed, FrameSize source_px,
               FrameSize target_px, const InverseCellsOptions& options);

  int cellsWide() const { return cells_w_; }
  int cellsHigh() const { return cells_h_; }
  Kind kind(int cx, int cy) const { return kinds_[index(cx, cy, cells_w_)]; }
  // All four nodes solved: the patch exists (certified or not).
  bool hasPatch(int cx, int cy) const;
  // The patch of cell (cx, y / kCell) along output row y (hasPatch must hold).
  void row(int cx, int y, CellRow& out) const;
  // A certified cell's patch in float (kind(cx, cy) == kCertified; cells (cx, cy), (cx + 1,
  // cy), … follow each other in memory).
  const CellPoly& poly(int cx, int cy) const { return polys_[index(cx, cy, cells_w_)]; }
  // out[i] = 1 where output pixel (x + i, y) may have a preimage within reach (always without
  // coverage), else 0; pixels x … x + n − 1 lie in one cell.
  void coveredRun(int x, int y, int n, unsigned char* out) const;

  // An open cell split into kSubs × kSubs subcells of kSub pixels, each with its own kind and
  // patch: a quadrant's (2 kSub pixels) where that certifies, else the subcell's own.
  bool refined(int cx, int cy) const {
    return refined_index_.empty() ? false : refined_index_[index(cx, cy, cells_w_)] >= 0;
  }
  Kind subKind(int cx, int cy, int sx, int sy) const {
    return refinedAt(cx, cy).kinds[sy * kSubs + sx];
  }
  bool hasSubPatch(int cx, int cy, int sx, int sy) const;
  // The patch of subcell (sx, y's) of cell cx along output row y (hasSubPatch must hold):
  // the cubic at u = (x + 0.5 − x0) / size.
  struct SubRow {
    CellRow cubic;
    int x0 = 0, size = 0;
  };
  void subRow(int cx, int sx, int y, SubRow& out) const;
  // A certified subcell's square of the quadtree (the one whose patch it takes): its origin
  // in output pixels, its side in pixels, and its patch in float as a certified cell's
  // (CellPoly, over the square's local (u, v) ∈ [0, 1]²).
  struct SubSquare {
    const CellPoly* poly = nullptr;
    int x0 = 0, y0 = 0, size = 0;
  };
  SubSquare subSquare(int cx, int cy, int sx, int sy) const;

  // Shares of the output area (cells and subcells by their pixels): the patch unchecked, and
  // transparent without a solve. The rest runs the per-pixel path.
  double certifiedShare() const;
  double emptyShare() const;
  bool coverageKnown() const { return coverage_known_; }

 private:
  struct Node {
    Eigen::Vector2d s{0, 0};    // source pixel of the node
    Eigen::Vector2d su{0, 0};   // kCell · ∂s/∂x (the derivative per cell)
    Eigen::Vector2d sv{0, 0};   // kCell · ∂s/∂y
    Eigen::Vector2d suv{0, 0};  // kCell² · ∂²s/∂x∂y
    bool valid = false;
    bool cross = false;  // suv set (crossDerivative, or a certified patch's: patchNode)
  };

  static size_t index(int i, int j, int w) {
    return static_cast<size_t>(j) * static_cast<size_t>(w) + static_cast<size_t>(i);
  }
  const Node& node(int i, int j) const { return nodes_[index(i, j, nodes_w_)]; }
  Node& node(int i, int j) { return nodes_[index(i, j, nodes_w_)]; }

  // The four nodes of a patch: a = (0, 0), b = (1, 0), c = (0, 1), d = (1, 1) in local (u, v).
  struct Corners {
    const Node *a, *b, *c, *d;
  };
  struct Refined {
    Node nodes[(kSubs + 1) * (kSubs + 1)];  // kSub apart, derivatives per kSub
    Kind kinds[kSubs * kSubs];
    // Per subcell: the side, in subcells (kSubs / 2, …, 2, 1), of the square of the quadtree
    // that decided it, whose patch (its corner nodes) it takes — certified, or as the per-pixel
    // path's start when open.
    unsigned char side[kSubs * kSubs];
    unsigned char covered[kFines * kFines];
    bool fine;  // covered[] from the split lattice (else all covered)
    // Per certified subcell: its square's float patch, square_polys_[poly_base + poly[…]]
    // (made when the square certifies, so that a row of it costs no double Hermite blend).
    unsigned char poly[kSubs * kSubs];
    int poly_base;  // set where the cell has a certified square
    // The square of `size` subcells at subcell (sx, sy): its corner nodes with their
    // derivatives scaled to the square (per size · kSub pixels).
    void square(int sx, int sy, int size, Node out[4]) const {
      const int w = kSubs + 1;
      const Node* n[4] = {&nodes[sy * w + sx], &nodes[sy * w + sx + size], &nodes[(sy + size) * w + sx],
                          &nodes[(sy + size) * w + sx + size]};
      for (int k = 0; k < 4; ++k) {
        out[k] = *n[k];
        out[k].su *= size;
        out[k].sv *= size;
        out[k].suv *= static_cast<double>(size) * size;
      }
    }
  };

  Corners cellCorners(int cx, int cy) const {
    return {&node(cx, cy), &node(cx + 1, cy), &node(cx, cy + 1), &node(cx + 1, cy + 1)};
  }
  const Refined& refinedAt(int cx, int cy) const {
    return refined_[static_cast<size_t>(refined_index_[index(cx, cy, cells_w_)])];
  }

  bool solveNode(const Eigen::Vector2d& t, const Eigen::Vector2d* start, Node& out) const;
  // The node's derivatives at its solution s, scaled to a patch of `size` pixels.
  // The node at the solution s, from the forward Jacobian j there (the solve's last one).
  bool finishNode(const Eigen::Vector2d& s, const Eigen::Matrix2d& j, double size, Node& out) const;
  void crossDerivative(Node& n, double size) const;  // drops a node next to a pole
  // The nodes not yet valid on rows and columns that are multiples of `stride` (where a cell
  // they bound may show something), each from the last valid node before it on its row.
  void solveNodes(int threads, int stride);
  void crossDerivatives();  // of the valid nodes without one
  // Pairs of cells: 2 × 2 cells (pair a, b: cells 2a, 2a + 1 by 2b, 2b + 1) whose patch from
  // its corner nodes certifies as one square of 2 kCell pixels. Each of its cells is then that
  // patch over its quarter (a bicubic restricted to a square is one), its nodes between the
  // corners taken from the patch (deriveNodes, patchNode): no solve and no certification.
  void certifySupers(int threads);
  bool superCorners(int a, int b, Node out[4]) const;  // false where a corner is not valid
  void deriveNodes(int threads);
  static void patchNode(const Corners& n, double u, double v, Node& out);
  // Cell (cx, cy) lies in a certified pair and has its patch.
  bool inSuper(int cx, int cy) const;
  static void edgesAt(const Corners& n, double v, Eigen::Vector2d& f0, Eigen::Vector2d& f1,
                      Eigen::Vector2d& d0, Eigen::Vector2d& d1);
  static void rowOf(const Corners& n, double v, CellRow& out);
  static void polyOf(const Corners& n, CellPoly& out);
  // The patch's value at local (u, v) ∈ [0, 1]².
  static Eigen::Vector2d patchAt(const Corners& n, double u, double v);
  // The patch over the square of `size` output pixels at (x0, y0), to `tol` output pixels;
  // `edges` false leaves out the four edge midpoints (the caller checked them).
  bool certify(const Corners& n, double x0, double y0, double size, double tol, bool edges = true) const;
  // One point: the patch's value p for output point t is one Newton step within `tol` of the
  // exact inverse, on the source centre's side of every pole curve and of the fold.
  bool pointCertifies(const Eigen::Vector2d& p, const Eigen::Vector2d& t, double tol) const;
  bool patchBeyondReach(const Corners& n) const;
  void buildCoverage(int threads);
  // Whether the output frame lies inside the image of the source frame grown by the reach, so
  // that every block is covered and marking them can be skipped: the centre's image is in the
  // frame, the lattice within reach has no point beyond a pole curve or the fold, and its ring
  // of boundary quads maps wholly outside the frame. Then the frame meets no image of the
  // boundary, and a map without a fold covers all of it (its degree there is that at the
  // centre's image, at least one). `ok` per lattice point: 1 on the centre's side of both.
  // i0 … i1 by j0 … j1: the quads within reach (reachableQuads).
  bool frameInsideImage(const Eigen::Vector2d* mapped, const unsigned char* ok, int pw,
                        int i0, int i1, int j0, int j1) const;
  bool cellCovered(int cx, int cy) const;
  // Marks the blocks of the open cells (coveredRun reads no other) that the lattice quads'
  // boxes touch, from the block ranges buildCoverage kept.
  void coverOpenCells(int threads);
  static constexpr double kLattice = 32.0;  // source pixels between coverage lattice points
  void refineOpenCells(int threads);
  void coverFine(int threads);
  // The output box a source lattice quad may cover: its mapped corners' bounding box, grown
  // by 2 px and a quarter of its size for the edges' curvature. Inline and in plain doubles,
  // so that the box stays in registers through the marking loop.
  static void quadBox(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                      const Eigen::Vector2d& d, Eigen::Vector2d& lo, Eigen::Vector2d& hi) {
    const double lx = std::min(std::min(a.x(), b.x()), std::min(c.x(), d.x()));
    const double ly = std::min(std::min(a.y(), b.y()), std::min(c.y(), d.y()));
    const double hx = std::max(std::max(a.x(), b.x()), std::max(c.x(), d.x()));
    const double hy = std::max(std::max(a.y(), b.y()), std::max(c.y(), d.y()));
    // The edges' curvature: a quarter of the quad's size is far beyond the chord's sag of any
    // map smooth at the lattice's scale (near a pole the corners spread and the box with them).
    const double grow = 2.0 + 0.25 * std::max(hx - lx, hy - ly);
    lo = Eigen::Vector2d(lx - grow, ly - grow);
    hi = Eigen::Vector2d(hx + grow, hy + grow);
  }
  // Whether the coverage lattice's interval k along an axis (the lattice starting `margin`
  // before a frame side `size` pixels long) lies within the reach of the frame: a quad (i, j)
  // is drawn when both of its intervals are.
  bool latticeReaches(int k, double margin, double size) const;
  // The quads within the reach of the frame: a rectangle of lattice indices, i0 … i1 by
  // j0 … j1 (empty when i0 > i1 or j0 > j1).
  void reachableQuads(double margin, int qw, int qh, int& i0, int& i1, int& j0, int& j1) const;
  // Lattice quad (i, j)'s box (quadBox) from its mapped corners, `pw` points a row; false
  // when it misses the output.
  bool latticeQuadBox(const Eigen::Vector2d* mapped, int pw, int i, int j, Eigen::Vector2d& lo,
                      Eigen::Vector2d& hi) const;
  void coverQuadFine(int i, int j);
  // Marks the fine blocks of the open cells needing them (Refined::fine) that the output box
  // lo … hi touches; markFineQuad those within `grow` of the mapped quad q (corners in order
  // around it), a folded quad's box else. Both mark row by row (markFineRow: blocks a … b of
  // fine row fy) within fineBlocks' range of the box, false when the box misses the output.
  void markFine(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi);
  void markFineQuad(const std::array<Eigen::Vector2d, 4>& q, double grow);
  void markFineRow(int fy, int a, int b);
  bool fineBlocks(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi, int& fx0, int& fy0, int& fx1,
                  int& fy1) const;
  // Writes its certified squares' patches to square_polys_ from `next_poly` on.
  void refineCell(int cx, int cy, Refined& r, std::atomic<int>& next_poly) const;
  bool solveSubNode(int cx, int cy, int i, int j, Refined& r) const;

  const NewtonInverse& newton_;
  const RationalMap* seed_;
  FrameSize source_px_, target_px_;
  InverseCellsOptions options_;
  double reach_px_ = 0.0;
  int nodes_w_ = 0, nodes_h_ = 0, cells_w_ = 0, cells_h_ = 0, blocks_w_ = 0, blocks_h_ = 0;
  // nodes_w_ × nodes_h_ nodes and cells_w_ × cells_h_ float patches (the latter written where
  // kinds_ is kCertified only, so never filled first), in scratch blocks as the refined cells.
  ScratchBlock node_storage_, poly_storage_;
  Node* nodes_ = nullptr;
  size_t node_count_ = 0;
  std::vector<Kind> kinds_;
  int supers_w_ = 0, supers_h_ = 0;
  std::vector<unsigned char> supers_;  // per pair of cells: 1 certified
  CellPoly* polys_ = nullptr;
  bool coverage_known_ = false;
  // The coverage lattice mapped forward (buildCoverage), for the open cells' finer coverage,
  // its points' sides of the pole and fold, and the covered blocks, in one scratch block, so
  // that their ~0.9 MB is not faulted in from the system page by page every build.
  ScratchBlock coverage_storage_;
  // A lattice quad's box in blocks (x0 > x1: it marks nothing).
  struct QuadBlocks {
    int x0 = 0, y0 = 0, x1 = -1, y1 = -1;
  };
  unsigned char* covered_cells_ = nullptr;  // cells_w_ × cells_h_: a quad's box touches the cell
  unsigned char* covered_ = nullptr;        // blocks_w_ × blocks_h_, in open cells only
  QuadBlocks* quad_blocks_ = nullptr;       // lattice_w_ × lattice_h_
  double lattice_margin_ = 0.0;
  int lattice_w_ = 0, lattice_h_ = 0;  // quads
  Eigen::Vector2d* lattice_mapped_ = nullptr;
  std::vector<int> refined_index_;  // per cell: into refined_, or −1
  // refined_count_ cells in refined_index_'s order, in storage the cells construct themselves
  // in parallel (Refined is trivially destructible: releasing the storage ends them). Scratch
  // blocks (core/util/scratch.h): megabytes a strong lens's every render would fault in afresh.
  ScratchBlock refined_storage_;
  Refined* refined_ = nullptr;
  int refined_count_ = 0;
  // The certified squares' float patches, each refined cell's together (Refined::poly_base):
  // room for every subcell's, of which only the pages written are ever touched.
  ScratchBlock square_storage_;
  CellPoly* square_polys_ = nullptr;
};

}  // namespace artcam
