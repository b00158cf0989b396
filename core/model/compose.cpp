// SPDX-License-Identifier: Apache-2.0
// Composition of cameras; see compose.h for the three outcomes and why.
#include "core/model/compose.h"

#include "core/model/frames.h"
#include "core/model/structure.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

namespace artcam {
namespace {

bool isPositionOnly(const Camera& camera) {
  return camera.blocks().size() == 1 && camera.blocks()[0].kind == BlockKind::Position;
}

// A single-stage position-only camera whose geometry is at most a homography: its column-form
// target_from_source matrix in the normalised frames.
std::optional<Eigen::MatrixXd> homographyOf(const Camera& camera) {
  if (!isPositionOnly(camera) || camera.stages().size() != 1) return std::nullopt;
  const CameraStructure s = analyseStructure(camera);
  if (s.degenerate || s.geometry == GeometryClass::Rational || s.homography.size() == 0)
    return std::nullopt;
  return s.homography;
}

std::string sizeText(FrameSize s) { return std::to_string(s.width) + "x" + std::to_string(s.height); }

// Pixels of `from` scaled per axis onto pixels of `to`, column form: what a renderer does to a
// camera applied to a photo of another size (core/pipeline/render.h, outputFrameFor).
Eigen::Matrix3d pixelScale(FrameSize from, FrameSize to) {
  Eigen::Matrix3d m = Eigen::Matrix3d::Identity();
  m(0, 0) = static_cast<double>(to.width) / from.width;
  m(1, 1) = static_cast<double>(to.height) / from.height;
  return m;
}

// Whether two image frames have one shape: the height one would have at the other's width is
// within a rounding pixel (outputFrameFor's test for a photo of another aspect).
bool sameShape(FrameSize a, FrameSize b) {
  return std::abs(a.height - static_cast<double>(b.height) * a.width / b.width) <= 1.0;
}

// How first's target frame meets second's source frame (docs/architecture.md, "Composition").
// Equal frames meet as they are. Frames of one shape and another size meet as `warp` would
// apply second to first's output: second's frames scaled by first.target / second.source per
// axis, which is exact (an affine change of the position block on either side), and reported.
// Frames of different shapes are refused: meeting them would stretch the picture per axis or
// crop it, and the composed camera would hide that.
struct FrameMeeting {
  Status status = Status::success();
  Eigen::MatrixXd bridge;            // first's target normalised frame → second's source one
  FrameSize target;                  // the composed camera's target frame
  Eigen::Matrix3d target_change = Eigen::Matrix3d::Identity();  // second's target normalised → target's
  std::string note;                  // non-empty when rescaled
};

FrameMeeting meetFrames(const Camera& first, const Camera& second) {
  FrameMeeting m;
  const int k = first.blocks()[static_cast<size_t>(first.layout().find(BlockKind::Position))].size;
  m.bridge = Eigen::MatrixXd::Identity(k, k);
  m.target = second.targetSize();
  const FrameSize a = first.targetSize(), b = second.sourceSize();
  if (k != 3 || a == b || !a.isImage()) return m;
  if (!sameShape(a, b)) {
    m.status = Status::failure(
        "the first camera's target frame is " + sizeText(a) + " but the second camera was made for " +
        sizeText(b) + " (another shape): composed, the picture would be stretched or cropped; make "
        "the second camera at " + sizeText(a) + " (e.g. `artcam preset … --size " + sizeText(a) +
        "`) or fit it on the first camera's output");
    return m;
  }
  m.bridge = normalizedFromPixelMatrix(b) * pixelScale(a, b) * pixelFromNormalizedMatrix(a);
  const FrameSize t = second.targetSize();
  if (t.isImage()) {
    m.target = {std::max(1, static_cast<int>(std::lround(t.width * static_cast<double>(a.width) / b.width))),
                std::max(1, static_cast<int>(std::lround(t.height * static_cast<double>(a.height) / b.height)))};
    m.target_change = normalizedFromPixelMatrix(m.target) * pixelScale(t, m.target) * pixelFromNormalizedMatrix(t);
  }
  char scale[32];
  std::snprintf(scale, sizeof scale, "%.4g", static_cast<double>(a.width) / b.width);
  m.note = "; the second camera, made for " + sizeText(b) + ", is applied at the first's " + sizeText(a) +
           " target frame (scaled x" + scale + ", as warp applies a camera to a photo of another size)" +
           (t.isImage() ? ": target frame " + sizeText(m.target) : std::string());
  return m;
}

// Position-only tensors are defined up to one common scale; keep entries near 1 so chained
// homographies do not drift towards overflow. (With colour blocks the scale is alpha, so
// those cameras are left as they are.)
void rescalePositionOnly(Camera& camera) {
  if (!isPositionOnly(camera)) return;
  for (Stage& stage : camera.stages()) {
    double largest = 0.0;
    for (const Eigen::MatrixXd& q : stage.q) largest = std::max(largest, q.cwiseAbs().maxCoeff());
    if (largest > 0.0 && std::isfinite(largest))
      for (Eigen::MatrixXd& q : stage.q) q /= largest;
  }
}

}  // namespace

Result<Camera> composeCameras(const Camera& first, const Camera& second,
                              CompositionSummary* summary) {
  if (first.blocks() != second.blocks())
    return Result<Camera>::failure(
        "the two cameras have different blocks; compose needs the same blocks on both");
  const int position = first.layout().find(BlockKind::Position);
  if (position < 0)
    return Result<Camera>::failure("compose needs cameras with a position block");
  if (first.targetSize().isImage() != second.sourceSize().isImage())
    return Result<Camera>::failure(
        "the first camera's target frame (" + std::to_string(first.targetSize().width) + "x" +
        std::to_string(first.targetSize().height) + ") and the second's source frame (" +
        std::to_string(second.sourceSize().width) + "x" +
        std::to_string(second.sourceSize().height) +
        ") are not both images or both object space");

  const FrameMeeting meeting = meetFrames(first, second);
  if (!meeting.status) return Result<Camera>::failure(meeting.status.message);
  const Eigen::MatrixXd& bridge = meeting.bridge;
  CompositionSummary local;
  Camera out;

  if (const auto a = homographyOf(second)) {
    // Output side: second's homography after the bridge mixes first's outputs.
    out = first;
    changeOutputFrame(out, position, (*a) * bridge);
    local.kind = CompositionKind::OutputHomography;
    local.description = "the second camera is a homography: folded into the first's outputs";
  } else if (const auto h = homographyOf(first)) {
    // Input side: x2 = (bridge · H) x1 in column form, so x2_row = x1_row (bridge · H)ᵀ.
    // homographyOf() admits position-only cameras, and the blocks match, so every output of
    // second is a form in position alone and H's change of homogeneous weight cancels (eq 5).
    out = second;
    changeInputFrame(out, position, (bridge * (*h)).transpose());
    local.kind = CompositionKind::InputHomography;
    local.description = "the first camera is a homography: folded into the second's inputs";
  } else {
    Camera tail = second;
    if (!bridge.isIdentity(0.0)) changeInputFrame(tail, position, bridge.transpose());
    std::vector<Stage> stages = first.stages();
    for (const Stage& s : tail.stages()) stages.push_back(s);
    out = Camera(first.blocks(), std::move(stages), first.sourceSize(), second.targetSize());
    local.kind = CompositionKind::Chain;
    local.description = "general cameras: a chain of " + std::to_string(out.stages().size()) +
                        " stages (first's, then second's)";
  }
  if (!meeting.target_change.isIdentity(0.0)) changeOutputFrame(out, position, meeting.target_change);
  out.setFrames(first.sourceSize(), meeting.target);
  local.description += meeting.note;
  rescalePositionOnly(out);
  out.validate();
  local.stages = static_cast<int>(out.stages().size());
  if (summary) *summary = std::move(local);
  return Result<Camera>::success(std::move(out));
}

}  // namespace artcam

namespace artcam {
namespace {

// Evaluates `camera` at the source frame centre with a mid-grey opaque colour and depth d.
Eigen::VectorXd probe(const Camera& camera, double d) {
  const BlockLayout& layout = camera.layout();
  Eigen::VectorXd x = Eigen::VectorXd::Zero(layout.dimension);
  for (size_t b = 0; b < layout.blocks.size(); ++b) {
    const int o = layout.offsets[b];
    const Block& block = layout.blocks[b];
    if (block.kind == BlockKind::Position) {
      x(o + block.size - 1) = 1.0;
      for (int k = 0; k + 1 < block.size; ++k) x(o + k) = 0.1 * (k + 1);
    } else if (weightIsAlpha(block.kind)) {
      for (int k = 0; k + 1 < block.size; ++k) x(o + k) = 0.5;
      x(o + block.size - 1) = 1.0;
    } else {
      x(o) = d;
      x(o + 1) = 1.0;
    }
  }
  return camera.evaluate(x);
}

const double kProbeDepths[] = {0.7, 2.0, 9.0, 40.0};

// The depth output differs from the depth input.
bool changesDepth(const Camera& camera) {
  const int b = camera.layout().find(BlockKind::Depth);
  if (b < 0) return false;
  const int o = camera.layout().offsets[static_cast<size_t>(b)];
  for (const double d : kProbeDepths) {
    const Eigen::VectorXd y = probe(camera, d);
    if (!(std::abs(y(o) - d) <= 1e-9 * std::max(1.0, d))) return true;
  }
  return false;
}

// Some output depends on the depth input (beyond passing it on unchanged).
bool readsDepth(const Camera& camera) {
  if (camera.layout().find(BlockKind::Depth) < 0) return false;
  if (changesDepth(camera)) return true;
  const int b = camera.layout().find(BlockKind::Depth);
  const int o = camera.layout().offsets[static_cast<size_t>(b)];
  const Eigen::VectorXd reference = probe(camera, kProbeDepths[0]);
  for (const double d : kProbeDepths) {
    Eigen::VectorXd y = probe(camera, d);
    y(o) = reference(o);
    if (!((y - reference).cwiseAbs().maxCoeff() <= 1e-9)) return true;
  }
  return false;
}

// `camera` written over `blocks`, which hold each of its blocks (same kind and size): its tensors
// embedded where its blocks are, every other element passed on (x_i · x_unit, as
// Camera::identity does).
Camera liftToBlocks(const Camera& camera, const std::vector<Block>& blocks) {
  const BlockLayout layout(blocks);
  const BlockLayout& own = camera.layout();
  std::vector<int> at(static_cast<size_t>(own.dimension));  // own element → wide element
  for (size_t b = 0; b < own.blocks.size(); ++b) {
    const int w = layout.find(own.blocks[b].kind);
    for (int k = 0; k < own.blocks[b].size; ++k)
      at[static_cast<size_t>(own.offsets[b] + k)] = layout.offsets[static_cast<size_t>(w)] + k;
  }
  std::vector<bool> mine(static_cast<size_t>(layout.dimension), false);
  for (int i : at) mine[static_cast<size_t>(i)] = true;
  std::vector<Stage> stages;
  for (const Stage& stage : camera.stages()) {
    Stage lifted;
    lifted.q.assign(static_cast<size_t>(layout.dimension), Eigen::MatrixXd());
    for (int i = 0; i < layout.dimension; ++i)
      if (!mine[static_cast<size_t>(i)])
        lifted.q[static_cast<size_t>(i)] =
            symmetricOuter(Eigen::VectorXd::Unit(layout.dimension, i),
                           Eigen::VectorXd::Unit(layout.dimension, layout.unitIndex()));
    for (int i = 0; i < own.dimension; ++i) {
      Eigen::MatrixXd q = Eigen::MatrixXd::Zero(layout.dimension, layout.dimension);
      const Eigen::MatrixXd& o = stage.q[static_cast<size_t>(i)];
      for (int r = 0; r < own.dimension; ++r)
        for (int c = 0; c < own.dimension; ++c) q(at[size_t(r)], at[size_t(c)]) = o(r, c);
      lifted.q[static_cast<size_t>(at[static_cast<size_t>(i)])] = std::move(q);
    }
    stages.push_back(std::move(lifted));
  }
  return Camera(blocks, std::move(stages), camera.sourceSize(), camera.targetSize());
}

// Every block of `narrow` is in `wide` (same kind and size), in the same order.
bool blocksWithin(const std::vector<Block>& narrow, const std::vector<Block>& wide) {
  size_t w = 0;
  for (const Block& b : narrow) {
    while (w < wide.size() && wide[w] != b) ++w;
    if (w == wide.size()) return false;
    ++w;
  }
  return true;
}

// Brings the side whose blocks the other holds to the other's blocks, so a lens composes with
// a camera that carries colour or depth, and a colour camera with one that carries shading. The
// lifted side passes the blocks it lacks on unchanged, which is what it did to them.
std::pair<Camera, Camera> commonBlocks(const Camera& a, const Camera& b) {
  if (a.blocks() == b.blocks()) return {a, b};
  const int pa = a.layout().find(BlockKind::Position), pb = b.layout().find(BlockKind::Position);
  if (pa < 0 || pb < 0 || a.blocks()[size_t(pa)] != b.blocks()[size_t(pb)]) return {a, b};
  if (blocksWithin(a.blocks(), b.blocks())) return {liftToBlocks(a, b.blocks()), b};
  if (blocksWithin(b.blocks(), a.blocks())) return {a, liftToBlocks(b, a.blocks())};
  return {a, b};
}


// Where b reads depth only in its depth output, in one stage, from the depth block alone (depth
// of field's σ² = h(d)), that output can be re-expressed on another variable.
bool depthOutputReadsDepthAlone(const Camera& b) {
  const int block = b.layout().find(BlockKind::Depth);
  if (block < 0 || b.stages().size() != 1) return false;
  const int o = b.layout().offsets[static_cast<size_t>(block)];
  const auto& q = b.stages()[0].q;
  for (int i = 0; i < b.dimension(); ++i) {
    const Eigen::MatrixXd& m = q[static_cast<size_t>(i)];
    for (int r = 0; r < b.dimension(); ++r)
      for (int c = 0; c < b.dimension(); ++c) {
        const bool depth_entry = r >= o && r <= o + 1 && c >= o && c <= o + 1;
        const bool depth_output = i == o || i == o + 1;
        if (m(r, c) != 0.0 && depth_output != depth_entry) return false;
      }
  }
  return true;
}

double depthOut(const Camera& camera, double d) {
  const int block = camera.layout().find(BlockKind::Depth);
  return probe(camera, d)(camera.layout().offsets[static_cast<size_t>(block)]);
}

// A depth output l = g(d) normalised as aerial perspective's is (g = 0 at its near depth, 1 at
// its far depth, increasing between), found by scanning depths from 1e-4 to 1e6 and bisecting.
std::optional<std::pair<double, double>> unitInterval(const Camera& a) {
  constexpr int kSamples = 4001;
  std::optional<double> near, far;
  double previous_d = 0, previous_g = std::numeric_limits<double>::quiet_NaN();
  for (int j = 0; j < kSamples && !far; ++j) {
    const double d = std::pow(10.0, -4.0 + 10.0 * j / (kSamples - 1));
    const double g = depthOut(a, d);
    if (!std::isfinite(g)) {
      near.reset();
    } else if (std::isfinite(previous_g)) {
      if (!near && previous_g < 0.0 && g >= 0.0) near = previous_d;
      if (near && g < previous_g) near.reset();  // not increasing: start again
      if (near && previous_g < 1.0 && g >= 1.0) far = d;
    }
    previous_d = d;
    previous_g = g;
  }
  if (!near || !far) return std::nullopt;
  return std::make_pair(*near, *far);
}

// g⁻¹(l) on [lo, hi] by bisection (g increasing there).
double inverseDepth(const Camera& a, double l, double lo, double hi) {
  for (int k = 0; k < 80; ++k) {
    const double mid = std::sqrt(lo * hi);
    (depthOut(a, mid) < l ? lo : hi) = mid;
  }
  return std::sqrt(lo * hi);
}

// A ratio of quadratics on (l, 1): N(l)/D(l), each a 2×2 symmetric tensor.
struct DepthRatio {
  Eigen::Matrix2d numerator, denominator;
  double value(double l) const {
    const Eigen::Vector2d v(l, 1.0);
    return v.dot(numerator * v) / v.dot(denominator * v);
  }
};

// N/D ≈ y on the samples: linearised least squares re-weighted by the denominator
// (Sanathanan–Koerner), as aerial perspective fits its log depth, each row also weighted by how
// much an error in y matters (`importance`: the slope of what is computed from y); D normalised
// by its constant term. Empty when the denominator vanishes on a sample.
std::optional<DepthRatio> fitRatio(const std::vector<double>& ls, const std::vector<double>& ys,
                                   const std::vector<double>& importance) {
  const int n = static_cast<int>(ls.size());
  Eigen::VectorXd x = Eigen::VectorXd::Zero(5);  // n2, n1, n0, e2, e1 (e0 = 1)
  std::vector<double> weight(ls.size(), 1.0);
  for (int iteration = 0; iteration < 8; ++iteration) {
    Eigen::MatrixXd m(n, 5);
    Eigen::VectorXd rhs(n);
    for (int k = 0; k < n; ++k) {
      const double l = ls[size_t(k)], y = ys[size_t(k)];
      const double w = weight[size_t(k)] * importance[size_t(k)];
      m.row(k) << w * l * l, w * l, w, -w * y * l * l, -w * y * l;
      rhs(k) = w * y;
    }
    x = m.colPivHouseholderQr().solve(rhs);
    for (int k = 0; k < n; ++k) {
      const double l = ls[size_t(k)];
      const double den = x(3) * l * l + x(4) * l + 1.0;
      if (!(std::abs(den) > 1e-12)) return std::nullopt;
      weight[size_t(k)] = 1.0 / std::abs(den);
    }
  }
  DepthRatio r;
  r.numerator << x(0), x(1) / 2, x(1) / 2, x(2);
  r.denominator << x(3), x(4) / 2, x(4) / 2, 1.0;
  return r;
}

// The bridge from first's depth output l = g(d) back to a variable second can read exactly: the
// depth d = g⁻¹(l) or the inverse depth m = 1/g⁻¹(l), fitted as a ratio of quadratics in (l, 1)
// over [0, 1]; whichever gives second's output the smaller error. Second's depth output, a ratio
// of quadratics in (d, 1), is one in (m, 1) too (d = 1/m: the tensors' d·d and 1·1 entries swap
// and the common 1/m² cancels), so the fit is the only approximation. The depth of field's thin
// lens is polynomial in m, its linear model in d.
struct DepthBridge {
  DepthRatio ratio;     // l → the bridged variable
  bool inverse = true;  // the variable is the inverse depth m (else the depth d itself)
  double max_error = 0;  // of second's depth output through the bridge, over l in [0, 1]
  double scale = 0;      // the largest |second's depth output| there
};

// The depth block's two tensors of `stage` as they act on (m, 1) instead of (d, 1).
void onInverseDepth(Stage& stage, int o) {
  for (Eigen::MatrixXd& q : stage.q) {
    std::swap(q(o, o), q(o + 1, o + 1));
  }
}

std::optional<DepthBridge> bridgeDepth(const Camera& a, const Camera& b) {
  const auto interval = unitInterval(a);
  if (!interval) return std::nullopt;
  const auto depth_at = [&](double l) { return inverseDepth(a, l, interval->first, interval->second); };
  constexpr int kFit = 129, kCheck = 1001;
  std::vector<double> ls, ds, ms;
  for (int k = 0; k < kFit; ++k) {
    ls.push_back(static_cast<double>(k) / (kFit - 1));
    ds.push_back(depth_at(ls.back()));
    ms.push_back(1.0 / ds.back());
  }
  std::optional<DepthBridge> best;
  for (const bool inverse : {true, false}) {
    // Errors of the bridged variable weighted by the slope of second's output there, so the fit
    // minimises (to first order) the error of that output; a floor keeps flat parts fitted.
    const std::vector<double>& vs = inverse ? ms : ds;
    std::vector<double> slope(vs.size());
    double steepest = 0;
    for (size_t k = 0; k < vs.size(); ++k) {
      const double v = vs[k], step = 1e-6 * std::abs(v);
      const auto out = [&](double x) { return depthOut(b, inverse ? 1.0 / x : x); };
      slope[k] = std::abs(out(v + step) - out(v - step)) / (2 * step);
      steepest = std::max(steepest, slope[k]);
    }
    for (double& w : slope) w = std::max(w, 1e-3 * steepest);
    const std::optional<DepthRatio> fit = fitRatio(ls, vs, slope);
    if (!fit) continue;
    DepthBridge bridge{*fit, inverse, 0.0, 0.0};
    bool pole = false;
    for (int k = 0; k < kCheck && !pole; ++k) {
      const double l = static_cast<double>(k) / (kCheck - 1);
      const Eigen::Vector2d v(l, 1.0);
      const double value = fit->value(l);
      pole = !(v.dot(fit->denominator * v) > 0.0) || !(value > 0.0);
      const double exact = depthOut(b, depth_at(l));
      const double through = depthOut(b, inverse ? 1.0 / value : value);
      bridge.max_error = std::max(bridge.max_error, std::abs(through - exact));
      bridge.scale = std::max(bridge.scale, std::abs(exact));
    }
    if (!pole && (!best || bridge.max_error < best->max_error)) best = bridge;
  }
  return best;
}

// first, then the bridge stage (depth l → m, everything else passed on), then second with its
// depth output read on (m, 1).
Result<Camera> composeThroughBridge(const Camera& a, const Camera& b, const DepthBridge& bridge,
                                    CompositionSummary* summary) {
  Camera stage = Camera::identity(a.blocks(), a.targetSize(), a.targetSize());
  const int o = a.layout().offsets[static_cast<size_t>(a.layout().find(BlockKind::Depth))];
  Eigen::MatrixXd& num = stage.stages()[0].q[static_cast<size_t>(o)];
  Eigen::MatrixXd& den = stage.stages()[0].q[static_cast<size_t>(o + 1)];
  num.setZero();
  den.setZero();
  num.block(o, o, 2, 2) = bridge.ratio.numerator;
  den.block(o, o, 2, 2) = bridge.ratio.denominator;
  Camera second = b;
  const int ob = b.layout().offsets[static_cast<size_t>(b.layout().find(BlockKind::Depth))];
  if (bridge.inverse) onInverseDepth(second.stages()[0], ob);
  auto first_and_bridge = composeCameras(a, stage);
  if (!first_and_bridge) return first_and_bridge;
  return composeCameras(*first_and_bridge, second, summary);
}

// The largest error of the refit allowed, relative to the largest value of the depth output
// over the first camera's depth range: σ then stays within ½ % of its exact value.
constexpr double kRefitTolerance = 1e-2;

// The pieces of h, then `pieces` (the paper's §5: canonical view → table → reflection with a
// refracting or reflecting piecewise camera). Each patch camera takes h by the input-side rule
// (composeCameras: Q_i ← Hᵀ Q_i H, exact, one stage); the rectangles and support hulls stay in
// the frame they were fitted in, which the patch frame's homography (source pixels → that
// frame) reaches: a rectangle's preimage is a quadrilateral, kept exactly this way rather than
// approximated by a rectangle (piecewise_camera.h, PatchFrame). Patches no source pixel reaches
// are left out; none left is refused.
Result<PiecewiseCamera> piecesAfterHomography(const Camera& h, const PiecewiseCamera& pieces, FrameSize target) {
  using R = Result<PiecewiseCamera>;
  PiecewiseCamera out = pieces;
  out.patches.clear();
  // Source pixels → the homography's target pixels → the piecewise camera's source pixels (the
  // per-axis scale meetFrames applies when the frames have one shape) → its patch frame.
  const auto hn = homographyOf(h);
  if (!hn) return R::failure("the first camera is not a homography");
  const Eigen::Matrix3d h_px = pixelFromNormalizedMatrix(h.targetSize()) * Eigen::Matrix3d(*hn) *
                               normalizedFromPixelMatrix(h.sourceSize());
  const Eigen::Matrix3d before = pieces.patch_frame ? pieces.patch_frame->patch_from_source
                                                    : Eigen::Matrix3d::Identity();
  PatchFrame frame;
  frame.size = pieces.patchFrameSize();
  frame.patch_from_source = before * pixelScale(h.targetSize(), pieces.source_size) * h_px;
  // The source frame's side of the pole line has positive weight (PatchFrame); then entries
  // near 1.
  const Eigen::Vector3d centre(h.sourceSize().width / 2.0, h.sourceSize().height / 2.0, 1.0);
  const double w = (frame.patch_from_source * centre).z();
  if (!(std::abs(w) > 0.0) || !std::isfinite(w))
    return R::failure("the homography maps the centre of its source onto its pole line");
  frame.patch_from_source /= w;
  out.patch_frame = frame;
  out.source_size = h.sourceSize();
  out.target_size = target;
  for (size_t i = 0; i < pieces.patches.size(); ++i) {
    auto c = composeCameras(h, pieces.patches[i].camera);
    if (!c) return R::failure("patch " + std::to_string(i) + ": " + c.status.message);
    CameraPatch patch = pieces.patches[i];
    patch.camera = std::move(*c);
    out.patches.push_back(std::move(patch));
    const PatchRect box = out.sourceBox(static_cast<int>(out.patches.size() - 1));
    if (!(box.x1 > box.x0 && box.y1 > box.y0)) out.patches.pop_back();
  }
  if (out.patches.empty())
    return R::failure("no pixel of the homography's " + sizeText(h.sourceSize()) +
                      " source reaches the piecewise camera's patches");
  return R::success(std::move(out));
}

bool positionOnlyImage(const Artcam& c) {
  return c.layers.size() == 1 && !c.pieces && c.blocks().size() == 1 &&
         c.blocks()[0].kind == BlockKind::Position && c.blocks()[0].size == 3 &&
         c.depth_output == DepthOutput::Depth;
}

}  // namespace

Result<Artcam> composeArtcams(const Artcam& first, const Artcam& second, std::string* description) {
  using R = Result<Artcam>;
  if (first.pieces && second.pieces)
    return R::failure("two piecewise cameras do not compose into one: the second's patches are "
                      "rectangles of its source, which the first's patches would cut and bend");
  if (second.pieces && !(positionOnlyImage(first) && first.main().stages().size() == 1 &&
                         homographyOf(first.main())))
    return R::failure("only a homography can come before a piecewise camera: its patches are "
                      "rectangles of its source, which a homography maps onto quadrilaterals "
                      "(kept exactly) and any other camera would bend into curves");
  if (first.pieces && !positionOnlyImage(second))
    return R::failure("a piecewise camera is followed only by a single-layer position-only image "
                      "camera (its patches are position-only; colour, depth and layers after "
                      "patches are not supported)");
  if (first.depth_output == DepthOutput::BlurVariance)
    return R::failure("the first camera's depth output is a blur variance (depth of field), not a "
                      "depth: depth of field must come last");
  const size_t n1 = first.layers.size(), n2 = second.layers.size();
  if (n1 > 1 && n2 > 1 && n1 != n2)
    return R::failure("layered cameras compose layer by layer and need as many layers (" +
                      std::to_string(n1) + " and " + std::to_string(n2) + ")");
  Artcam out;
  out.depth_output = second.depth_output;
  std::string text;
  const size_t n = std::max(n1, n2);
  for (size_t k = 0; k < n; ++k) {
    CompositionSummary summary;
    const auto [a, b] = commonBlocks(first.layers[n1 > 1 ? k : 0], second.layers[n2 > 1 ? k : 0]);
    std::string refit_note;
    std::optional<DepthBridge> bridge;
    if (changesDepth(a) && readsDepth(b)) {
      // The chain would feed b first's depth output (aerial perspective's log depth l) where b
      // expects a depth. When b reads depth only in its depth output (depth of field's σ²),
      // that output is re-expressed on l by a fitted ratio of quadratics, as the paper fits
      // aerial perspective's log; otherwise the composition cannot be one camera.
      const std::optional<DepthBridge> fit =
          depthOutputReadsDepthAlone(b) ? bridgeDepth(a, b) : std::nullopt;
      if (!fit)
        return R::failure("the first camera outputs something else than the depth it read (e.g. "
                          "aerial perspective's log depth) and the second reads depth in a way "
                          "that cannot be re-expressed on it: composed, it would read the wrong "
                          "quantity");
      if (fit->max_error > kRefitTolerance * fit->scale)
        return R::failure("the second camera's depth output bridged from the first's depth "
                          "output is off by " + std::to_string(fit->max_error) + " (of " +
                          std::to_string(fit->scale) + "): too far to be one camera");
      bridge = fit;
      char note[160];
      std::snprintf(note, sizeof note,
                    "; depth bridged from the first camera's depth output by a fitted %s "
                    "(largest error of the depth output %.3g of %.3g)",
                    fit->inverse ? "inverse depth" : "depth", fit->max_error, fit->scale);
      refit_note = note;
    }
    auto c = bridge ? composeThroughBridge(a, b, *bridge, &summary) : composeCameras(a, b, &summary);
    if (!c) return R::failure((n > 1 ? "layer " + std::to_string(k + 1) + ": " : "") + c.status.message);
    out.layers.push_back(std::move(*c));
    if (k == 0) text = summary.description + refit_note;
  }
  if (first.pieces) {
    PiecewiseCamera pieces = *first.pieces;
    for (size_t i = 0; i < pieces.patches.size(); ++i) {
      auto c = composeCameras(pieces.patches[i].camera, second.main());
      if (!c) return R::failure("patch " + std::to_string(i) + ": " + c.status.message);
      pieces.patches[i].camera = std::move(*c);
    }
    pieces.source_size = out.sourceSize();
    pieces.target_size = out.targetSize();
    out.pieces = std::move(pieces);
    text += "; " + std::to_string(out.pieces->patches.size()) + " patches composed";
  }
  if (second.pieces) {
    auto pieces = piecesAfterHomography(first.main(), *second.pieces, out.targetSize());
    if (!pieces) return R::failure(pieces.status.message);
    const size_t dropped = second.pieces->patches.size() - pieces->patches.size();
    text += "; the homography folded into each of " + std::to_string(pieces->patches.size()) +
            " patches, their rectangles kept in the piecewise camera's source frame (patch frame)";
    if (dropped > 0)
      text += "; " + std::to_string(dropped) + " patches no source pixel reaches left out";
    out.pieces = std::move(*pieces);
  }
  if (n > 1) text += " (" + std::to_string(n) + " layers, layer by layer)";
  if (description) *description = text;
  return R::success(std::move(out));
}

}  // namespace artcam
