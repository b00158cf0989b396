#include "core/render/coordinates.h"

#include "core/model/frames.h"
#include "core/render/inverse_seed.h"
#include "core/render/parallel.h"

#include <Eigen/LU>

#include <cmath>
#include <stdexcept>
#include <vector>

namespace artcam {
namespace {

class ProjectiveKernel final : public CoordinateKernel {
 public:
  ProjectiveKernel(const Eigen::Matrix3d& target_from_source, FrameSize source_px) {
    const Eigen::Matrix3d& h = target_from_source;
    // An affine map keeps w constant; invert it in closed form so the last row stays exactly
    // (0, 0, 1) and the span loop can skip the division.
    affine_ = h(2, 0) == 0.0 && h(2, 1) == 0.0 && h(2, 2) != 0.0;
    if (affine_) {
      const Eigen::Matrix2d a = h.topLeftCorner<2, 2>() / h(2, 2);
      const Eigen::Vector2d b = h.topRightCorner<2, 1>() / h(2, 2);
      const Eigen::FullPivLU<Eigen::Matrix2d> lu(a);
      if (!lu.isInvertible()) throw std::invalid_argument("the camera's affine map is singular");
      m_.setZero();
      m_.topLeftCorner<2, 2>() = lu.inverse();
      m_.topRightCorner<2, 1>() = -m_.topLeftCorner<2, 2>() * b;
      m_(2, 2) = 1.0;
      centre_positive_ = true;
    } else {
      const Eigen::FullPivLU<Eigen::Matrix3d> lu(h);
      if (!lu.isInvertible()) throw std::invalid_argument("the camera's homography is singular");
      m_ = lu.inverse();
      const double scale = m_.cwiseAbs().maxCoeff();
      if (!(scale > 0.0) || !m_.allFinite())
        throw std::invalid_argument("the camera's homography has no finite inverse");
      m_ /= scale;  // a positive factor keeps every sign below
      // The forward denominator at s_h / s_h3 is 1 / s_h3 up to a positive scale (inverse.cpp).
      const Eigen::Vector3d centre(source_px.width / 2.0, source_px.height / 2.0, 1.0);
      centre_positive_ = (h * centre).z() > 0.0;
    }
    if (!m_.allFinite()) throw std::invalid_argument("the camera's homography has no finite inverse");
  }

  int span(int y, int x0, int n, float* sx, float* sy, unsigned char* valid,
           RowState&) const override {
    const Eigen::Vector3d h0 = m_ * Eigen::Vector3d(x0 + 0.5, y + 0.5, 1.0);
    const double dx = m_(0, 0), dy = m_(1, 0), dw = m_(2, 0);
    if (affine_) {
      for (int i = 0; i < n; ++i) {
        sx[i] = static_cast<float>(h0.x() + i * dx);
        sy[i] = static_cast<float>(h0.y() + i * dy);
        valid[i] = 1;
      }
      return 0;
    }
    for (int i = 0; i < n; ++i) {
      const double w = h0.z() + i * dw;
      const bool side = centre_positive_ ? w > 0.0 : w < 0.0;
      const double inv = 1.0 / w;
      const double u = (h0.x() + i * dx) * inv, v = (h0.y() + i * dy) * inv;
      // Beyond the horizon, or so close to it that the point overflows float: no preimage.
      const bool ok = side && std::abs(u) < 1e30 && std::abs(v) < 1e30;
      sx[i] = ok ? static_cast<float>(u) : 0.0f;
      sy[i] = ok ? static_cast<float>(v) : 0.0f;
      valid[i] = ok ? 1 : 0;
    }
    return 0;
  }

  bool sourceJacobian(const Eigen::Vector2d& t, const Eigen::Vector2d& s,
                      Eigen::Matrix2d& j) const override {
    const double w = m_.row(2).dot(Eigen::Vector3d(t.x(), t.y(), 1.0));
    if (!(std::abs(w) > 0.0)) return false;
    // d(X/W) = (∇X − s ∇W) / W.
    j.row(0) = (m_.block<1, 2>(0, 0) - s.x() * m_.block<1, 2>(2, 0)) / w;
    j.row(1) = (m_.block<1, 2>(1, 0) - s.y() * m_.block<1, 2>(2, 0)) / w;
    return j.allFinite();
  }

  std::optional<std::array<int, 2>> wholePixelOffset() const override {
    if (!affine_) return std::nullopt;
    if (!(m_.topLeftCorner<2, 2>() - Eigen::Matrix2d::Identity()).isZero(1e-12)) return std::nullopt;
    const double tx = m_(0, 2), ty = m_(1, 2);
    if (std::abs(tx - std::round(tx)) > 1e-9 || std::abs(ty - std::round(ty)) > 1e-9) return std::nullopt;
    if (std::abs(tx) > 1e9 || std::abs(ty) > 1e9) return std::nullopt;
    return std::array<int, 2>{static_cast<int>(std::lround(tx)), static_cast<int>(std::lround(ty))};
  }

 private:
  Eigen::Matrix3d m_;  // source_from_target, column form, pixels
  bool affine_ = false;
  bool centre_positive_ = true;
};

// One quadratic form x Q xᵀ of x = (u, v, 1) as n = a u² + b uv + c u + d v² + e v + f.
struct Quadratic {
  double a, b, c, d, e, f;
  explicit Quadratic(const Eigen::Matrix3d& q)
      : a(q(0, 0)), b(2 * q(0, 1)), c(2 * q(0, 2)), d(q(1, 1)), e(2 * q(1, 2)), f(q(2, 2)) {}
  double value(double u, double v) const { return (a * u + b * v + c) * u + (d * v + e) * v + f; }
  double du(double u, double v) const { return 2 * a * u + b * v + c; }
  double dv(double u, double v) const { return b * u + 2 * d * v + e; }
};

class RationalKernel final : public CoordinateKernel {
 public:
  RationalKernel(RationalMap forward, std::optional<RationalMap> seed, FrameSize source_px,
                 FrameSize target_px, const CoordinateOptions& options, int threads)
      : newton_(std::move(forward), source_px, options.residual_tolerance_px),
        seed_tolerance_(options.seed_tolerance_px) {
    if (seed && seed->stageCount() == 1) seed_q_ = seed->stage(0);
    if (newton_.forward().stageCount() == 1)
      for (const Eigen::Matrix3d& q : newton_.forward().stage(0)) forward_q_.emplace_back(q);
    buildCorrectionGrid(target_px, threads);
  }

  int span(int y, int x0, int n, float* sx, float* sy, unsigned char* valid,
           RowState& state) const override {
    const double ty = y + 0.5;
    // The grid correction: bilinear in y once per cell, then linear in x along the cell.
    const int gj = std::min(static_cast<int>(ty / kGrid), grid_h_ - 2);
    const double fy = ty / kGrid - gj;
    double corr_x[kSpanPixels], corr_y[kSpanPixels];
    for (int c0 = 0; c0 < n; c0 += kGrid) {
      const int gi = (x0 + c0) / kGrid, c1 = std::min(n, c0 + kGrid);
      Eigen::Vector2d left(0, 0), slope(0, 0);
      if (gi + 1 < grid_w_ && cellValid(gi, gj)) {
        left = (1 - fy) * node(gi, gj) + fy * node(gi, gj + 1);
        const Eigen::Vector2d right = (1 - fy) * node(gi + 1, gj) + fy * node(gi + 1, gj + 1);
        slope = (right - left) / kGrid;
        left -= slope * (gi * kGrid);  // so that correction(tx) = left + slope · tx
      }
      for (int i = c0; i < c1; ++i) {
        corr_x[i] = left.x() + slope.x() * (x0 + i + 0.5);
        corr_y[i] = left.y() + slope.y() * (x0 + i + 0.5);
      }
    }
    // Pass 1, every pixel independent (plain arrays the compiler may vectorise): the seed by
    // forward differences, the grid correction, and the one-evaluation check.
    double bx[kSpanPixels], by[kSpanPixels], qx[kSpanPixels], qy[kSpanPixels];
    unsigned char have[kSpanPixels], passed[kSpanPixels];
    if (!seed_q_.empty()) {
      RowQuadratics seed_row(seed_q_, y, x0);
      for (int i = 0; i < n; ++i, seed_row.advance()) {
        const double den = seed_row.numerator(2);
        bx[i] = seed_row.numerator(0) / den;
        by[i] = seed_row.numerator(1) / den;
      }
    } else {
      for (int i = 0; i < n; ++i) {
        bx[i] = x0 + i + 0.5;
        by[i] = ty;
      }
    }
    for (int i = 0; i < n; ++i) {
      bx[i] += corr_x[i];
      by[i] += corr_y[i];
      have[i] = std::isfinite(bx[i]) && std::isfinite(by[i]);
    }
    if (forward_q_.size() == 3) {
      checkSpan(x0, ty, n, bx, by, qx, qy, passed);
      for (int i = 0; i < n; ++i) passed[i] &= have[i];
    } else {
      for (int i = 0; i < n; ++i) {
        Eigen::Vector2d q;
        passed[i] = have[i] && check(Eigen::Vector2d(x0 + i + 0.5, ty), Eigen::Vector2d(bx[i], by[i]), q);
        qx[i] = q.x();
        qy[i] = q.y();
      }
    }

    // Pass 2, in order along the row: the pixels the seed missed try the extrapolation of
    // their solved neighbours, then Newton.
    int newton_count = 0;
    for (int i = 0; i < n; ++i) {
      const Eigen::Vector2d t(x0 + i + 0.5, ty);
      const Eigen::Vector2d base(bx[i], by[i]);
      Eigen::Vector2d s(qx[i], qy[i]);
      bool ok = passed[i] != 0, from_base = ok;
      // Quadratic extrapolation of the last three solutions misses by the map's third
      // derivative (~1e-5 px); linear by its second, which strong lenses make ~1e-2 px.
      if (!ok && state.run >= 3) ok = check(t, 3.0 * (state.previous - state.before_previous) + state.third, s);
      if (!ok && state.run == 2) ok = check(t, 2.0 * state.previous - state.before_previous, s);
      if (!ok && have[i] && state.run >= 1) ok = from_base = check(t, base + state.seed_offset, s);
      if (!ok) {
        ++newton_count;
        if (state.run >= 2)
          ok = newton_.solve(t, 2.0 * state.previous - state.before_previous, s, kQuickIterations);
        if (!ok && have[i]) ok = from_base = newton_.solve(t, base, s, kQuickIterations);
        if (!ok && state.run >= 1) ok = newton_.solve(t, state.previous, s, kQuickIterations);
        if (!ok) ok = newton_.solveFromCentre(t, s, kMaxIterations);
      }
      valid[i] = ok ? 1 : 0;
      if (ok) {
        sx[i] = static_cast<float>(s.x());
        sy[i] = static_cast<float>(s.y());
        if (from_base) state.seed_offset = s - base;
        state.third = state.before_previous;
        state.before_previous = state.previous;
        state.previous = s;
        ++state.run;
      } else {
        sx[i] = sy[i] = 0.0f;
        state.run = 0;
      }
    }
    return newton_count;
  }

  bool sourceJacobian(const Eigen::Vector2d&, const Eigen::Vector2d& s,
                      Eigen::Matrix2d& j) const override {
    Eigen::Vector2d f;
    Eigen::Matrix2d jf;
    if (!newton_.forward().evaluate(s, f, &jf)) return false;
    const double det = jf.determinant();
    if (!(std::abs(det) > 0.0)) return false;
    j = jf.inverse();
    return j.allFinite();
  }

 private:
  static constexpr int kQuickIterations = 8;
  static constexpr int kMaxIterations = 30;
  // Correction-grid spacing (output pixels): bilinear interpolation of the seed's error
  // misses by spacing²/8 · its curvature; 64 px measured ~1/256 px on the peer's mild lens
  // (half the pixels failing the check), 32 px a quarter of that. A divisor of kSpanPixels.
  static constexpr int kGrid = kSpanPixels / 2;

  // The forward map and its Jacobian (eq 1, 2); the one-stage case inline, chains generic.
  bool forward(const Eigen::Vector2d& s, Eigen::Vector2d& f, Eigen::Matrix2d& j,
               unsigned& signs) const {
    if (forward_q_.empty()) return newton_.forward().evaluate(s, f, &j, &signs);
    const double u = s.x(), v = s.y();
    const double den = forward_q_[2].value(u, v);
    if (!(std::abs(den) > 0.0)) return false;
    const double inv = 1.0 / den;
    const double fx = forward_q_[0].value(u, v) * inv, fy = forward_q_[1].value(u, v) * inv;
    const double du = forward_q_[2].du(u, v), dv = forward_q_[2].dv(u, v);
    j << (forward_q_[0].du(u, v) - fx * du) * inv, (forward_q_[0].dv(u, v) - fx * dv) * inv,
        (forward_q_[1].du(u, v) - fy * du) * inv, (forward_q_[1].dv(u, v) - fy * dv) * inv;
    f = Eigen::Vector2d(fx, fy);
    signs = den < 0.0 ? 1u : 0u;
    return std::isfinite(fx) && std::isfinite(fy);
  }

  // check() for a whole span of starts (bx, by) with the one-stage forward map in plain
  // doubles and no branches: q = start − δ, passed = the same acceptance as check().
  void checkSpan(int x0, double ty, int n, const double* bx, const double* by, double* qx,
                 double* qy, unsigned char* passed) const {
    const Quadratic f0 = forward_q_[0], f1 = forward_q_[1], f2 = forward_q_[2];
    const bool den_negative = newton_.centre().denominator_signs & 1u;
    const bool det_positive = newton_.centre().det_positive;
    const double tol = seed_tolerance_;
    for (int i = 0; i < n; ++i) {
      const double u = bx[i], v = by[i];
      const double den = f2.value(u, v), inv = 1.0 / den;
      const double fx = f0.value(u, v) * inv, fy = f1.value(u, v) * inv;
      const double du = f2.du(u, v), dv = f2.dv(u, v);
      const double j00 = (f0.du(u, v) - fx * du) * inv, j01 = (f0.dv(u, v) - fx * dv) * inv;
      const double j10 = (f1.du(u, v) - fy * du) * inv, j11 = (f1.dv(u, v) - fy * dv) * inv;
      const double det = j00 * j11 - j01 * j10;
      const double rx = fx - (x0 + i + 0.5), ry = fy - ty;
      const double stepx = (j11 * rx - j01 * ry) / det, stepy = (-j10 * rx + j00 * ry) / det;
      qx[i] = u - stepx;
      qy[i] = v - stepy;
      // The negated comparisons also reject NaN (a start on the pole, a singular Jacobian).
      passed[i] = ((den < 0.0) == den_negative) & ((det > 0.0) == det_positive) &
                  (std::abs(stepx) <= tol) & (std::abs(stepy) <= tol);
    }
  }

  // The seed check: one forward evaluation, the Newton step it implies, and the pole and fold
  // tests of inverse.h at the start.
  bool check(const Eigen::Vector2d& t, const Eigen::Vector2d& start, Eigen::Vector2d& s) const {
    Eigen::Vector2d f;
    Eigen::Matrix2d j;
    unsigned signs = 0;
    if (!forward(start, f, j, signs)) return false;
    const CentreReference& c = newton_.centre();
    const double det = j(0, 0) * j(1, 1) - j(0, 1) * j(1, 0);
    if (signs != c.denominator_signs || (det > 0.0) != c.det_positive) return false;
    const Eigen::Vector2d r = f - t;
    const Eigen::Vector2d step(( j(1, 1) * r.x() - j(0, 1) * r.y()) / det,
                               (-j(1, 0) * r.x() + j(0, 0) * r.y()) / det);
    if (!(std::abs(step.x()) <= seed_tolerance_ && std::abs(step.y()) <= seed_tolerance_))
      return false;
    s = start - step;
    return true;
  }

  Eigen::Vector2d seedAt(const Eigen::Vector2d& t, bool& ok) const {
    ok = true;
    if (seed_q_.empty()) return t;
    const Quadratic q0(seed_q_[0]), q1(seed_q_[1]), q2(seed_q_[2]);
    const double den = q2.value(t.x(), t.y());
    const Eigen::Vector2d s = Eigen::Vector2d(q0.value(t.x(), t.y()), q1.value(t.x(), t.y())) / den;
    ok = s.allFinite();
    return s;
  }

  // The exact inverse minus the seed at nodes every kGrid output pixels (including the
  // far edge); a node with no preimage makes its cells fall back to the seed alone.
  void buildCorrectionGrid(FrameSize target_px, int threads) {
    grid_w_ = target_px.width / kGrid + 2;
    grid_h_ = target_px.height / kGrid + 2;
    nodes_.assign(static_cast<size_t>(grid_w_) * static_cast<size_t>(grid_h_), Eigen::Vector2d::Zero());
    node_valid_.assign(nodes_.size(), 0);
    ParallelOptions po;
    po.threads = threads;
    po.band_rows = 4;
    parallelForRows(grid_h_, po, [&](int j0, int j1) {
      for (int j = j0; j < j1; ++j)
        for (int i = 0; i < grid_w_; ++i) {
          const Eigen::Vector2d t(i * kGrid, j * kGrid);
          bool seeded = false;
          const Eigen::Vector2d base = seedAt(t, seeded);
          Eigen::Vector2d s;
          bool ok = seeded && newton_.solve(t, base, s, kMaxIterations);
          if (!ok) ok = newton_.solveFromCentre(t, s, kMaxIterations);
          const size_t k = static_cast<size_t>(j) * static_cast<size_t>(grid_w_) + static_cast<size_t>(i);
          if (ok && seeded) {
            nodes_[k] = s - base;
            node_valid_[k] = 1;
          }
        }
    });
  }

  const Eigen::Vector2d& node(int i, int j) const {
    return nodes_[static_cast<size_t>(j) * static_cast<size_t>(grid_w_) + static_cast<size_t>(i)];
  }
  bool cellValid(int i, int j) const {
    const auto at = [&](int a, int b) {
      return node_valid_[static_cast<size_t>(b) * static_cast<size_t>(grid_w_) + static_cast<size_t>(a)] != 0;
    };
    return at(i, j) && at(i + 1, j) && at(i, j + 1) && at(i + 1, j + 1);
  }

  NewtonInverse newton_;
  std::vector<Eigen::Matrix3d> seed_q_;
  std::vector<Quadratic> forward_q_;
  double seed_tolerance_;
  int grid_w_ = 0, grid_h_ = 0;
  std::vector<Eigen::Vector2d> nodes_;
  std::vector<unsigned char> node_valid_;
};

Eigen::Matrix3d pixelHomography(const CameraStructure& structure, FrameSize source_px,
                                FrameSize target_px) {
  // The homography is stored normalised (frames.h); in pixels it is P_out · H · N_source.
  return pixelFromNormalizedMatrix(target_px) * Eigen::Matrix3d(structure.homography) *
         normalizedFromPixelMatrix(source_px);
}

}  // namespace

KernelChoice makeCoordinateKernel(const Camera& camera, const CameraStructure& structure,
                                  FrameSize source_px, FrameSize target_px,
                                  const CoordinateOptions& options, int threads) {
  KernelChoice choice;
  if (!options.force_rational && structure.geometry != GeometryClass::Rational) {
    const bool same_size = source_px == target_px;
    // An identity between frames of different pixel sizes is an axis-aligned scaling.
    choice.name = structure.geometry == GeometryClass::Identity
                      ? (same_size ? "identity" : "affine")
                      : std::string(geometryClassName(structure.geometry));
    choice.kernel = std::make_unique<ProjectiveKernel>(
        pixelHomography(structure, source_px, target_px), source_px);
    return choice;
  }
  choice.name = "rational";
  RationalMap forward(camera, source_px, target_px);
  std::optional<RationalMap> seed;
  if (options.fit_inverse_seed) {
    Result<RationalMap> fitted = fitInverseSeed(forward, source_px, target_px);
    if (fitted) seed = std::move(*fitted);
    else choice.note = "inverse seed not used: " + fitted.status.message;
  }
  choice.kernel = std::make_unique<RationalKernel>(std::move(forward), std::move(seed), source_px,
                                                   target_px, options, threads);
  return choice;
}

std::unique_ptr<InverseMap> makeReferenceInverse(const Camera& camera,
                                                 const CameraStructure& structure,
                                                 FrameSize source_px, FrameSize target_px,
                                                 bool force_rational) {
  if (!force_rational && structure.geometry != GeometryClass::Rational)
    return makeHomographyInverse(pixelHomography(structure, source_px, target_px), source_px);
  // The pre-fusion production path: Newton at every pixel to ~1e-7 px, from the fitted seed,
  // the neighbours and the centre (validated against closed forms in test_kernels).
  RationalMap forward(camera, source_px, target_px);
  std::optional<RationalMap> seed;
  if (Result<RationalMap> fitted = fitInverseSeed(forward, source_px, target_px)) seed = std::move(*fitted);
  RationalInverseOptions ro;
  return makeRationalInverse(std::move(forward), std::move(seed), source_px, ro);
}

}  // namespace artcam
