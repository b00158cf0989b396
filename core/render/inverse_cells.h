// SPDX-License-Identifier: Apache-2.0
// The rational kernel's inverse map at memory speed for any camera: the exact inverse solved at
// the nodes of a target grid (every kCell output pixels), with its Jacobian, and one bicubic
// Hermite patch per cell between them. Per pixel a certified cell costs a cubic along the row
// (three multiply-adds per coordinate), whatever the lens: strong lenses and fisheyes, whose
// inverse no single quadratic camera follows, interpolate as cheaply as mild ones.
//
// Why Hermite: values and first derivatives at the corners make the patch exact to fourth
// order, its error ~ G⁴/384 · |∂⁴s|; a fisheye's inverse, whose bilinear interpolation misses
// by ~0.1 px at 32 px, is met to ~1e-6 px. The first derivatives are exact (the inverse of the
// forward Jacobian, eq 2, at the solved node); the cross derivative is the central difference
// of the neighbouring nodes' derivatives (its error enters at the same fourth order).
//
// Certification: a cell is certified when, at its centre and its four edge midpoints (where
// a Hermite patch's error peaks), one Newton step from the patch's value (r = F(p) − t,
// δ = J⁻¹ r: the distance to the exact inverse up to curvature · δ²) is within the tolerance,
// and each point lies on the source centre's side of every pole curve and of the fold
// (inverse.h). The tolerance is half the 1/256 px budget; the tests check every pixel.
//
// What has no preimage is known at once:
// - a certified cell whose patch lies wholly beyond the source frame grown by the filters'
//   reach is empty (the patch lies in the convex hull of its Bézier control points, so their
//   bounding box decides, exactly up to the certified error);
// - where cells are not certified (nodes without a preimage: a fold or pole nearby, the edge of
//   what the camera can see), the source frame grown by the reach is mapped forward as a lattice
//   of quads, and every output block of kBlock pixels touched by a quad's image (its corners'
//   bounding box, grown by a quarter of its size for the edges' curvature) is marked covered.
//   Output pixels in blocks no quad touches have no preimage within reach: transparent without
//   a Newton solve. A quad with a corner beyond a pole curve has an unbounded image: then no
//   coverage is claimed at all and every uncertified pixel runs the per-pixel path.
// Folds follow inverse.h's rule (a preimage must lie in the source centre's fold); the patch
// interpolates only between nodes on that side, and a cell the fold crosses fails to certify.
#pragma once

#include "core/model/frames.h"
#include "core/render/inverse.h"

#include <Eigen/Core>

#include <vector>

namespace artcam {

struct InverseCellsOptions {
  double certify_tolerance_px = 1.0 / 4096.0;
  // How far beyond the source frame a preimage may lie and still reach the output through a
  // filter's taps (source pixels), before the scale term below: bicubic reaches 2 px.
  double reach_px = 4.0;
  int threads = 0;
};

// Cell cx's patch along one output row: s(u) = c[0] + u (c[1] + u (c[2] + u c[3])), per axis,
// at u = (x + 0.5 − cx · kCell) / kCell.
struct CellRow {
  double x[4], y[4];
};

class InverseCells {
 public:
  static constexpr int kCell = 32;  // output pixels per cell side; divides kSpanPixels
  static constexpr int kBlock = 8;  // output pixels per coverage block side

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
  // Output pixel (x, y) may have a preimage within reach (always true without coverage).
  bool covered(int x, int y) const;

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
  };

  static size_t index(int i, int j, int w) {
    return static_cast<size_t>(j) * static_cast<size_t>(w) + static_cast<size_t>(i);
  }
  const Node& node(int i, int j) const { return nodes_[index(i, j, nodes_w_)]; }
  Node& node(int i, int j) { return nodes_[index(i, j, nodes_w_)]; }

  bool solveNode(const Eigen::Vector2d& t, const Eigen::Vector2d* start, Node& out) const;
  void solveNodes(int threads);
  void crossDerivatives();  // also drops nodes next to a pole
  void edgesAt(int cx, int cy, double v, Eigen::Vector2d& f0, Eigen::Vector2d& f1, Eigen::Vector2d& d0,
               Eigen::Vector2d& d1) const;
  // The patch's value at local (u, v) ∈ [0, 1]² of cell (cx, cy).
  Eigen::Vector2d patchAt(int cx, int cy, double u, double v) const;
  bool certify(int cx, int cy) const;
  bool patchBeyondReach(int cx, int cy) const;
  void buildCoverage(int threads);
  bool cellCovered(int cx, int cy) const;

  const NewtonInverse& newton_;
  const RationalMap* seed_;
  FrameSize source_px_, target_px_;
  InverseCellsOptions options_;
  double reach_px_ = 0.0;
  int nodes_w_ = 0, nodes_h_ = 0, cells_w_ = 0, cells_h_ = 0, blocks_w_ = 0, blocks_h_ = 0;
  std::vector<Node> nodes_;
  std::vector<Kind> kinds_;
  bool coverage_known_ = false;
  std::vector<unsigned char> covered_;  // blocks_w_ × blocks_h_
};

}  // namespace artcam
