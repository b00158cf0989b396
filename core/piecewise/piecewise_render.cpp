// SPDX-License-Identifier: Apache-2.0
// Mesh warp through a piecewise camera; see piecewise_render.h.
#include "core/piecewise/piecewise_render.h"

#include "core/model/image_view.h"
#include "core/mapping/coordinates.h"
#include "core/mapping/rational_map.h"
#include "core/sampling/span_sampler.h"
#include "core/util/cpu_features.h"
#include "core/util/parallel.h"
#include "core/util/scratch.h"

#include <Eigen/Geometry>
#include <Eigen/LU>

#if defined(__SSE2__)
#include <emmintrin.h>
#include <immintrin.h>
#endif

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>
#include <stdexcept>
#include <type_traits>
#include <vector>

namespace artcam {
namespace {

double edge(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double px, double py) {
  return (b.x() - a.x()) * (py - a.y()) - (b.y() - a.y()) * (px - a.x());
}

constexpr int kBandRows = 16;
// Cells per side of a chunk: the unit the bands list. A chunk's target bounding box decides
// which bands look at its cells, so a band visits the few thousand cells near it, not the
// lattice (millions at 24 MP), and no per-triangle record is ever stored.
constexpr int kChunkCells = 16;

// A target-space bounding box, empty (x0 > x1) until something is added.
struct Box {
  double x0 = std::numeric_limits<double>::infinity(), y0 = x0, x1 = -x0, y1 = -x0;
  void add(const Eigen::Vector2d& p) {
    x0 = std::min(x0, p.x()), y0 = std::min(y0, p.y()), x1 = std::max(x1, p.x()), y1 = std::max(y1, p.y());
  }
  void add(const Box& b) { x0 = std::min(x0, b.x0), y0 = std::min(y0, b.y0), x1 = std::max(x1, b.x1), y1 = std::max(y1, b.y1); }
};

// `count` values carved from a scratch block (scratch.h): the mesh's arrays are rebuilt every
// render, and as vectors their ~1 MB at a 45 px lattice on 24 MP would come back from the
// system with every page faulted and zeroed again (so do the band buffers, renderPiecewise).
template <typename T>
struct ScratchArray {
  T* data = nullptr;
  size_t count = 0;
  T& operator[](size_t i) const { return data[i]; }
  T* begin() const { return data; }
  T* end() const { return data + count; }
  size_t size() const { return count; }
};

// The source lattice (vertex (i, j) at all.x0 + i · step, clamped to the patches' extent)
// mapped forward into output pixels, and which cells the mesh draws.
struct Mesh {
  int nx = 0, ny = 0;                     // vertices per row and per column
  PatchRect all;                          // the patches' extent, source pixels of the camera
  double step = 0.0;
  Eigen::Vector2d source_scale{1.0, 1.0};  // camera source pixels → source image pixels
  Eigen::Vector2d out_scale{1.0, 1.0};     // camera target pixels → output pixels
  ScratchBlock storage;                   // holds the arrays below
  ScratchArray<Eigen::Vector2d> target;   // output pixels, nx · ny
  ScratchArray<unsigned char> valid;      // some patch maps the vertex
  ScratchArray<int> patch;                // the one patch that maps the vertex; −1: several
                                          // (their average is taken) or none
  ScratchArray<unsigned char> cell_ok;    // (nx − 1) · (ny − 1): the cell's centre has data,
                                          // or the outline crosses it (extendToOutlines)
  // The vertex has no data of its own but a cell the outline crosses needs it: mapped through
  // the patch of that cell's vertices that have data (its index in `patch`). Triangles with
  // such a vertex are drawn pixel by pixel up to the outline (keepOutlinePixel).
  ScratchArray<unsigned char> outside;
  bool gaps = false;                      // some vertex or cell centre has no data
  bool outlines = false;                  // some vertex is `outside`
  // The bend of the lattice's edges from vertex (i, j): to its right, down and down-right
  // neighbour. The exact preimage of the midpoint of the edge's two targets, less the
  // midpoint of its two sources (camera source pixels): what makes the triangles quadratic.
  ScratchArray<Eigen::Vector2d> bend[3];
  int chunks_x = 0, chunks_y = 0;
  std::vector<std::vector<int>> bands;    // chunks whose cells may cover each band's rows
  // Per cell row j and chunk column ci (j · chunks_x + ci): the output box of its drawn
  // triangles (empty where it draws none). A band skips a chunk's cell rows that miss it with
  // one test each instead of one per cell.
  std::vector<Box> row_boxes;
  long long triangles = 0;

  // Without a patch frame (piecewise_camera.h) the lattice is in source pixels; with one it is
  // in the patch frame, where the rectangles are, and each vertex's source position is its
  // preimage under the homography composed before: the mesh is then the piecewise camera's
  // own, with the sources moved, so the composition renders as the two in turn without the
  // second resampling.
  bool has_patch_frame = false;
  Eigen::Matrix3d source_from_patch = Eigen::Matrix3d::Identity();
  // The camera (outlives the mesh: the render's caller holds it), its patches' forward maps in
  // pixels, and the rectangles' tolerance: set first by buildMesh, read by everything after.
  const PiecewiseCamera* camera = nullptr;
  std::vector<RationalMap> maps;
  double tolerance = 0.0;

  size_t at(int i, int j) const { return static_cast<size_t>(j) * static_cast<size_t>(nx) + static_cast<size_t>(i); }
  // Vertex (i, j) in the patch frame.
  Eigen::Vector2d latticeAt(int i, int j) const {
    return {std::min(all.x1, all.x0 + i * step), std::min(all.y1, all.y0 + j * step)};
  }
  // Its source position (camera source pixels); not finite beyond the pole line.
  Eigen::Vector2d sourceOf(const Eigen::Vector2d& lattice) const {
    if (!has_patch_frame) return lattice;
    const Eigen::Vector3d x = source_from_patch * lattice.homogeneous();
    if (!(x.z() > 0.0)) return Eigen::Vector2d::Constant(std::numeric_limits<double>::quiet_NaN());
    return x.hnormalized();
  }
  Eigen::Vector2d sourceAt(int i, int j) const { return sourceOf(latticeAt(i, j)); }
};

// The mesh's arrays for `vertices` vertices and `cells` cells, in one scratch block: targets
// and bends uninitialised, valid 0, patch −1, cell_ok 0.
void allocateArrays(Mesh& mesh, size_t vertices, size_t cells) {
  const auto rounded = [](size_t bytes) { return (bytes + 63) / 64 * 64; };  // each array on a cache line
  const size_t points = rounded(vertices * sizeof(Eigen::Vector2d));
  const size_t bytes =
      4 * points + rounded(vertices * sizeof(int)) + 2 * rounded(vertices) + rounded(cells);
  mesh.storage = takeScratch(bytes);
  char* at = static_cast<char*>(mesh.storage.data());
  const auto carve = [&](auto& array, size_t count, size_t size) {
    array.data = reinterpret_cast<std::remove_reference_t<decltype(array[0])>*>(at);
    array.count = count;
    at += rounded(size);
  };
  carve(mesh.target, vertices, vertices * sizeof(Eigen::Vector2d));
  for (auto& b : mesh.bend) carve(b, vertices, vertices * sizeof(Eigen::Vector2d));
  carve(mesh.patch, vertices, vertices * sizeof(int));
  carve(mesh.valid, vertices, vertices);
  carve(mesh.outside, vertices, vertices);
  carve(mesh.cell_ok, cells, cells);
  std::fill(mesh.valid.begin(), mesh.valid.end(), 0);
  std::fill(mesh.outside.begin(), mesh.outside.end(), 0);
  std::fill(mesh.patch.begin(), mesh.patch.end(), -1);
  std::fill(mesh.cell_ok.begin(), mesh.cell_ok.end(), 0);
}

// Lattice indices [first, last] whose coordinate (origin + k · step, clamped to `end`) may lie
// in [lo, hi]: one index of slack each side, the exact test is the caller's.
void latticeRange(double origin, double step, double end, int count, double lo, double hi, int& first, int& last) {
  first = std::max(0, static_cast<int>(std::floor((lo - origin) / step)) - 1);
  last = std::min(count - 1, static_cast<int>(std::ceil((std::min(hi, end) - origin) / step)) + 1);
  if (hi >= end) last = count - 1;  // the clamped last vertex sits on `end`
}

// Patch k has data at the patch-frame point: inside its rectangle (to `tolerance`) and its
// support. What a vertex, a cell centre and an outline pixel are each held to.
bool holdsData(const PiecewiseCamera& camera, size_t k, const Eigen::Vector2d& p,
               double tolerance) {
  return camera.patches[k].rect.contains(p, tolerance) && camera.supports(static_cast<int>(k), p);
}

// The patches' averaged map at a source point, as at the vertices, with the first patch's
// Jacobian; false where no patch has data.
bool averagedMap(const PiecewiseCamera& camera, const std::vector<RationalMap>& maps, const Eigen::Vector2d& s,
                 double tolerance, Eigen::Vector2d& target, Eigen::Matrix2d& jacobian) {
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  int count = 0;
  const std::optional<Eigen::Vector2d> in_patch_frame = camera.patchPixelFromSourcePixel(s);
  if (!in_patch_frame) return false;
  const Eigen::Vector2d& p = *in_patch_frame;
  for (size_t k = 0; k < camera.patches.size(); ++k) {
    Eigen::Vector2d t;
    Eigen::Matrix2d j;
    if (holdsData(camera, k, p, tolerance) && maps[k].evaluate(s, t, count == 0 ? &j : nullptr)) {
      if (count == 0) jacobian = j;
      sum += t;
      ++count;
    }
  }
  if (count == 0) return false;
  target = sum / count;
  return true;
}

// The exact preimage of `target` (camera target pixels) near `start`: two Newton steps through
// patch `patch`'s map, or the averaged map when it is −1. False where the map has no data or
// no inverse Jacobian.
bool preimageNear(const PiecewiseCamera& camera, const std::vector<RationalMap>& maps, int patch,
                  const Eigen::Vector2d& target, Eigen::Vector2d start, double tolerance, Eigen::Vector2d& source) {
  for (int k = 0; k < 2; ++k) {
    Eigen::Vector2d f;
    Eigen::Matrix2d j;
    const bool mapped = patch >= 0 ? maps[static_cast<size_t>(patch)].evaluate(start, f, &j)
                                   : averagedMap(camera, maps, start, tolerance, f, j);
    if (!mapped || !(std::abs(j.determinant()) > 0.0)) return false;
    start += j.inverse() * (target - f);
  }
  source = start;
  return start.allFinite();
}

// Where a patch's data ends inside a cell (the outline of a marked wall, the hull of a fitted
// grid), the cell would be dropped with the vertices beyond the outline, leaving a staircase up
// to a cell deep inside it transparent. Instead each such vertex is mapped through the patch of
// the cell's vertices that have data (its camera is defined past its data; the outline only
// says where it is trusted) and the cell is drawn; keepOutlinePixel then cuts its triangles at
// the outline pixel by pixel. A cell the outline only clips at a corner, none of whose
// vertices has data, is still dropped (at most half a cell's corner).
void extendToOutlines(Mesh& mesh) {
  const int cells_x = mesh.nx - 1, cells_y = mesh.ny - 1;
  const auto holder = [&](const Eigen::Vector2d& v) {
    for (size_t k = 0; k < mesh.camera->patches.size(); ++k)
      if (holdsData(*mesh.camera, k, v, mesh.tolerance)) return static_cast<int>(k);
    return -1;
  };
  for (int j = 0; j < cells_y; ++j)
    for (int i = 0; i < cells_x; ++i) {
      const size_t v[4] = {mesh.at(i, j), mesh.at(i + 1, j), mesh.at(i, j + 1),
                           mesh.at(i + 1, j + 1)};
      int with_data = -1, without = 0;
      for (int q = 0; q < 4; ++q) {
        if (mesh.valid[v[q]] && !mesh.outside[v[q]]) {
          if (with_data < 0) with_data = q;
        } else if (!mesh.valid[v[q]]) {
          ++without;
        }
      }
      if (with_data < 0 || without == 0) continue;
      const int qi = i + (with_data & 1), qj = j + (with_data >> 1);
      const int k =
          mesh.patch[v[with_data]] >= 0 ? mesh.patch[v[with_data]] : holder(mesh.latticeAt(qi, qj));
      if (k < 0) continue;
      bool all = true;
      for (int q = 0; q < 4; ++q) {
        if (mesh.valid[v[q]]) continue;
        const Eigen::Vector2d source = mesh.sourceAt(i + (q & 1), j + (q >> 1));
        Eigen::Vector2d t;
        if (source.allFinite() && mesh.maps[static_cast<size_t>(k)].evaluate(source, t, nullptr) &&
            t.allFinite()) {
          mesh.valid[v[q]] = 1;
          mesh.outside[v[q]] = 1;
          mesh.patch[v[q]] = k;
          mesh.target[v[q]] = t.cwiseProduct(mesh.out_scale);
          mesh.outlines = true;
        } else {
          all = false;
        }
      }
      if (all)
        mesh.cell_ok[static_cast<size_t>(j) * static_cast<size_t>(cells_x) +
                     static_cast<size_t>(i)] = 1;
    }
}

// A pixel of a triangle drawn past an outline (Mesh::outside) is kept where its source
// position lies in a patch's data (as a vertex's must, buildMesh) and that patch maps it back
// onto the pixel: a triangle extrapolated across a fold or a pole never shows through.
bool keepOutlinePixel(const Mesh& mesh, int x, int y, float sx, float sy) {
  const Eigen::Vector2d source(sx / mesh.source_scale.x(), sy / mesh.source_scale.y());
  const std::optional<Eigen::Vector2d> p = mesh.camera->patchPixelFromSourcePixel(source);
  if (!p) return false;
  const Eigen::Vector2d centre(x + 0.5, y + 0.5);
  for (size_t k = 0; k < mesh.camera->patches.size(); ++k) {
    Eigen::Vector2d t;
    if (holdsData(*mesh.camera, k, *p, mesh.tolerance) &&
        mesh.maps[k].evaluate(source, t, nullptr) &&
        (t.cwiseProduct(mesh.out_scale) - centre).norm() <= 0.5)
      return true;
  }
  return false;
}

// With `whole_only`, a lattice with a vertex or cell without data is returned as soon as that
// is known (gaps set; no bends, chunks or bands): the step choice's test for coarse lattices.
Mesh buildMesh(const PiecewiseCamera& camera, FrameSize source_image, FrameSize size, double step,
               int threads, bool whole_only = false) {
  Mesh mesh;
  mesh.step = step;
  PatchRect& all = mesh.all;
  all = camera.patches.front().rect;
  for (const CameraPatch& p : camera.patches) {
    all.x0 = std::min(all.x0, p.rect.x0);
    all.y0 = std::min(all.y0, p.rect.y0);
    all.x1 = std::max(all.x1, p.rect.x1);
    all.y1 = std::max(all.y1, p.rect.y1);
  }
  const int nx = mesh.nx = static_cast<int>(std::ceil(all.width() / step)) + 1;
  const int ny = mesh.ny = static_cast<int>(std::ceil(all.height() / step)) + 1;
  mesh.source_scale = {static_cast<double>(source_image.width) / camera.source_size.width,
                       static_cast<double>(source_image.height) / camera.source_size.height};
  const Eigen::Vector2d out_scale = mesh.out_scale = {static_cast<double>(size.width) / camera.target_size.width,
                                                      static_cast<double>(size.height) / camera.target_size.height};
  if (camera.patch_frame) {
    mesh.has_patch_frame = true;
    mesh.source_from_patch = camera.patch_frame->patch_from_source.inverse();
  }
  const size_t vertices = static_cast<size_t>(nx) * static_cast<size_t>(ny);
  allocateArrays(mesh, vertices, static_cast<size_t>(std::max(0, nx - 1)) * static_cast<size_t>(std::max(0, ny - 1)));
  const double tolerance = mesh.tolerance = 1e-9 * std::max(all.width(), all.height());
  mesh.camera = &camera;
  // Each patch's forward map in pixels, evaluated from its six coefficients per form
  // (rational_map.h): the lattice asks it ~1.5 million times at 24 MP.
  for (const CameraPatch& p : camera.patches)
    mesh.maps.emplace_back(p.camera, camera.source_size, camera.target_size);
  const std::vector<RationalMap>& maps = mesh.maps;
  const auto cellAt = [&](int i, int j) { return static_cast<size_t>(j) * static_cast<size_t>(nx - 1) + static_cast<size_t>(i); };
  ParallelOptions po;
  po.threads = threads;
  po.band_rows = 8;
  parallelForRows(ny, po, [&](int j0, int j1) {
    std::vector<Eigen::Vector2d> sum(static_cast<size_t>(nx));
    std::vector<int> count(static_cast<size_t>(nx)), last_patch(static_cast<size_t>(nx));
    for (int j = j0; j < j1; ++j) {
      std::fill(sum.begin(), sum.end(), Eigen::Vector2d::Zero());
      std::fill(count.begin(), count.end(), 0);
      const double y = mesh.latticeAt(0, j).y();
      const double centre_y = std::min(all.y1, all.y0 + (j + 0.5) * step);
      // Only the patches whose rectangle holds the row, over the columns it spans: the same
      // tests as one pass over every patch per vertex, at a fraction of the cost.
      for (size_t k = 0; k < camera.patches.size(); ++k) {
        const PatchRect& r = camera.patches[k].rect;
        if (y < r.y0 - tolerance || y > r.y1 + tolerance) continue;
        int first = 0, last = -1;
        latticeRange(all.x0, step, all.x1, nx, r.x0 - tolerance, r.x1 + tolerance, first, last);
        for (int i = first; i <= last; ++i) {
          const Eigen::Vector2d v = mesh.latticeAt(i, j);
          Eigen::Vector2d t;
          if (!holdsData(camera, k, v, tolerance)) continue;
          const Eigen::Vector2d source = mesh.sourceOf(v);
          if (source.allFinite() && maps[k].evaluate(source, t, nullptr)) {
            sum[static_cast<size_t>(i)] += t;
            ++count[static_cast<size_t>(i)];
            last_patch[static_cast<size_t>(i)] = static_cast<int>(k);
          }
        }
      }
      for (int i = 0; i < nx; ++i)
        if (count[static_cast<size_t>(i)] > 0) {
          mesh.valid[mesh.at(i, j)] = 1;
          if (count[static_cast<size_t>(i)] == 1) mesh.patch[mesh.at(i, j)] = last_patch[static_cast<size_t>(i)];
          mesh.target[mesh.at(i, j)] = (sum[static_cast<size_t>(i)] / count[static_cast<size_t>(i)]).cwiseProduct(out_scale);
        }
      // A cell counts only when its centre lies where a patch has data (the quadtree's empty
      // corners stay empty).
      if (j + 1 >= ny) continue;
      for (size_t k = 0; k < camera.patches.size(); ++k) {
        const PatchRect& r = camera.patches[k].rect;
        if (centre_y < r.y0 || centre_y > r.y1) continue;
        int first = 0, last = -1;
        latticeRange(all.x0 + 0.5 * step, step, all.x1, nx - 1, r.x0, r.x1, first, last);
        for (int i = first; i <= last; ++i) {
          unsigned char& ok = mesh.cell_ok[cellAt(i, j)];
          if (ok) continue;
          const Eigen::Vector2d centre(std::min(all.x1, all.x0 + (i + 0.5) * step), centre_y);
          ok = holdsData(camera, k, centre, 0.0) ? 1 : 0;
        }
      }
    }
  });
  mesh.gaps = std::find(mesh.valid.begin(), mesh.valid.end(), 0) != mesh.valid.end() ||
              std::find(mesh.cell_ok.begin(), mesh.cell_ok.end(), 0) != mesh.cell_ok.end();
  if (whole_only && mesh.gaps) return mesh;
  if (mesh.gaps) extendToOutlines(mesh);
  // Chunks: the target bounding box of each chunk's drawn triangles, per cell row first (in
  // parallel), then merged; the triangle count on the way.
  const int cells_x = std::max(0, nx - 1), cells_y = std::max(0, ny - 1);
  mesh.chunks_x = (cells_x + kChunkCells - 1) / kChunkCells;
  mesh.chunks_y = (cells_y + kChunkCells - 1) / kChunkCells;
  std::vector<Box>& row_boxes = mesh.row_boxes;
  row_boxes.assign(static_cast<size_t>(cells_y) * static_cast<size_t>(mesh.chunks_x), Box{});
  std::atomic<long long> triangles{0};
  for (auto& b : mesh.bend) std::fill(b.begin(), b.end(), Eigen::Vector2d::Zero());
  // Edge (i, j) → (i + di, j + dj)'s bend, where both ends are mapped.
  const auto bendOf = [&](int i, int j, int di, int dj) {
    const size_t a = mesh.at(i, j), b = mesh.at(i + di, j + dj);
    if (!mesh.valid[a] || !mesh.valid[b]) return Eigen::Vector2d(Eigen::Vector2d::Zero());
    const Eigen::Vector2d m = 0.5 * (mesh.sourceAt(i, j) + mesh.sourceAt(i + di, j + dj));
    const Eigen::Vector2d mid = (0.5 * (mesh.target[a] + mesh.target[b])).cwiseQuotient(out_scale);
    Eigen::Vector2d exact;
    const int patch = mesh.patch[a] >= 0 && mesh.patch[a] == mesh.patch[b] ? mesh.patch[a] : -1;
    if (!preimageNear(camera, maps, patch, mid, m, tolerance, exact)) return Eigen::Vector2d(Eigen::Vector2d::Zero());
    return Eigen::Vector2d(exact - m);
  };
  parallelForRows(cells_y, po, [&](int j0, int j1) {
    long long count = 0;
    for (int j = j0; j < j1; ++j) {
      // The edges the cells of row j draw: right edges of vertex rows j (and j + 1 on the
      // last row), down edges of every vertex of row j, diagonals.
      for (int i = 0; i < nx; ++i) {
        const size_t v = mesh.at(i, j);
        if (i + 1 < nx) {
          mesh.bend[0][v] = bendOf(i, j, 1, 0);
          if (j + 1 == cells_y) mesh.bend[0][mesh.at(i, j + 1)] = bendOf(i, j + 1, 1, 0);
          mesh.bend[2][v] = bendOf(i, j, 1, 1);
        }
        mesh.bend[1][v] = bendOf(i, j, 0, 1);
      }
      for (int i = 0; i < cells_x; ++i) {
        if (!mesh.cell_ok[cellAt(i, j)]) continue;
        const size_t v00 = mesh.at(i, j), v10 = mesh.at(i + 1, j), v01 = mesh.at(i, j + 1), v11 = mesh.at(i + 1, j + 1);
        Box& box = row_boxes[static_cast<size_t>(j) * static_cast<size_t>(mesh.chunks_x) + static_cast<size_t>(i / kChunkCells)];
        const auto triangle = [&](size_t a, size_t b, size_t c) {
          if (!mesh.valid[a] || !mesh.valid[b] || !mesh.valid[c]) return;
          const Eigen::Vector2d &ta = mesh.target[a], &tb = mesh.target[b], &tc = mesh.target[c];
          if (!(std::abs(edge(ta, tb, tc.x(), tc.y())) > 1e-12)) return;
          ++count;
          box.add(ta), box.add(tb), box.add(tc);
        };
        triangle(v00, v10, v11);
        triangle(v00, v11, v01);
      }
    }
    triangles += count;
  });
  mesh.triangles = triangles.load();
  mesh.bands.resize(static_cast<size_t>((size.height + kBandRows - 1) / kBandRows));
  for (int cj = 0; cj < mesh.chunks_y; ++cj)
    for (int ci = 0; ci < mesh.chunks_x; ++ci) {
      Box box;
      for (int j = cj * kChunkCells; j < std::min(cells_y, (cj + 1) * kChunkCells); ++j)
        box.add(row_boxes[static_cast<size_t>(j) * static_cast<size_t>(mesh.chunks_x) + static_cast<size_t>(ci)]);
      if (!(box.x0 <= box.x1)) continue;  // nothing drawn
      const int y_begin = std::max(0, static_cast<int>(std::ceil(box.y0 - 0.5)));
      const int y_end = std::min(size.height - 1, static_cast<int>(std::floor(box.y1 - 0.5)));
      if (y_begin > y_end || box.x1 < 0.5 - 1e-9 || box.x0 > size.width - 0.5 + 1e-9) continue;
      for (int band = y_begin / kBandRows; band <= y_end / kBandRows; ++band)
        mesh.bands[static_cast<size_t>(band)].push_back(cj * mesh.chunks_x + ci);
    }
  return mesh;
}

// The cell's two triangles: the vertex offsets of each, counter-wise as drawn, and which bend
// each edge (a→b, b→c, c→a) takes, with the vertex it starts from.
struct TriangleShape {
  int v[3][2];          // (di, dj) of a, b, c
  int bend[3][3];       // per edge: bend index, (di, dj) of the vertex it belongs to
};
constexpr TriangleShape kTriangles[2] = {
    {{{0, 0}, {1, 0}, {1, 1}}, {{0, 0, 0}, {1, 1, 0}, {2, 0, 0}}},   // v00 v10 v11
    {{{0, 0}, {1, 1}, {0, 1}}, {{2, 0, 0}, {0, 0, 1}, {1, 0, 0}}},   // v00 v11 v01
};

// Edge a→b's bend as seen going that way: the bend is stored from the edge's first lattice
// vertex; traversing the edge backwards leaves the midpoint and so the bend unchanged.
Eigen::Vector2d bendOf(const Mesh& mesh, int i, int j, const int e[3]) {
  return mesh.bend[e[0]][mesh.at(i + e[1], j + e[2])];
}

// The quadratic triangle's source position at barycentric (wa, wb, wc): the vertices' blend
// plus each edge's bend on the edge's quadratic bubble 4 w w′ (1 at its midpoint, 0 at the
// vertices and along the other edges), so shared edges agree and the mesh stays continuous.
inline Eigen::Vector2d quadratic(double wa, double wb, double wc, const Eigen::Vector2d s[3], const Eigen::Vector2d bend[3]) {
  return wa * s[0] + wb * s[1] + wc * s[2] + 4.0 * (wa * wb * bend[0] + wb * wc * bend[1] + wc * wa * bend[2]);
}

// The largest J⁻¹ (t − f(s)) over the drawn triangles at their centroids and their edges'
// quarter points (where a quadratic's error peaks, away from the exact nodes), s the mesh's
// position for the target point t, f the map of the one patch that maps all three vertices: in
// pixels of the image rendered from. Triangles whose vertices several patches map, or
// different ones, are left out: there the mesh blends patches that disagree by the fit's seam
// gap (piecewise_fit.h reports it), which no step removes.
// An edge's points depend only on the edge (its two vertices, its bend, their patch), so an
// edge two drawn triangles share is measured once, by the cell's first triangle (kTriangles[0]:
// top, right and diagonal edges) where that is drawn, else by the second (bottom, left,
// diagonal): 8 evaluations a cell instead of 14.
double meshError(const Mesh& mesh, int threads) {
  const std::vector<RationalMap>& maps = mesh.maps;
  const int cells_x = mesh.nx - 1, cells_y = mesh.ny - 1;
  std::vector<double> row_worst(static_cast<size_t>(std::max(0, cells_y)), 0.0);
  // The centroid, then two points on each edge: a–b, b–c, c–a.
  const double points[7][3] = {{1 / 3.0, 1 / 3.0, 1 / 3.0}, {0.75, 0.25, 0}, {0.25, 0.75, 0}, {0, 0.75, 0.25},
                               {0, 0.25, 0.75}, {0.25, 0, 0.75}, {0.75, 0, 0.25}};
  // Whether triangle `shape` of cell (i, j) is drawn and measured: the cell is, and one patch
  // maps all three vertices (its index in `patch`).
  const auto drawn = [&](int i, int j, const TriangleShape& shape, int* patch_out) {
    if (i < 0 || j < 0 || i >= cells_x || j >= cells_y) return false;
    if (!mesh.cell_ok[static_cast<size_t>(j) * static_cast<size_t>(cells_x) + static_cast<size_t>(i)]) return false;
    const int patch = mesh.patch[mesh.at(i + shape.v[0][0], j + shape.v[0][1])];
    if (patch < 0) return false;
    for (int q = 0; q < 3; ++q) {
      const size_t v = mesh.at(i + shape.v[q][0], j + shape.v[q][1]);
      if (!mesh.valid[v] || mesh.patch[v] != patch) return false;
    }
    if (patch_out) *patch_out = patch;
    return true;
  };
  ParallelOptions po;
  po.threads = threads;
  po.band_rows = 8;
  parallelForRows(std::max(0, cells_y), po, [&](int j0, int j1) {
    for (int j = j0; j < j1; ++j) {
      double worst = 0.0;
      for (int i = 0; i < cells_x; ++i) {
        for (int k = 0; k < 2; ++k) {
          const TriangleShape& shape = kTriangles[k];
          int patch = -1;
          if (!drawn(i, j, shape, &patch)) continue;
          // Which of its edges this triangle measures: all of the first's; the second's (a–b
          // the diagonal, b–c the bottom, c–a the left) where the first triangle across it is
          // not drawn.
          bool edge[3] = {true, true, true};
          if (k == 1) {
            edge[0] = !drawn(i, j, kTriangles[0], nullptr);
            edge[1] = !drawn(i, j + 1, kTriangles[0], nullptr);
            edge[2] = !drawn(i - 1, j, kTriangles[0], nullptr);
          }
          Eigen::Vector2d s[3], t[3], bend[3];
          for (int q = 0; q < 3; ++q) {
            const size_t v = mesh.at(i + shape.v[q][0], j + shape.v[q][1]);
            s[q] = mesh.sourceAt(i + shape.v[q][0], j + shape.v[q][1]);
            t[q] = mesh.target[v].cwiseQuotient(mesh.out_scale);
            bend[q] = bendOf(mesh, i, j, shape.bend[q]);
          }
          for (int p = 0; p < 7; ++p) {
            if (p > 0 && !edge[(p - 1) / 2]) continue;
            const double* w = points[p];
            const Eigen::Vector2d target = w[0] * t[0] + w[1] * t[1] + w[2] * t[2];
            const Eigen::Vector2d source = quadratic(w[0], w[1], w[2], s, bend);
            Eigen::Vector2d f;
            Eigen::Matrix2d jac;
            if (!maps[static_cast<size_t>(patch)].evaluate(source, f, &jac) || !(std::abs(jac.determinant()) > 0.0)) continue;
            const double err = (jac.inverse() * (target - f)).cwiseProduct(mesh.source_scale).norm();
            if (std::isfinite(err)) worst = std::max(worst, err);
          }
        }
      }
      row_worst[static_cast<size_t>(j)] = worst;
    }
  });
  double worst = 0.0;
  for (const double w : row_worst) worst = std::max(worst, w);
  return worst;
}

// The step for the options, and its mesh when it was built on the way.
MeshChoice chooseStep(const PiecewiseCamera& camera, FrameSize source_image, FrameSize size,
                      const PiecewiseRenderOptions& options, std::optional<Mesh>* built) {
  MeshChoice choice;
  if (options.mesh_step_px > 0.0) {
    choice.step_px = std::max(0.25, options.mesh_step_px);
    if (!built)
      choice.error_px = meshError(
          buildMesh(camera, source_image, size, choice.step_px, options.threads), options.threads);
    else choice.error_px = -1.0;  // not measured
    return choice;
  }
  // The error falls as the step cubed (quadratic triangles). So a coarse lattice is measured
  // first, the step that law predicts at kAim of the budget is measured next, and so on down:
  // the step used is one whose measured error is within the budget (or the finest, 2 px,
  // whatever it measures), and the rasteriser's work per pixel falls with the step (its rows
  // are shorter the finer the mesh).
  // The first lattice, 128 px, is only a probe, cheap beside a 64-px one: the step used is at
  // most 64 px, since so coarse a lattice may have too few triangles inside single patches to
  // measure (a small insertion region's measured none), and its centroid-and-quarter-point
  // estimate grows less certain. The law extrapolated from so far overestimates the step (a
  // mild lens on a 320×240 frame: 0.0453 px at 128 predicted 0.0030 at 52, which measured
  // 0.0039), so the probe's step aims at kProbeAim of the budget.
  // Where the patches leave holes or a ragged edge, the cells their outline crosses are drawn
  // through a patch's camera past its data (extendToOutlines): there the step stays at most
  // 32 px, so that extrapolation reaches at most a 32-px cell beyond the data. A coarser one is
  // kept only where every vertex and cell centre of its lattice has data, a test at the lattice's
  // own spacing (a notch narrower than a step between those points could still pass it).
  constexpr double kProbe = 128.0, kCoarsest = 64.0, kCoarsestAtEdges = 32.0, kFinest = 2.0, kAim = 0.8,
                   kProbeAim = 0.75;
  double step = kProbe;
  for (int measured = 0;;) {
    const bool coarse = step > kCoarsestAtEdges, probe = step > kCoarsest;
    Mesh mesh = buildMesh(camera, source_image, size, step, options.threads, /*whole_only=*/coarse);
    if (coarse && mesh.gaps) {  // known before its bends are solved
      step = kCoarsestAtEdges;
      continue;
    }
    const double error = meshError(mesh, options.threads);
    if (probe) {
      step = error > 0.0 ? std::min(kCoarsest, std::floor(step * std::cbrt(kProbeAim * options.max_error_px / error)))
                         : kCoarsest;
      step = std::max(kFinest, step);
      continue;
    }
    choice.step_px = step;
    choice.error_px = error;
    ++measured;
    if (choice.error_px <= options.max_error_px || step <= kFinest) {
      if (built) built->emplace(std::move(mesh));
      break;
    }
    // Whole pixels, at least a tenth finer each time, and halving once the law's predictions
    // have missed twice (a camera whose error does not follow it still ends in a few meshes).
    double next = std::floor(step * std::cbrt(kAim * options.max_error_px / choice.error_px));
    next = std::min(next, std::floor(0.9 * step));
    if (measured >= 3) next = std::min(next, step / 2.0);
    step = std::max(kFinest, next);
  }
  return choice;
}

// A triangle's pixel rows, set up once per band (triangleRows) and walked row by row (rowRun).
// Each barycentric weight is affine in x along a row, so the position is quadratic in it:
// p(k) = p0 + k (d1 + k d2), evaluated per pixel (no value carried from one pixel to the next).
struct TriangleRows {
  int row_begin = 0, row_end = -1, x_begin = 0;
  double k_max = 0.0, eps = 0.0, eps_bound = 0.0;
  double w_first[3] = {}, dy[3] = {}, dw[3] = {}, inv_dw[3] = {};
  Eigen::Vector2d d_linear, d2;
  const Eigen::Vector2d* s = nullptr;
  const Eigen::Vector2d* bend = nullptr;
};

// False when the triangle has no pixel centre in rows [y0, y1).
bool triangleRows(const Eigen::Vector2d t[3], const Eigen::Vector2d s[3], const Eigen::Vector2d bend[3], int y0,
                  int y1, int width, TriangleRows& rows) {
  const Eigen::Vector2d &a = t[0], &b = t[1], &c = t[2];
  const double lo_y = std::min({a.y(), b.y(), c.y()}), hi_y = std::max({a.y(), b.y(), c.y()});
  rows.row_begin = std::max(y0, static_cast<int>(std::ceil(lo_y - 0.5)));
  rows.row_end = std::min(y1 - 1, static_cast<int>(std::floor(hi_y - 0.5)));
  if (rows.row_begin > rows.row_end) return false;
  const double lo_x = std::min({a.x(), b.x(), c.x()}), hi_x = std::max({a.x(), b.x(), c.x()});
  rows.x_begin = std::max(0, static_cast<int>(std::ceil(lo_x - 0.5)));
  const int x_end = std::min(width - 1, static_cast<int>(std::floor(hi_x - 0.5)));
  if (rows.x_begin > x_end) return false;
  const double area = edge(a, b, c.x(), c.y());
  if (!(std::abs(area) > 1e-12)) return false;
  rows.eps = -1e-9 * std::abs(area);
  // The row's run of pixels inside is bounded by dividing: each weight w0 + k dw ≥ eps is a
  // half-line in k. The bound is taken at twice eps, so rounding (~1e-16 of k) never drops a
  // pixel the per-pixel test w ≥ eps would keep: a pixel on an edge shared by two triangles is
  // drawn by both, with the same position to rounding (the mesh is continuous), never by neither.
  rows.eps_bound = 2.0 * rows.eps;
  rows.k_max = x_end - rows.x_begin;
  const double inv = 1.0 / area;
  const double dwa = -(c.y() - b.y()) * inv, dwb = -(a.y() - c.y()) * inv, dwc = -(b.y() - a.y()) * inv;
  rows.d_linear = dwa * s[0] + dwb * s[1] + dwc * s[2];
  rows.d2 = 4.0 * (dwa * dwb * bend[0] + dwb * dwc * bend[1] + dwc * dwa * bend[2]);
  // And affine in y at the row's first pixel.
  const double px0 = rows.x_begin + 0.5, py0 = rows.row_begin + 0.5;
  rows.w_first[0] = edge(b, c, px0, py0) * inv;
  rows.w_first[1] = edge(c, a, px0, py0) * inv;
  rows.w_first[2] = edge(a, b, px0, py0) * inv;
  rows.dy[0] = (c.x() - b.x()) * inv;
  rows.dy[1] = (a.x() - c.x()) * inv;
  rows.dy[2] = (b.x() - a.x()) * inv;
  rows.dw[0] = dwa;
  rows.dw[1] = dwb;
  rows.dw[2] = dwc;
  for (int q = 0; q < 3; ++q) rows.inv_dw[q] = rows.dw[q] != 0.0 ? 1.0 / rows.dw[q] : 0.0;
  rows.s = s;
  rows.bend = bend;
  return true;
}

// Row y's run of pixels inside, k … end (offsets from x_begin), where it starts in the band's
// buffers (band rows from y0, `width` apart), and its positions p(m) = p + m (d1 + m d2).
struct RowRun {
  int k = 0, end = -1;
  size_t at = 0;  // the band buffers' index of the row's pixel x_begin
  Eigen::Vector2d p, d1;
};
// The position at a row's first pixel of the box (k = 0) and its slope there, from the row's
// weights there: quadratic() and its derivative along x, one coordinate at a time in the order
// rowsAvx512's lanes repeat (eight rows at once), so both give the same bits.
__attribute__((always_inline)) inline void rowStart(const TriangleRows& rows, const double w0[3], Eigen::Vector2d& p,
                                                    Eigen::Vector2d& d1) {
  const Eigen::Vector2d* s = rows.s;
  const Eigen::Vector2d* bend = rows.bend;
  const double* dw = rows.dw;
  const double b01 = w0[0] * w0[1], b12 = w0[1] * w0[2], b20 = w0[2] * w0[0];
  const double g01 = w0[0] * dw[1] + dw[0] * w0[1], g12 = w0[1] * dw[2] + dw[1] * w0[2],
               g20 = w0[2] * dw[0] + dw[2] * w0[0];
  for (int c = 0; c < 2; ++c) {
    p[c] = w0[0] * s[0][c] + w0[1] * s[1][c] + w0[2] * s[2][c] +
           4.0 * (b01 * bend[0][c] + b12 * bend[1][c] + b20 * bend[2][c]);
    d1[c] = rows.d_linear[c] + 4.0 * (g01 * bend[0][c] + g12 * bend[1][c] + g20 * bend[2][c]);
  }
}

// False when the row has none. Inlined into each clone of the row loop (a call per row costs
// more than the row's eight-wide steps); the clones agree bit for bit because this file is
// built without floating-point contraction (CMakeLists), so no clone fuses a multiply-add.
__attribute__((always_inline)) inline bool rowRun(const TriangleRows& rows, int y, int y0, int width, RowRun& run) {
  const double ry = y - rows.row_begin;
  const double w0[3] = {rows.w_first[0] + ry * rows.dy[0], rows.w_first[1] + ry * rows.dy[1],
                        rows.w_first[2] + ry * rows.dy[2]};
  double k_lo = 0.0, k_hi = rows.k_max;
  for (int q = 0; q < 3; ++q) {
    const double at = (rows.eps_bound - w0[q]) * rows.inv_dw[q];
    if (rows.dw[q] > 0.0) k_lo = std::max(k_lo, at);
    else if (rows.dw[q] < 0.0) k_hi = std::min(k_hi, at);
    else if (w0[q] < rows.eps) k_hi = -1.0;
  }
  if (!(k_lo <= k_hi)) return false;
  // 0 ≤ k_lo ≤ k_hi ≤ k_max here: truncation is the floor, and the ceiling one more where
  // it cut (std::ceil and std::floor are a dozen instructions each on the x86-64 baseline).
  const int k_trunc = static_cast<int>(k_lo);
  run.k = k_trunc + (static_cast<double>(k_trunc) < k_lo ? 1 : 0);
  run.end = static_cast<int>(k_hi);
  if (run.k > run.end) return false;
  run.at = static_cast<size_t>(y - y0) * static_cast<size_t>(width) + static_cast<size_t>(rows.x_begin);
  rowStart(rows, w0, run.p, run.d1);
  return true;
}

#if defined(__x86_64__)
// A row's positions p(m) = p + m (d1 + m d2) for m = k … end, four at a time, with the SSE2
// loop's operations (no FMA) so every bit agrees; returns the first m it left.
__attribute__((target("avx2"))) int rowRunAvx2(double px, double py, double d1x, double d1y, double d2x,
                                               double d2y, int k, int end, float* row_x, float* row_y) {
  const __m256d ax = _mm256_set1_pd(px), ay = _mm256_set1_pd(py);
  const __m256d bx = _mm256_set1_pd(d1x), by = _mm256_set1_pd(d1y);
  const __m256d cx = _mm256_set1_pd(d2x), cy = _mm256_set1_pd(d2y);
  const __m256d four = _mm256_set1_pd(4.0);
  const double m0 = k;
  __m256d m = _mm256_setr_pd(m0, m0 + 1.0, m0 + 2.0, m0 + 3.0);
  int q = k;
  for (; q + 3 <= end; q += 4, m = _mm256_add_pd(m, four)) {
    const __m128 fx = _mm256_cvtpd_ps(_mm256_add_pd(ax, _mm256_mul_pd(m, _mm256_add_pd(bx, _mm256_mul_pd(m, cx)))));
    const __m128 fy = _mm256_cvtpd_ps(_mm256_add_pd(ay, _mm256_mul_pd(m, _mm256_add_pd(by, _mm256_mul_pd(m, cy)))));
    _mm_storeu_ps(row_x + q, fx);
    _mm_storeu_ps(row_y + q, fy);
  }
  return q;
}

#pragma GCC diagnostic push
// GCC 12's AVX-512 intrinsics start from _mm512_undefined_*() (a self-initialised variable):
// a false positive of both warnings.
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#pragma GCC diagnostic ignored "-Wuninitialized"
// The rows' set-up eight rows at a time, the row loop eight pixels per step, the last step
// masked, and the coverage bytes by masked stores: a band's triangles are short runs (~16
// pixels a row at a 32 px lattice, ~22 at 45 px), where the per-row set-up, the tails and a
// memset call per row would be most of the rasteriser's time.
// The same double operations as the portable loop (no FMA), so every bit agrees.
__attribute__((target("avx512f,avx512vl,avx512bw"))) long long rowsAvx512(const TriangleRows& rows, int y0,
                                                                                    int width, float* sx, float* sy,
                                                                                    unsigned char* valid) {
  long long covered = 0;
  const __m512d lanes = _mm512_setr_pd(0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0);
  const __m512d eight = _mm512_set1_pd(8.0);
  const __m512i ones = _mm512_set1_epi8(1);
  const __m512d cx = _mm512_set1_pd(rows.d2.x()), cy = _mm512_set1_pd(rows.d2.y());  // the triangle's
  // rowRun's set-up for eight rows at once, lane r for row y + r: each lane does the scalar
  // code's operations in its order (rowRun, rowStart), so every bit agrees. Per row it would be
  // most of the rasteriser's time: ~1.1 M runs of ~22 pixels a 24 MP render at a 45 px lattice.
  const __m512d four = _mm512_set1_pd(4.0), eps_bound = _mm512_set1_pd(rows.eps_bound), eps = _mm512_set1_pd(rows.eps);
  const __m512d k_max = _mm512_set1_pd(rows.k_max);
  __m512d wf[3], dy[3], dw[3], inv_dw[3];
  for (int q = 0; q < 3; ++q) {
    wf[q] = _mm512_set1_pd(rows.w_first[q]);
    dy[q] = _mm512_set1_pd(rows.dy[q]);
    dw[q] = _mm512_set1_pd(rows.dw[q]);
    inv_dw[q] = _mm512_set1_pd(rows.inv_dw[q]);
  }
  alignas(64) int first[8], last[8];
  alignas(64) double start_x[8], start_y[8], slope_x[8], slope_y[8];
  for (int y8 = rows.row_begin; y8 <= rows.row_end; y8 += 8) {
    const __m512d ry = _mm512_add_pd(_mm512_set1_pd(static_cast<double>(y8 - rows.row_begin)), lanes);
    __m512d w0[3];
    __m512d k_lo = _mm512_setzero_pd(), k_hi = k_max;
    for (int q = 0; q < 3; ++q) {
      w0[q] = _mm512_add_pd(wf[q], _mm512_mul_pd(ry, dy[q]));
      const __m512d at = _mm512_mul_pd(_mm512_sub_pd(eps_bound, w0[q]), inv_dw[q]);
      if (rows.dw[q] > 0.0) k_lo = _mm512_max_pd(k_lo, at);
      else if (rows.dw[q] < 0.0) k_hi = _mm512_min_pd(k_hi, at);
      else k_hi = _mm512_mask_mov_pd(k_hi, _mm512_cmp_pd_mask(w0[q], eps, _CMP_LT_OQ), _mm512_set1_pd(-1.0));
    }
    const int left = rows.row_end - y8 + 1;
    const __mmask8 open = _mm512_cmp_pd_mask(k_lo, k_hi, _CMP_LE_OQ) &
                          (left >= 8 ? static_cast<__mmask8>(0xFF) : static_cast<__mmask8>((1u << left) - 1u));
    if (!open) continue;
    _mm256_store_si256(reinterpret_cast<__m256i*>(first),
                       _mm512_cvt_roundpd_epi32(k_lo, _MM_FROUND_TO_POS_INF | _MM_FROUND_NO_EXC));
    _mm256_store_si256(reinterpret_cast<__m256i*>(last),
                       _mm512_cvt_roundpd_epi32(k_hi, _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC));
    const __m512d b01 = _mm512_mul_pd(w0[0], w0[1]), b12 = _mm512_mul_pd(w0[1], w0[2]), b20 = _mm512_mul_pd(w0[2], w0[0]);
    const __m512d g01 = _mm512_add_pd(_mm512_mul_pd(w0[0], dw[1]), _mm512_mul_pd(dw[0], w0[1]));
    const __m512d g12 = _mm512_add_pd(_mm512_mul_pd(w0[1], dw[2]), _mm512_mul_pd(dw[1], w0[2]));
    const __m512d g20 = _mm512_add_pd(_mm512_mul_pd(w0[2], dw[0]), _mm512_mul_pd(dw[2], w0[0]));
    double* const starts[2] = {start_x, start_y};
    double* const slopes[2] = {slope_x, slope_y};
    for (int c = 0; c < 2; ++c) {
      const __m512d s0 = _mm512_set1_pd(rows.s[0][c]), s1 = _mm512_set1_pd(rows.s[1][c]), s2 = _mm512_set1_pd(rows.s[2][c]);
      const __m512d e0 = _mm512_set1_pd(rows.bend[0][c]), e1 = _mm512_set1_pd(rows.bend[1][c]),
                    e2 = _mm512_set1_pd(rows.bend[2][c]);
      const __m512d blend = _mm512_add_pd(_mm512_add_pd(_mm512_mul_pd(w0[0], s0), _mm512_mul_pd(w0[1], s1)), _mm512_mul_pd(w0[2], s2));
      const __m512d bubble = _mm512_add_pd(_mm512_add_pd(_mm512_mul_pd(b01, e0), _mm512_mul_pd(b12, e1)), _mm512_mul_pd(b20, e2));
      _mm512_store_pd(starts[c], _mm512_add_pd(blend, _mm512_mul_pd(four, bubble)));
      const __m512d bent = _mm512_add_pd(_mm512_add_pd(_mm512_mul_pd(g01, e0), _mm512_mul_pd(g12, e1)), _mm512_mul_pd(g20, e2));
      _mm512_store_pd(slopes[c], _mm512_add_pd(_mm512_set1_pd(rows.d_linear[c]), _mm512_mul_pd(four, bent)));
    }
    for (int r = 0; r < 8; ++r) {
      if (!(open >> r & 1u)) continue;
      const int k = first[r], end = last[r];
      if (k > end) continue;
      const size_t at = static_cast<size_t>(y8 + r - y0) * static_cast<size_t>(width) + static_cast<size_t>(rows.x_begin);
      float* row_x = sx + at;
      float* row_y = sy + at;
      const __m512d ax = _mm512_set1_pd(start_x[r]), ay = _mm512_set1_pd(start_y[r]);
      const __m512d bx = _mm512_set1_pd(slope_x[r]), by = _mm512_set1_pd(slope_y[r]);
      __m512d m = _mm512_add_pd(_mm512_set1_pd(static_cast<double>(k)), lanes);
      for (int q = k; q <= end; q += 8, m = _mm512_add_pd(m, eight)) {
        const int run_left = end - q + 1;
        const __mmask8 mask = run_left >= 8 ? static_cast<__mmask8>(0xFF) : static_cast<__mmask8>((1u << run_left) - 1u);
        const __m256 fx = _mm512_cvtpd_ps(_mm512_add_pd(ax, _mm512_mul_pd(m, _mm512_add_pd(bx, _mm512_mul_pd(m, cx)))));
        const __m256 fy = _mm512_cvtpd_ps(_mm512_add_pd(ay, _mm512_mul_pd(m, _mm512_add_pd(by, _mm512_mul_pd(m, cy)))));
        _mm256_mask_storeu_ps(row_x + q, mask, fx);
        _mm256_mask_storeu_ps(row_y + q, mask, fy);
      }
      for (int q = k; q <= end; q += 64) {
        const int run_left = end - q + 1;
        const __mmask64 mask = run_left >= 64 ? ~__mmask64{0} : (__mmask64{1} << run_left) - 1;
        _mm512_mask_storeu_epi8(valid + at + q, mask, ones);
      }
      covered += end - k + 1;
    }
  }
  return covered;
}
#pragma GCC diagnostic pop
#endif

// The pixel centres of output rows [y0, y1) inside triangle t[0..2] (output pixels) into the
// band's position buffers (row r of the band at r · width), each the quadratic triangle's
// source position (quadratic(), in pixels of the image rendered from). Shared edges are drawn
// by both triangles with the same value (the mesh is continuous), so the inclusive test costs
// nothing but a second identical write.
long long rasterise(const Eigen::Vector2d t[3], const Eigen::Vector2d s[3], const Eigen::Vector2d bend[3], int y0,
                    int y1, int width, float* sx, float* sy, unsigned char* valid, bool avx512) {
  TriangleRows rows;
  if (!triangleRows(t, s, bend, y0, y1, width, rows)) return 0;
#if defined(__x86_64__)
  if (avx512) return rowsAvx512(rows, y0, width, sx, sy, valid);
#endif
  long long covered = 0;
  for (int y = rows.row_begin; y <= rows.row_end; ++y) {
    RowRun r;
    if (!rowRun(rows, y, y0, width, r)) continue;
    float* row_x = sx + r.at;
    float* row_y = sy + r.at;
    const Eigen::Vector2d &p = r.p, &d1 = r.d1, &d2 = rows.d2;
    const int k = r.k, end = r.end;
    int q = k;
#if defined(__x86_64__)
    if (cpuHasAvx2()) q = rowRunAvx2(p.x(), p.y(), d1.x(), d1.y(), d2.x(), d2.y(), k, end, row_x, row_y);
#endif
#if defined(__SSE2__)
    // Two pixels per step.
    const __m128d ax = _mm_set1_pd(p.x()), ay = _mm_set1_pd(p.y());
    const __m128d bx = _mm_set1_pd(d1.x()), by = _mm_set1_pd(d1.y());
    const __m128d cx = _mm_set1_pd(d2.x()), cy = _mm_set1_pd(d2.y());
    const double m0 = q;
    __m128d m = _mm_setr_pd(m0, m0 + 1.0);
    const __m128d two = _mm_set1_pd(2.0);
    for (; q + 1 <= end; q += 2, m = _mm_add_pd(m, two)) {
      const __m128 fx = _mm_cvtpd_ps(_mm_add_pd(ax, _mm_mul_pd(m, _mm_add_pd(bx, _mm_mul_pd(m, cx)))));
      const __m128 fy = _mm_cvtpd_ps(_mm_add_pd(ay, _mm_mul_pd(m, _mm_add_pd(by, _mm_mul_pd(m, cy)))));
      _mm_storel_pi(reinterpret_cast<__m64*>(row_x + q), fx);
      _mm_storel_pi(reinterpret_cast<__m64*>(row_y + q), fy);
    }
#endif
    for (; q <= end; ++q) {
      const double mm = q;
      row_x[q] = static_cast<float>(p.x() + mm * (d1.x() + mm * d2.x()));
      row_y[q] = static_cast<float>(p.y() + mm * (d1.y() + mm * d2.y()));
    }
    std::memset(valid + r.at + static_cast<size_t>(k), 1, static_cast<size_t>(end - k + 1));
    covered += end - k + 1;
  }
  return covered;
}

// Every drawn triangle of the chunks listed for the band of output rows [y0, y1).
// Triangles with an `outside` vertex go to the outline buffers (sx2, sy2, valid2), which the
// caller cuts at the outline (keepOutlinePixel); they are null when the mesh has none.
long long rasteriseBand(const Mesh& mesh, int y0, int y1, int width, float* sx, float* sy,
                        unsigned char* valid, float* sx2, float* sy2, unsigned char* valid2,
                        bool avx512) {
  const double top = y0 + 0.5 - 1e-9, bottom = y1 - 0.5 + 1e-9;  // the band's pixel centres
  const int cells_x = mesh.nx - 1, cells_y = mesh.ny - 1;
  long long covered = 0;
  for (const int chunk : mesh.bands[static_cast<size_t>(y0 / kBandRows)]) {
    const int ci = chunk % mesh.chunks_x, cj = chunk / mesh.chunks_x;
    for (int j = cj * kChunkCells; j < std::min(cells_y, (cj + 1) * kChunkCells); ++j) {
      const Box& drawn = mesh.row_boxes[static_cast<size_t>(j) * static_cast<size_t>(mesh.chunks_x) + static_cast<size_t>(ci)];
      if (!(drawn.x0 <= drawn.x1) || drawn.y1 < top || drawn.y0 > bottom) continue;
      for (int i = ci * kChunkCells; i < std::min(cells_x, (ci + 1) * kChunkCells); ++i) {
        if (!mesh.cell_ok[static_cast<size_t>(j) * static_cast<size_t>(cells_x) + static_cast<size_t>(i)]) continue;
        const size_t v[4] = {mesh.at(i, j), mesh.at(i + 1, j), mesh.at(i, j + 1), mesh.at(i + 1, j + 1)};
        const double lo = std::min({mesh.target[v[0]].y(), mesh.target[v[1]].y(), mesh.target[v[2]].y(), mesh.target[v[3]].y()});
        const double hi = std::max({mesh.target[v[0]].y(), mesh.target[v[1]].y(), mesh.target[v[2]].y(), mesh.target[v[3]].y()});
        if (hi < top || lo > bottom) continue;  // the common case: a cell above or below the band
        for (const TriangleShape& shape : kTriangles) {
          Eigen::Vector2d t[3], s[3], bend[3];
          bool ok = true, outline = false;
          for (int q = 0; q < 3 && ok; ++q) {
            const size_t at = mesh.at(i + shape.v[q][0], j + shape.v[q][1]);
            ok = mesh.valid[at] != 0;
            outline = outline || mesh.outside[at] != 0;
            t[q] = mesh.target[at];
            s[q] = mesh.sourceAt(i + shape.v[q][0], j + shape.v[q][1]).cwiseProduct(mesh.source_scale);
            bend[q] = bendOf(mesh, i, j, shape.bend[q]).cwiseProduct(mesh.source_scale);
          }
          if (ok && outline)
            rasterise(t, s, bend, y0, y1, width, sx2, sy2, valid2, avx512);
          else if (ok)
            covered += rasterise(t, s, bend, y0, y1, width, sx, sy, valid, avx512);
        }
      }
    }
  }
  return covered;
}

// The mesh a render of `camera` from a `source_image` photo into `size` output pixels draws:
// its step chosen (or given) as renderPiecewise documents. renderPiecewise and
// piecewisePositionMap both take it from here, so a map and a render can never draw different
// meshes.
Mesh meshFor(const PiecewiseCamera& camera, FrameSize source_image, FrameSize size,
             const PiecewiseRenderOptions& options, PiecewiseRenderStats& stats) {
  std::optional<Mesh> probe;
  const MeshChoice choice = chooseStep(camera, source_image, size, options, &probe);
  Mesh mesh = probe ? std::move(*probe) : buildMesh(camera, source_image, size, choice.step_px, options.threads);
  stats.mesh_step_px = choice.step_px;
  stats.error_px = choice.error_px;
  stats.triangles = static_cast<int>(std::min<long long>(mesh.triangles, std::numeric_limits<int>::max()));
  return mesh;
}


// The mesh rasterised in bands of kBandRows rows on the render's threads: each band's source
// positions and coverage in a scratch block (scratch.h), the same blocks band after band and
// render after render, not reallocated and page-faulted afresh by the threads parallelForRows
// starts; then `use(y0, y1, sx, sy, valid)` reads them. Returns the pixels the mesh covers. The
// render samples them, the position map stores them: one rasterisation for both.
template <class Use>
long long forEachRasterisedBand(const Mesh& mesh, FrameSize output, int threads, bool avx512,
                                const Use& use) {
  std::atomic<long long> covered{0};
  ParallelOptions po;
  po.threads = threads;
  po.band_rows = kBandRows;
  parallelForRows(output.height, po, [&](int y0, int y1) {
    const size_t cells = static_cast<size_t>(kBandRows) * static_cast<size_t>(output.width);
    const int sets = mesh.outlines ? 2 : 1;
    const ScratchBlock buffers = takeScratch(sets * cells * (2 * sizeof(float) + 1));
    float* const sx = static_cast<float*>(buffers.data());
    float* const sy = sx + cells;
    float* const sx2 = mesh.outlines ? sy + cells : nullptr;
    float* const sy2 = mesh.outlines ? sx2 + cells : nullptr;
    unsigned char* const valid = reinterpret_cast<unsigned char*>(sx + sets * 2 * cells);
    unsigned char* const valid2 = mesh.outlines ? valid + cells : nullptr;
    std::memset(valid, 0, sets * cells);
    long long band_covered =
        rasteriseBand(mesh, y0, y1, output.width, sx, sy, valid, sx2, sy2, valid2, avx512);
    // The outline triangles fill only what no inner triangle drew, cut at the outline.
    if (mesh.outlines)
      for (int y = y0; y < y1; ++y)
        for (int x = 0; x < output.width; ++x) {
          const size_t at = static_cast<size_t>(y - y0) * static_cast<size_t>(output.width) +
                            static_cast<size_t>(x);
          if (valid[at] || !valid2[at] || !keepOutlinePixel(mesh, x, y, sx2[at], sy2[at])) continue;
          sx[at] = sx2[at];
          sy[at] = sy2[at];
          valid[at] = 1;
          ++band_covered;
        }
    use(y0, y1, sx, sy, valid);
    covered += band_covered;
  });
  return covered.load();
}

}  // namespace

MeshChoice chooseMeshStep(const PiecewiseCamera& camera, FrameSize source_image, FrameSize output,
                          const PiecewiseRenderOptions& options) {
  if (camera.patches.empty() || !camera.target_size.isImage() || !camera.source_size.isImage()) return {};
  const FrameSize size = output.isImage() ? output : camera.target_size;
  return chooseStep(camera, source_image, size, options, nullptr);
}

void renderPiecewise(const ConstImageView& source, const PiecewiseCamera& camera, const ImageView& out,
                     const PiecewiseRenderOptions& options, PiecewiseRenderStats* stats_out) {
  if (source.empty()) throw std::invalid_argument("renderPiecewise: empty source image");
  if (!camera.target_size.isImage() || !camera.source_size.isImage())
    throw std::invalid_argument("renderPiecewise: the camera has no image frames");
  const SpanSampler sampler(source, out, options.filter, options.allow_simd, options.allow_avx512,
                            options.edge);  // validates both
  const bool avx512 = options.allow_avx512 && cpuHasAvx512bwvl();
  const FrameSize size{out.width, out.height};
  PiecewiseRenderStats stats;
  if (camera.patches.empty()) {
    for (int y = 0; y < out.height; ++y)
      std::memset(out.row(y), 0, static_cast<size_t>(out.width) * static_cast<size_t>(out.pixelBytes()));
    if (stats_out) *stats_out = stats;
    return;
  }
  const Mesh mesh = meshFor(camera, {source.width, source.height}, size, options, stats);
  // Every output pixel is written by the sampler (no position: transparent), so the output
  // needs no clearing first.
  stats.covered_pixels = forEachRasterisedBand(
      mesh, size, options.threads, avx512,
      [&](int y0, int y1, const float* sx, const float* sy, const unsigned char* valid) {
        // Span-major as the warp's tiles (warp.cpp): one span column down the band's rows, then
        // the next, so the source region a tile reads stays in cache; a whole 6000-pixel row
        // sweeps every source line its curve crosses.
        for (int x0 = 0; x0 < out.width; x0 += kSpanPixels) {  // the warp's spans (coordinates.h)
          const int n = std::min(kSpanPixels, out.width - x0);
          for (int y = y0; y < y1; ++y) {
            const size_t row = static_cast<size_t>(y - y0) * static_cast<size_t>(out.width);
            sampler.run(y, x0, n, sx + row + x0, sy + row + x0, valid + row + x0);
          }
        }
      });
  if (stats_out) *stats_out = stats;
}

PositionMap piecewisePositionMap(const PiecewiseCamera& camera, FrameSize source_image, FrameSize output,
                                 const PiecewiseRenderOptions& options, PiecewiseRenderStats* stats_out) {
  if (!camera.target_size.isImage() || !camera.source_size.isImage())
    throw std::invalid_argument("piecewisePositionMap: the camera has no image frames");
  PositionMap map = emptyPositionMap(source_image, output);  // checks the sizes
  map.kernel = "piecewise mesh";
  PiecewiseRenderStats stats;
  if (camera.patches.empty()) {
    if (stats_out) *stats_out = stats;
    return map;
  }
  const bool avx512 = options.allow_avx512 && cpuHasAvx512bwvl();
  const Mesh mesh = meshFor(camera, source_image, output, options, stats);
  // The render's bands and rasteriser (renderPiecewise), the positions stored instead of sampled.
  stats.covered_pixels = forEachRasterisedBand(
      mesh, output, options.threads, avx512,
      [&](int y0, int y1, const float* sx, const float* sy, const unsigned char* valid) {
        for (int y = y0; y < y1; ++y) {
          const size_t row = static_cast<size_t>(y - y0) * static_cast<size_t>(output.width);
          for (int x = 0; x < output.width; ++x)
            if (valid[row + static_cast<size_t>(x)])
              storePreimage(map, map.index(x, y), sx[row + static_cast<size_t>(x)],
                            sy[row + static_cast<size_t>(x)]);
        }
      });
  countPreimages(map);
  if (stats_out) *stats_out = stats;
  return map;
}

ImageF renderPiecewise(const ImageF& source, const PiecewiseCamera& camera,
                       const PiecewiseRenderOptions& options, PiecewiseRenderStats* stats_out) {
  if (source.empty()) throw std::invalid_argument("renderPiecewise: empty source image");
  if (!camera.target_size.isImage() || !camera.source_size.isImage())
    throw std::invalid_argument("renderPiecewise: the camera has no image frames");
  const int channels = source.alpha_channel >= 0 ? source.channels : source.channels + 1;
  const FrameSize size = options.output.isImage() ? options.output : camera.target_size;
  ImageF out(size.width, size.height, channels, channels - 1);
  renderPiecewise(viewOf(source), camera, viewOf(out), options, stats_out);
  return out;
}

void compositeOver(const ImageF& top, ImageF& bottom) {
  if (top.width != bottom.width || top.height != bottom.height || top.alpha_channel < 0)
    throw std::invalid_argument("compositeOver: sizes differ or the top image has no alpha");
  const int colour = top.channels - 1;
  const size_t n = static_cast<size_t>(top.width) * static_cast<size_t>(top.height);
  for (size_t k = 0; k < n; ++k) {
    const float* t = top.data.data() + k * static_cast<size_t>(top.channels);
    float* b = bottom.data.data() + k * static_cast<size_t>(bottom.channels);
    const float keep = 1.0f - std::clamp(t[top.alpha_channel], 0.0f, 1.0f);
    for (int c = 0; c < bottom.channels; ++c) {
      if (c == bottom.alpha_channel) {
        b[c] = t[top.alpha_channel] + keep * b[c];
      } else {
        const int tc = std::min(c, colour - 1);  // grey graphics over colour photos
        b[c] = t[tc] + keep * b[c];
      }
    }
  }
}

}  // namespace artcam
