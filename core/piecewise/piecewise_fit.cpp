// SPDX-License-Identifier: Apache-2.0
// Quadtree fitting of piecewise cameras; see piecewise_fit.h.
#include "core/piecewise/piecewise_fit.h"

#include "core/fit/poles.h"
#include "core/model/artcam.h"
#include "core/model/frames.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>

namespace artcam {
namespace {

struct Cell {
  PatchRect rect;
  int depth = 0;
};

struct PatchFit {
  Camera camera;
  std::string model;
};

std::vector<int> matchesIn(const std::vector<PointMatch>& matches, const PatchRect& rect,
                           double margin) {
  std::vector<int> out;
  for (size_t i = 0; i < matches.size(); ++i)
    if (rect.contains(matches[i].source.head<2>(), margin)) out.push_back(static_cast<int>(i));
  return out;
}

// The matches a cell is fitted on: those within the shared margin, the margin grown (up to
// the cell's own size) until there are enough to fit, so small cells on sparse data can still
// split instead of stopping above the threshold.
std::vector<int> sharedMatchesOf(const std::vector<PointMatch>& matches, const PatchRect& rect,
                                 const PiecewiseOptions& o) {
  const double size = std::max(rect.width(), rect.height());
  double margin = o.shared_margin * size;
  std::vector<int> ids = matchesIn(matches, rect, margin);
  while (static_cast<int>(ids.size()) < o.min_matches && margin < size) {
    margin = std::min(size, margin * 1.5 + 1e-9 * size);
    ids = matchesIn(matches, rect, margin);
  }
  return ids;
}

std::vector<PointMatch> subset(const std::vector<PointMatch>& matches, const std::vector<int>& ids) {
  std::vector<PointMatch> out;
  out.reserve(ids.size());
  for (int i : ids) out.push_back(matches[static_cast<size_t>(i)]);
  return out;
}

// The denominator keeps one sign over the patch's rectangle (poles.h, exact).
bool poleFreeOver(const Camera& camera, const PatchRect& rect) {
  const Eigen::Vector2d a = normalizedFromPixel(camera.sourceSize(), {rect.x0, rect.y0});
  const Eigen::Vector2d b = normalizedFromPixel(camera.sourceSize(), {rect.x1, rect.y1});
  const Eigen::Matrix3d q_n = camera.stages()[0].q[2];
  return checkDenominator(q_n, a.cwiseMin(b), a.cwiseMax(b)).pole_free;
}

// The richest requested model whose denominator stays away from the rectangle; falls back
// down the ladder to the homography and affine map, which cannot hide a pole inside a patch
// as easily (and the affine cannot at all).
std::optional<PatchFit> fitPatch(const std::vector<PointMatch>& shared, const PatchRect& rect,
                                 FrameSize source, FrameSize target, const PiecewiseOptions& o) {
  std::vector<ModelClass> ladder{o.model};
  for (ModelClass m : {ModelClass::Homography, ModelClass::Affine})
    if (m != o.model) ladder.push_back(m);
  for (ModelClass model : ladder) {
    if (static_cast<int>(shared.size()) < minimumMatches(model)) continue;
    FitOptions fo;
    fo.model = model;
    fo.refine = o.refine;
    fo.require_pole_free = false;  // checked over the patch below, not the whole frame
    fo.diagnostics = false;
    // A patch is small and nearly quadratic: LM converges from the DLT, and the quadtree
    // splits wherever it does not, so the polishing restarts would only multiply the cost.
    fo.restarts = 0;
    const FitSummary fit = fitImageCamera(shared, source, target, fo);
    if (!fit.status || !poleFreeOver(fit.camera, rect)) continue;
    return PatchFit{fit.camera, fit.record.model};
  }
  return std::nullopt;
}

double residual(const Camera& camera, const PointMatch& m) {
  const auto y = targetPixelFromSourcePixel(camera, m.source.head<2>());
  return y ? (*y - m.target.head<2>()).norm() : std::numeric_limits<double>::infinity();
}

// The held-out error of a cell (piecewise_fit.h): its own matches dealt into kFolds folds in
// order (a grid's rows then leave every fifth point out, spread over the cell), each predicted
// by the patch fitted on the shared matches without that fold. Infinite when a fold leaves too
// few matches for any pole-free fit: the patch cannot show what it does between its matches.
constexpr int kFolds = 5;
double heldOutMax(const std::vector<PointMatch>& matches, const std::vector<int>& own,
                  const std::vector<int>& shared, const PatchRect& rect, FrameSize source,
                  FrameSize target, const PiecewiseOptions& o) {
  double worst = 0.0;
  for (int fold = 0; fold < kFolds; ++fold) {
    std::vector<int> left_out;
    for (size_t k = static_cast<size_t>(fold); k < own.size(); k += kFolds) left_out.push_back(own[k]);
    if (left_out.empty()) continue;
    std::vector<PointMatch> train;
    for (int i : shared)
      if (!std::binary_search(left_out.begin(), left_out.end(), i))
        train.push_back(matches[static_cast<size_t>(i)]);
    const auto fit = fitPatch(train, rect, source, target, o);
    if (!fit) return std::numeric_limits<double>::infinity();
    for (int i : left_out) worst = std::max(worst, residual(fit->camera, matches[static_cast<size_t>(i)]));
  }
  return worst;
}

// The tiling's outer edges within `reach` of the frame's edges onto them, every rectangle
// clipped to the frame (piecewise_fit.h); patches clipped to nothing are dropped.
void snapToFrame(PiecewiseCamera& camera, double reach) {
  if (camera.patches.empty()) return;
  PatchRect hull = camera.patches.front().rect;
  for (const CameraPatch& p : camera.patches) {
    hull.x0 = std::min(hull.x0, p.rect.x0), hull.y0 = std::min(hull.y0, p.rect.y0);
    hull.x1 = std::max(hull.x1, p.rect.x1), hull.y1 = std::max(hull.y1, p.rect.y1);
  }
  const double w = camera.source_size.width, h = camera.source_size.height;
  const auto snap = [reach](double& edge, double outer, double frame_edge) {
    if (edge == outer && std::abs(edge - frame_edge) <= reach) edge = frame_edge;
  };
  std::vector<CameraPatch> kept;
  for (CameraPatch& p : camera.patches) {
    snap(p.rect.x0, hull.x0, 0.0), snap(p.rect.y0, hull.y0, 0.0);
    snap(p.rect.x1, hull.x1, w), snap(p.rect.y1, hull.y1, h);
    p.rect.x0 = std::max(p.rect.x0, 0.0), p.rect.y0 = std::max(p.rect.y0, 0.0);
    p.rect.x1 = std::min(p.rect.x1, w), p.rect.y1 = std::min(p.rect.y1, h);
    if (p.rect.x1 > p.rect.x0 && p.rect.y1 > p.rect.y0) kept.push_back(std::move(p));
  }
  camera.patches = std::move(kept);
}

// Four quadrants, or two halves across the longer side when quadrants would starve.
std::vector<PatchRect> splits(const PatchRect& r, bool quadrants) {
  const Eigen::Vector2d c = r.centre();
  if (quadrants)
    return {{r.x0, r.y0, c.x(), c.y()}, {c.x(), r.y0, r.x1, c.y()},
            {r.x0, c.y(), c.x(), r.y1}, {c.x(), c.y(), r.x1, r.y1}};
  if (r.width() >= r.height()) return {{r.x0, r.y0, c.x(), r.y1}, {c.x(), r.y0, r.x1, r.y1}};
  return {{r.x0, r.y0, r.x1, c.y()}, {r.x0, c.y(), r.x1, r.y1}};
}

// Median distance from a match to its nearest neighbour (source pixels), on up to 400 of them:
// how far apart the user's grid points are, so how far a patch's hull may be grown.
double matchSpacing(const std::vector<PointMatch>& matches) {
  const size_t n = matches.size();
  const size_t stride = std::max<size_t>(1, n / 400);
  std::vector<double> nearest;
  for (size_t i = 0; i < n; i += stride) {
    double best = std::numeric_limits<double>::infinity();
    for (size_t j = 0; j < n; ++j)
      if (j != i) {
        const double d = (matches[i].source.head<2>() - matches[j].source.head<2>()).norm();
        if (d > 0.0) best = std::min(best, d);
      }
    if (std::isfinite(best)) nearest.push_back(best);
  }
  if (nearest.empty()) return 0.0;
  std::nth_element(nearest.begin(), nearest.begin() + nearest.size() / 2, nearest.end());
  return nearest[nearest.size() / 2];
}

// Four quadrants, or else two halves, when every child that holds data can still be fitted on
// its shared matches; empty when the cell cannot be split.
std::optional<std::vector<PatchRect>> feasibleSplit(const std::vector<PointMatch>& matches,
                                                    const PatchRect& rect,
                                                    const PiecewiseOptions& options) {
  for (bool quadrants : {true, false}) {
    bool feasible = true;
    int children_with_data = 0;
    std::vector<PatchRect> kids = splits(rect, quadrants);
    for (const PatchRect& k : kids) {
      if (matchesIn(matches, k, 0.0).empty()) continue;
      ++children_with_data;
      if (static_cast<int>(sharedMatchesOf(matches, k, options).size()) < options.min_matches)
        feasible = false;
    }
    if (feasible && children_with_data > 0) return kids;
  }
  return std::nullopt;
}

struct Quadtree {
  const std::vector<PointMatch>& matches;
  FrameSize source, target;
  const PiecewiseOptions& options;
};

// A cell's patches; `worst` is the largest error of any of them, at or between its matches.
struct CellFit {
  Status status = Status::success();
  std::vector<CameraPatch> patches;
  double worst = 0.0;
};

// One cell of the quadtree: its patch when that meets the threshold at and between its
// matches, else its children's patches. A split forced by the error AT the matches is kept, as
// before; one asked for only by the held-out error is kept when the children are better between
// their matches than the cell was, since children fitted on fewer matches can bend more, not
// less (a sparse grid), and then the cell stays one patch, reported above the threshold.
CellFit fitCell(const Quadtree& q, const Cell& cell) {
  CellFit out;
  const std::vector<PointMatch>& matches = q.matches;
  const PiecewiseOptions& options = q.options;
  // Matches on an edge belong to both sides (the split point is computed, so allow round-off).
  const double edge_tolerance = 1e-9 * std::max(cell.rect.width(), cell.rect.height());
  const std::vector<int> own = matchesIn(matches, cell.rect, edge_tolerance);
  if (own.empty()) return out;  // no data: nothing to answer for here
  const std::vector<int> shared_ids = sharedMatchesOf(matches, cell.rect, options);
  const std::vector<PointMatch> shared = subset(matches, shared_ids);
  const auto fit = fitPatch(shared, cell.rect, q.source, q.target, options);

  double worst = std::numeric_limits<double>::infinity(), sum2 = 0.0;
  double held_out = std::numeric_limits<double>::infinity();
  if (fit) {
    worst = 0.0;
    for (int i : own) {
      const double r = residual(fit->camera, matches[static_cast<size_t>(i)]);
      worst = std::max(worst, r);
      sum2 += r * r;
    }
    // Only a patch good at its matches is worth the five extra fits.
    if (worst <= options.max_error_px)
      held_out = heldOutMax(matches, own, shared_ids, cell.rect, q.source, q.target, options);
  }
  const bool at_matches = fit && worst <= options.max_error_px;
  const bool good = at_matches && held_out <= options.max_error_px;
  const double error = std::max(worst, held_out);
  if (!good && cell.depth < options.max_depth) {
    if (const auto kids = feasibleSplit(matches, cell.rect, options)) {
      CellFit split;
      for (const PatchRect& k : *kids) {
        CellFit child = fitCell(q, {k, cell.depth + 1});
        if (!child.status) {
          split.status = child.status;
          break;
        }
        split.worst = std::max(split.worst, child.worst);
        for (CameraPatch& p : child.patches) split.patches.push_back(std::move(p));
      }
      if (!fit || (!at_matches && split.status) || (split.status && split.worst < error))
        return split;
    }
  }
  if (!fit) {
    out.status = Status::failure(
        "no pole-free camera fits the patch [" + std::to_string(cell.rect.x0) + ", " +
        std::to_string(cell.rect.y0) + "]–[" + std::to_string(cell.rect.x1) + ", " +
        std::to_string(cell.rect.y1) + "] and it cannot be split further (" +
        std::to_string(shared.size()) + " matches); add matches there");
    return out;
  }
  CameraPatch patch;
  patch.rect = cell.rect;
  patch.camera = fit->camera;
  patch.model = fit->model;
  patch.matches = static_cast<int>(own.size());
  patch.max_px = worst;
  patch.held_out_max_px = held_out;
  patch.rms_px = std::sqrt(sum2 / static_cast<double>(own.size()));
  patch.within_tolerance = good;
  std::vector<Eigen::Vector2d> own_points;
  for (int i : own) own_points.push_back(matches[static_cast<size_t>(i)].source.head<2>());
  patch.support = convexHull(std::move(own_points));
  out.worst = error;
  out.patches.push_back(std::move(patch));
  return out;
}

}  // namespace

std::string patchLimitNote(int depth) {
  return "; the tree stops at depth " + std::to_string(depth) +
         ": splitting further would need more than the " + std::to_string(kMaxPatches) +
         " patches a camera holds";
}

std::string PiecewiseSummary::report() const {
  char line[600];
  std::snprintf(
      line, sizeof line,
      "piecewise: %zu patches, %d matches, RMS %.4g px, max %.4g px, held-out max %.4g px, "
      "seam gap %.3g px%s%s\n"
      "single camera on the same matches: %s",
      camera.patches.size(), matches, rms_px, max_px, held_out_max_px, seam_gap_px,
      converged ? "" : " (some patches could not reach the threshold)",
      patch_limited_depth < 0 ? "" : patchLimitNote(patch_limited_depth).c_str(),
      single_rms_px < 0 ? "no fit"
                        : (std::to_string(single_rms_px) + " px RMS, " +
                           std::to_string(single_max_px) + " px max")
                              .c_str());
  return line;
}

double measureSeamGap(const PiecewiseCamera& camera, int samples_per_edge) {
  double worst = 0.0;
  const auto& p = camera.patches;
  for (size_t a = 0; a < p.size(); ++a)
    for (size_t b = a + 1; b < p.size(); ++b) {
      const PatchRect& r = p[a].rect;
      const PatchRect& s = p[b].rect;
      // The shared segment of two touching rectangles (vertical or horizontal edge).
      Eigen::Vector2d from, to;
      const double lo_y = std::max(r.y0, s.y0), hi_y = std::min(r.y1, s.y1);
      const double lo_x = std::max(r.x0, s.x0), hi_x = std::min(r.x1, s.x1);
      if ((r.x1 == s.x0 || s.x1 == r.x0) && hi_y > lo_y) {
        const double x = r.x1 == s.x0 ? r.x1 : r.x0;
        from = {x, lo_y};
        to = {x, hi_y};
      } else if ((r.y1 == s.y0 || s.y1 == r.y0) && hi_x > lo_x) {
        const double y = r.y1 == s.y0 ? r.y1 : r.y0;
        from = {lo_x, y};
        to = {hi_x, y};
      } else {
        continue;
      }
      for (int k = 0; k < samples_per_edge; ++k) {
        const Eigen::Vector2d q = from + (to - from) * (k / double(samples_per_edge - 1));
        if (!camera.supports(static_cast<int>(a), q) || !camera.supports(static_cast<int>(b), q))
          continue;
        // Edges are in the patch frame, the cameras read source pixels (piecewise_camera.h).
        const auto source = camera.sourcePixelFromPatchPixel(q);
        if (!source) continue;
        const auto ya = targetPixelFromSourcePixel(p[a].camera, *source);
        const auto yb = targetPixelFromSourcePixel(p[b].camera, *source);
        if (ya && yb) worst = std::max(worst, (*ya - *yb).norm());
      }
    }
  return worst;
}

PiecewiseSummary fitPiecewise(const std::vector<PointMatch>& all_matches, FrameSize source_size,
                              FrameSize target_size, const PiecewiseOptions& options) {
  PiecewiseSummary out;
  out.camera.source_size = source_size;
  out.camera.target_size = target_size;
  std::vector<PointMatch> matches;
  for (const PointMatch& m : all_matches) {
    if (!m.enabled) continue;
    if (m.source.size() != 2 || m.target.size() != 2)
      return out.status = Status::failure("piecewise fitting needs 2D image matches"), out;
    if (!m.source.allFinite() || !m.target.allFinite())
      return out.status = Status::failure("a match has a non-finite coordinate"), out;
    const double slack = options.outside_frame_px;
    if (m.source[0] < -slack || m.source[1] < -slack || m.source[0] > source_size.width + slack ||
        m.source[1] > source_size.height + slack) {
      char text[200];
      std::snprintf(text, sizeof text,
                    "match %zu: its source (%.6g, %.6g) lies outside the %dx%d source frame; "
                    "patches tile the source frame (give a size that holds every match)",
                    static_cast<size_t>(&m - all_matches.data()) + 1, m.source[0], m.source[1],
                    source_size.width, source_size.height);
      return out.status = Status::failure(text), out;
    }
    matches.push_back(m);
  }
  out.matches = static_cast<int>(matches.size());
  if (out.matches < options.min_matches)
    return out.status = Status::failure(
               "a piecewise fit needs at least " + std::to_string(options.min_matches) +
               " matches; have " + std::to_string(out.matches)),
           out;

  {  // The single-camera floor, for comparison.
    FitOptions fo;
    fo.model = ModelClass::Quadratic;
    fo.diagnostics = false;
    fo.require_pole_free = false;
    fo.restarts = 0;
    const FitSummary single = fitImageCamera(matches, source_size, target_size, fo);
    if (single.status) {
      out.single_rms_px = single.record.rms_px;
      out.single_max_px = single.record.max_px;
    }
  }

  PatchRect root{std::numeric_limits<double>::max(), std::numeric_limits<double>::max(),
                 std::numeric_limits<double>::lowest(), std::numeric_limits<double>::lowest()};
  for (const PointMatch& m : matches) {
    root.x0 = std::min(root.x0, m.source[0]);
    root.y0 = std::min(root.y0, m.source[1]);
    root.x1 = std::max(root.x1, m.source[0]);
    root.y1 = std::max(root.y1, m.source[1]);
  }

  // 1.5 spacings: a grid cell's diagonal (√2) plus room for a corner the user did not click.
  out.camera.support_margin_px = 1.5 * matchSpacing(matches);
  // A camera holds at most kMaxPatches (validateArtcam). Where the threshold cannot be met (a
  // circular fisheye's rim) cells split to the deepest level and a full tree has 4^depth
  // leaves: the tree is then grown again one level shallower, until it fits (4^5 = 1024 always
  // does), so the fit returns a camera the writer takes, with the patches that miss the
  // threshold reported, instead of one no file can hold.
  PiecewiseOptions tree_options = options;
  CellFit all;
  for (;;) {
    const Quadtree tree{matches, source_size, target_size, tree_options};
    all = fitCell(tree, {root, 0});
    if (!all.status) return out.status = all.status, out;
    if (all.patches.size() <= static_cast<size_t>(kMaxPatches) || tree_options.max_depth == 0)
      break;
    out.patch_limited_depth = --tree_options.max_depth;
  }
  if (all.patches.size() > static_cast<size_t>(kMaxPatches))
    return out.status = Status::failure("more patches than the " + std::to_string(kMaxPatches) +
                                        " a camera may hold"),
           out;
  out.camera.patches = std::move(all.patches);
  for (const CameraPatch& p : out.camera.patches) {
    out.converged = out.converged && p.within_tolerance;
    out.held_out_max_px = std::max(
        out.held_out_max_px, std::isfinite(p.held_out_max_px) && p.held_out_max_px >= 0 ? p.held_out_max_px : p.max_px);
  }
  snapToFrame(out.camera, options.snap_to_frame_px >= 0 ? options.snap_to_frame_px
                                                         : out.camera.support_margin_px);

  double sum2 = 0.0;
  for (const PointMatch& m : matches) {
    const auto y = out.camera.targetPixelFromSourcePixel(m.source.head<2>());
    const double r = y ? (*y - m.target.head<2>()).norm() : std::numeric_limits<double>::infinity();
    out.max_px = std::max(out.max_px, r);
    sum2 += r * r;
  }
  out.rms_px = std::sqrt(sum2 / static_cast<double>(matches.size()));
  out.seam_gap_px = measureSeamGap(out.camera);
  out.status = Status::success();
  return out;
}

}  // namespace artcam
