// SPDX-License-Identifier: Apache-2.0
// Lens calibration from straight lines (fit_lines.h). The unknowns are tensor entries in the
// normalised frames, q = (q_1, q_2, q_3), each the upper triangle of a symmetric Q_i in the
// order (uu, uv, uw, vv, vw, ww), so x Q_i xᵀ = χ·q_i with χ = (u², 2uv, 2u, v², 2v, 1) as in
// dlt.h. A model is an affine family q = q0 + B p of them (radial: one column; quadratic:
// every entry but Q_3's ww, which fixes the scale).
#include "core/fit/fit_lines.h"

#include "core/fit/line_model_guard.h"
#include "core/fit/poles.h"
#include "core/fit/report_format.h"
#include "core/model/frames.h"

#include <Eigen/QR>
#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>

namespace artcam {

namespace {

using Vec18 = Eigen::Matrix<double, 18, 1>;
using Chi = Eigen::Matrix<double, 6, 1>;
constexpr int kUU = 0, kUW = 2, kVV = 3, kVW = 4, kWW = 5;

Chi chiOf(double u, double v) {
  Chi c;
  c << u * u, 2 * u * v, 2 * u, v * v, 2 * v, 1.0;
  return c;
}

Vec18 identityEntries() {
  Vec18 q = Vec18::Zero();
  q[kUW] = 0.5;          // x Q_1 xᵀ = u
  q[6 + kVW] = 0.5;      // x Q_2 xᵀ = v
  q[12 + kWW] = 1.0;     // x Q_3 xᵀ = 1
  return q;
}

Eigen::Matrix3d tensorOf(const Vec18& q, int i) {
  const double* e = q.data() + 6 * i;
  Eigen::Matrix3d m;
  m << e[0], e[1], e[2], e[1], e[3], e[4], e[2], e[4], e[5];
  return m;
}

// Perpendicular distances of points (2 × n, pixels) from their total-least-squares line; the
// line's unit normal is the covariance's eigenvector of the smallest eigenvalue.
struct TlsLine {
  Eigen::Vector2d centroid;
  Eigen::Vector2d normal;
  Eigen::Vector2d tangent;
  double across = 0.0;  // the covariance's eigenvalues: across and along the line (px²)
  double along = 0.0;
  double spread = 0.0;  // RMS extent along the line (px): how long the trace is
};

TlsLine tlsLine(const Eigen::Matrix2Xd& y) {
  TlsLine line;
  line.centroid = y.rowwise().mean();
  const Eigen::Matrix2Xd centred = y.colwise() - line.centroid;
  const Eigen::Matrix2d cov = centred * centred.transpose() / static_cast<double>(y.cols());
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(cov);
  line.normal = eig.eigenvectors().col(0);
  line.tangent = eig.eigenvectors().col(1);
  line.across = eig.eigenvalues()[0];
  line.along = eig.eigenvalues()[1];
  line.spread = std::sqrt(std::max(0.0, eig.eigenvalues()[1]));
  return line;
}

struct Problem {
  std::vector<Eigen::Matrix2Xd> lines;  // enabled lines, normalised source coordinates
  Eigen::Matrix2Xd pair_src;            // normalised source
  Eigen::Matrix2Xd pair_dst_px;         // target pixels
  double s_t = 1.0;                     // target pixels per normalised unit
  Eigen::Vector2d c_t = Eigen::Vector2d::Zero();  // target centre in pixels
  double gauge_weight = 1.0;
  double tikhonov_weight = 0.0;
  Vec18 q0;
  Eigen::MatrixXd basis;  // 18 × P
  Eigen::Vector2d frame_lo, frame_hi;
  int points = 0;

  int residualCount() const { return points + 2 * static_cast<int>(pair_src.cols()) + 8 + 18; }
};

// The gauge (fit_lines.h): centre to centre, identity Jacobian there, no denominator tilt; in
// pixels at one normalised unit from the centre, times the gauge weight.
Eigen::Matrix<double, 8, 1> gaugeResiduals(const Problem& pb, const Vec18& q) {
  const double n1 = q[kWW], n2 = q[6 + kWW], d = q[12 + kWW];
  const double d_u = 2 * q[12 + kUW], d_v = 2 * q[12 + kVW];
  const double y1 = n1 / d, y2 = n2 / d;
  const double j11 = (2 * q[kUW] - y1 * d_u) / d, j12 = (2 * q[kVW] - y1 * d_v) / d;
  const double j21 = (2 * q[6 + kUW] - y2 * d_u) / d, j22 = (2 * q[6 + kVW] - y2 * d_v) / d;
  Eigen::Matrix<double, 8, 1> g;
  g << y1, y2, j11 - 1, j12, j21, j22 - 1, d_u / d, d_v / d;
  return g * (pb.s_t * pb.gauge_weight);
}

// Residuals in target pixels: line distances, pair components, gauge, least change. With
// jacobian, their derivatives in q, each line refitted (its centroid and normal move with the
// points). False where a point meets the pole (denominator ≤ 0: positive at the centre).
bool evaluate(const Problem& pb, const Vec18& q, Eigen::VectorXd& r, Eigen::MatrixXd* jacobian) {
  r.resize(pb.residualCount());
  if (jacobian) jacobian->setZero(pb.residualCount(), 18);
  const Eigen::Ref<const Chi> q1 = q.segment<6>(0), q2 = q.segment<6>(6), q3 = q.segment<6>(12);
  int row = 0;
  for (const Eigen::Matrix2Xd& line : pb.lines) {
    const Eigen::Index n = line.cols();
    Eigen::Matrix2Xd y(2, n);
    std::vector<Chi> chis(static_cast<size_t>(n));
    std::vector<double> dens(static_cast<size_t>(n));
    for (Eigen::Index k = 0; k < n; ++k) {
      const Chi c = chiOf(line(0, k), line(1, k));
      const double d = c.dot(q3);
      if (!(d > 0.0)) return false;
      y(0, k) = pb.s_t * c.dot(q1) / d + pb.c_t.x();
      y(1, k) = pb.s_t * c.dot(q2) / d + pb.c_t.y();
      chis[static_cast<size_t>(k)] = c;
      dens[static_cast<size_t>(k)] = d;
    }
    const TlsLine tls = tlsLine(y);
    for (Eigen::Index k = 0; k < n; ++k) r[row + k] = tls.normal.dot(y.col(k) - tls.centroid);
    if (jacobian) {
      // r_k = n·(y_k - c) with the line refitted: dr_k = n·(dy_k - dc) + (y_k - c)·dn, where
      // the normal turns with the covariance C: dn = t (tᵀ dC n) / (λ_across - λ_along) and
      // tᵀ dC n = (1/N) Σ_j (a_j n·dy_j + r_j t·dy_j), a_j = t·(y_j - c). Holding n instead
      // keeps the gradient but makes every turn of a line look costly: with pairs asking for
      // a rotation, LM then crept at 8 % per step.
      Eigen::Matrix<double, 1, 18> mean_row = Eigen::Matrix<double, 1, 18>::Zero();
      Eigen::Matrix<double, 1, 18> turn = Eigen::Matrix<double, 1, 18>::Zero();
      std::vector<double> a(static_cast<size_t>(n));
      for (Eigen::Index k = 0; k < n; ++k) {
        const Chi& c = chis[static_cast<size_t>(k)];
        const double f = pb.s_t / dens[static_cast<size_t>(k)];
        const double yn1 = (y(0, k) - pb.c_t.x()) / pb.s_t, yn2 = (y(1, k) - pb.c_t.y()) / pb.s_t;
        const auto rowAlong = [&](const Eigen::Vector2d& dir) {
          Eigen::Matrix<double, 1, 18> jr;
          jr << f * dir.x() * c.transpose(), f * dir.y() * c.transpose(),
              -f * (dir.x() * yn1 + dir.y() * yn2) * c.transpose();
          return jr;
        };
        const Eigen::Matrix<double, 1, 18> gn = rowAlong(tls.normal);
        a[static_cast<size_t>(k)] = tls.tangent.dot(y.col(k) - tls.centroid);
        jacobian->row(row + k) = gn;
        mean_row += gn / static_cast<double>(n);
        turn += (a[static_cast<size_t>(k)] * gn + r[row + k] * rowAlong(tls.tangent)) /
                static_cast<double>(n);
      }
      const double gap = tls.across - tls.along;
      for (Eigen::Index k = 0; k < n; ++k) {
        jacobian->row(row + k) -= mean_row;
        if (gap < 0) jacobian->row(row + k) += a[static_cast<size_t>(k)] / gap * turn;
      }
    }
    row += static_cast<int>(n);
  }
  for (Eigen::Index k = 0; k < pb.pair_src.cols(); ++k) {
    const Chi c = chiOf(pb.pair_src(0, k), pb.pair_src(1, k));
    const double d = c.dot(q3);
    if (!(d > 0.0)) return false;
    const double yn1 = c.dot(q1) / d, yn2 = c.dot(q2) / d;
    r[row] = pb.s_t * yn1 + pb.c_t.x() - pb.pair_dst_px(0, k);
    r[row + 1] = pb.s_t * yn2 + pb.c_t.y() - pb.pair_dst_px(1, k);
    if (jacobian) {
      const double f = pb.s_t / d;
      jacobian->block<1, 6>(row, 0) = f * c.transpose();
      jacobian->block<1, 6>(row, 12) = -f * yn1 * c.transpose();
      jacobian->block<1, 6>(row + 1, 6) = f * c.transpose();
      jacobian->block<1, 6>(row + 1, 12) = -f * yn2 * c.transpose();
    }
    row += 2;
  }
  const Eigen::Matrix<double, 8, 1> g = gaugeResiduals(pb, q);
  r.segment<8>(row) = g;
  if (jacobian) {
    // Eight residuals of six entries: central differences are exact to ~1e-10 here.
    for (int j = 0; j < 18; ++j) {
      Vec18 hi = q, lo = q;
      const double h = 1e-6;
      hi[j] += h;
      lo[j] -= h;
      jacobian->block<8, 1>(row, j) = (gaugeResiduals(pb, hi) - gaugeResiduals(pb, lo)) / (2 * h);
    }
  }
  row += 8;
  r.segment<18>(row) = (q - identityEntries()) * (pb.s_t * pb.tikhonov_weight);
  if (jacobian)
    jacobian->block<18, 18>(row, 0) = Eigen::Matrix<double, 18, 18>::Identity() *
                                      (pb.s_t * pb.tikhonov_weight);
  return r.allFinite();
}

bool poleSafe(const Problem& pb, const Vec18& q, double min_margin) {
  const PoleCheck check = checkDenominator(tensorOf(q, 2), pb.frame_lo, pb.frame_hi);
  return check.pole_free && check.margin >= min_margin;
}

struct Solved {
  Vec18 q;
  int iterations = 0;
  int undetermined = 0;
};

// Levenberg–Marquardt on p (q = q0 + B p) from p = 0, taking only steps that lower the cost
// and keep the frame pole-free with the margin.
Solved solve(const Problem& pb, const LinesFitOptions& options) {
  const Eigen::Index np = pb.basis.cols();
  Eigen::VectorXd p = Eigen::VectorXd::Zero(np);
  Vec18 q = pb.q0;
  Eigen::VectorXd r;
  Eigen::MatrixXd jq;
  Solved out;
  if (!evaluate(pb, q, r, &jq)) {
    out.q = q;
    return out;
  }
  double cost = r.squaredNorm();
  double mu = 1e-3;
  for (int it = 0; it < options.max_iterations; ++it) {
    out.iterations = it + 1;
    // The damped step as a least-squares problem [J; √(μ D)] δ = [-r; 0] solved by QR: the
    // normal matrix JᵀJ would square a condition number that the near-flat directions (the
    // gauge's, the least change's) already put near 1e8.
    const Eigen::MatrixXd jp = jq * pb.basis;
    const Eigen::VectorXd scale = jp.colwise().squaredNorm().transpose();
    const double floor = 1e-12 * scale.maxCoeff() + 1e-300;
    Eigen::MatrixXd aug(jp.rows() + np, np);
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(jp.rows() + np);
    aug.topRows(jp.rows()) = jp;
    rhs.head(jp.rows()) = -r;
    bool accepted = false;
    double new_cost = cost;
    while (mu < 1e12) {
      aug.bottomRows(np) = (mu * (scale.array() + floor)).sqrt().matrix().asDiagonal();
      const Eigen::VectorXd step = aug.colPivHouseholderQr().solve(rhs);
      const Eigen::VectorXd p_try = p + step;
      const Vec18 q_try = pb.q0 + pb.basis * p_try;
      Eigen::VectorXd r_try;
      if (step.allFinite() && poleSafe(pb, q_try, options.min_pole_margin) &&
          evaluate(pb, q_try, r_try, nullptr) && r_try.squaredNorm() < cost) {
        new_cost = r_try.squaredNorm();
        p = p_try;
        q = q_try;
        mu = std::max(mu / 3, 1e-12);
        accepted = true;
        break;
      }
      mu *= 4;
    }
    if (!accepted) break;
    const double fall = cost - new_cost;
    cost = new_cost;
    evaluate(pb, q, r, &jq);
    if (fall <= 1e-14 * cost || cost < 1e-24) break;
  }
  out.q = q;
  // Directions the lines, pairs and gauge leave free (the least-change rows excluded).
  const Eigen::MatrixXd jp = jq.topRows(pb.residualCount() - 18) * pb.basis;
  const Eigen::VectorXd ev =
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(jp.transpose() * jp).eigenvalues();
  for (Eigen::Index k = 0; k < ev.size(); ++k)
    if (ev[k] <= 1e-12 * ev[ev.size() - 1]) ++out.undetermined;

  return out;
}

Camera cameraOf(const Vec18& q, FrameSize source, FrameSize target) {
  std::vector<Eigen::Matrix3d> t = {tensorOf(q, 0), tensorOf(q, 1), tensorOf(q, 2)};
  // Stored like every fitted camera: largest entry 1, denominator positive at the centre.
  double scale = 0.0;
  for (const Eigen::Matrix3d& m : t) scale = std::max(scale, m.cwiseAbs().maxCoeff());
  if (t[2](2, 2) < 0) scale = -scale;
  for (Eigen::Matrix3d& m : t) m /= scale;
  return Camera::rtcam(t, source, target);
}

void bowTotals(const std::vector<LineBow>& bows, const std::vector<LineTrace>& lines,
               double& rms, double& max) {
  double sum = 0.0;
  int count = 0;
  max = 0.0;
  size_t k = 0;
  for (const LineTrace& line : lines) {
    if (!line.enabled) continue;
    const LineBow& b = bows[k++];
    sum += b.rms_px * b.rms_px * b.points;
    count += b.points;
    max = std::max(max, b.mapped ? b.max_px : std::numeric_limits<double>::infinity());
  }
  rms = count ? std::sqrt(sum / count) : 0.0;
}

// The radial family: one unknown, k, entering Q_3's uu and vv as -k.
void setRadial(Problem& pb) {
  pb.q0 = identityEntries();
  pb.basis = Eigen::MatrixXd::Zero(18, 1);
  pb.basis(12 + kUU, 0) = -1.0;
  pb.basis(12 + kVV, 0) = -1.0;
  pb.gauge_weight = 1.0;
  pb.tikhonov_weight = 0.0;
}

// The quadratic from the radial solution: away from the identity, where a common factor of the
// numerators and the denominator (Q_i = sym(l e_iᵀ)) would leave the map unchanged along two
// more directions. A hair of least change (1e-6) keeps those steps bounded.
Problem quadraticFrom(const Problem& pb, const Vec18& radial, bool pairs) {
  Problem quad = pb;
  quad.q0 = radial;
  quad.basis = Eigen::MatrixXd::Zero(18, 17);
  for (int j = 0, col = 0; j < 18; ++j)
    if (j != 12 + kWW) quad.basis(j, col++) = 1.0;
  quad.gauge_weight = pairs ? 1e-5 : 1.0;
  quad.tikhonov_weight = 1e-6;
  return quad;
}

// Each line left out in turn, both models fitted to the others, the left-out line's bow through
// each: how the models do on a line they were not fitted to. Lines only (no pairs).
struct HeldOut {
  bool possible = false;  // false: some fold leaves the quadratic fewer equations than it needs
  double radial_rms_px = 0.0;
  double quadratic_rms_px = 0.0;
};

HeldOut heldOutBows(const Problem& pb, const std::vector<const LineTrace*>& traces, int needs,
                    FrameSize source, FrameSize target, const LinesFitOptions& options) {
  HeldOut out;
  double radial_sum = 0.0, quadratic_sum = 0.0;
  int count = 0;
  for (size_t left = 0; left < pb.lines.size(); ++left) {
    Problem fold = pb;
    fold.lines.erase(fold.lines.begin() + static_cast<std::ptrdiff_t>(left));
    fold.points = 0;
    int information = 0;
    for (const Eigen::Matrix2Xd& l : fold.lines) {
      fold.points += static_cast<int>(l.cols());
      information += static_cast<int>(l.cols()) - 2;
    }
    if (information < needs) return out;
    setRadial(fold);
    const Solved radial = solve(fold, options);
    const Solved quadratic = solve(quadraticFrom(fold, radial.q, false), options);
    const std::vector<LineTrace> held = {*traces[left]};
    const LineBow r = lineBows(cameraOf(radial.q, source, target), held)[0];
    const LineBow q = lineBows(cameraOf(quadratic.q, source, target), held)[0];
    const double inf = std::numeric_limits<double>::infinity();
    radial_sum += (r.mapped ? r.rms_px * r.rms_px : inf) * r.points;
    quadratic_sum += (q.mapped ? q.rms_px * q.rms_px : inf) * q.points;
    count += r.points;
  }
  out.possible = count > 0;
  out.radial_rms_px = std::sqrt(radial_sum / std::max(count, 1));
  out.quadratic_rms_px = std::sqrt(quadratic_sum / std::max(count, 1));
  return out;
}

std::string percent(double fraction) { return threeFigures(100.0 * fraction) + " %"; }

}  // namespace

std::string_view lineModelName(LineModel model) {
  switch (model) {
    case LineModel::Auto: return "auto";
    case LineModel::Radial: return "radial";
    case LineModel::Quadratic: return "quadratic";
  }
  return "auto";
}

std::optional<LineModel> lineModelFromName(std::string_view name) {
  for (LineModel m : {LineModel::Auto, LineModel::Radial, LineModel::Quadratic})
    if (lineModelName(m) == name) return m;
  return std::nullopt;
}

std::vector<LineBow> lineBows(const Camera& camera, const std::vector<LineTrace>& lines) {
  std::vector<LineBow> bows;
  for (const LineTrace& line : lines) {
    if (!line.enabled) continue;
    LineBow bow;
    bow.label = line.label;
    bow.points = static_cast<int>(line.points.size());
    Eigen::Matrix2Xd y(2, line.points.size());
    for (size_t k = 0; k < line.points.size(); ++k) {
      const auto mapped = targetPixelFromSourcePixel(camera, line.points[k]);
      if (!mapped) {
        bow.mapped = false;
        break;
      }
      y.col(static_cast<Eigen::Index>(k)) = *mapped;
    }
    if (bow.mapped && bow.points >= 3) {
      const TlsLine tls = tlsLine(y);
      const Eigen::VectorXd d = tls.normal.transpose() * (y.colwise() - tls.centroid);
      bow.max_px = d.cwiseAbs().maxCoeff();
      double angle = std::atan2(tls.tangent.y(), tls.tangent.x()) * 180.0 / std::numbers::pi;
      if (angle > 90.0) angle -= 180.0;
      if (angle <= -90.0) angle += 180.0;
      bow.angle_deg = angle;
      bow.rms_px = std::sqrt(d.squaredNorm() / static_cast<double>(d.size()));
    }
    bows.push_back(bow);
  }
  return bows;
}

double tiltFromRoleDeg(const LineBow& bow, LineRole role) {
  if (role == LineRole::Horizontal) return bow.angle_deg;
  if (role != LineRole::Vertical) return 0.0;
  return bow.angle_deg > 0 ? bow.angle_deg - 90.0 : bow.angle_deg + 90.0;
}

Status LinesFitOptions::check(const FieldNames& names) const {
  using Ends = OptionsCheck::Ends;
  const bool known =
      model == LineModel::Auto || model == LineModel::Radial || model == LineModel::Quadratic;
  return OptionsCheck(names)
      .oneOf("model", known, "auto, radial or quadratic", static_cast<int>(model))
      .whole("max_iterations", max_iterations, 1, 100000)
      .number("auto_improvement", auto_improvement, 0.0, 1.0, Ends::AboveMin)
      .number("auto_min_gain_px", auto_min_gain_px, 0.0, OptionsCheck::kNoBound)
      .number("auto_max_spacing_change", auto_max_spacing_change, 0.0, OptionsCheck::kNoBound)
      .number("auto_max_empty_gain", auto_max_empty_gain, 0.0, 1.0)
      .number("min_pole_margin", min_pole_margin, 0.0, 1.0)
      .status();
}

LinesFitSummary fitLinesCamera(const std::vector<LineTrace>& lines,
                               const std::vector<PointMatch>& pairs, FrameSize source_size,
                               FrameSize target_size, const LinesFitOptions& options) {
  LinesFitSummary out;
  if (const Status s = options.check(); !s) {
    out.status = s;
    return out;
  }
  if (!source_size.isImage() || !target_size.isImage()) {
    out.status = Status::failure("a line fit needs the source and target image sizes");
    return out;
  }
  Problem pb;
  int information = 0;  // equations beyond each line's own position: Σ(n - 2) + 2 per pair
  for (const LineTrace& line : lines) {
    if (!line.enabled) continue;
    const int n = static_cast<int>(line.points.size());
    if (n < 3) {
      out.status = Status::failure("line \"" + line.label + "\" has " + std::to_string(n) +
                                   " point" + (n == 1 ? "" : "s") +
                                   "; a line needs at least 3 (two points are always on a line)");
      return out;
    }
    Eigen::Matrix2Xd px(2, n), normalized(2, n);
    for (int k = 0; k < n; ++k) {
      if (!line.points[static_cast<size_t>(k)].allFinite()) {
        out.status = Status::failure("line \"" + line.label + "\": point " +
                                     std::to_string(k + 1) + " is not a finite number");
        return out;
      }
      px.col(k) = line.points[static_cast<size_t>(k)];
      normalized.col(k) = normalizedFromPixel(source_size, px.col(k));
    }
    const double spread = tlsLine(px).spread;
    if (spread < 1.0) {
      out.status = Status::failure("line \"" + line.label + "\": its " + std::to_string(n) +
                                   " points lie within " + threeFigures(2 * spread) +
                                   " px of each other; trace it along the edge");
      return out;
    }
    pb.lines.push_back(normalized);
    pb.points += n;
    information += n - 2;
  }
  std::vector<const LineTrace*> enabled_traces;
  for (const LineTrace& line : lines)
    if (line.enabled) enabled_traces.push_back(&line);
  std::vector<const PointMatch*> enabled_pairs;
  for (const PointMatch& m : pairs)
    if (m.enabled) {
      if (m.source.size() != 2 || m.target.size() != 2 || !m.source.allFinite() ||
          !m.target.allFinite()) {
        out.status = Status::failure("pairs for a line fit must be finite 2D points");
        return out;
      }
      enabled_pairs.push_back(&m);
    }
  if (pb.lines.empty()) {
    out.status = Status::failure("no lines to straighten (" +
                                 std::string(lines.empty() ? "none given" : "all disabled") + ")");
    return out;
  }
  pb.pair_src.resize(2, static_cast<Eigen::Index>(enabled_pairs.size()));
  pb.pair_dst_px.resize(2, static_cast<Eigen::Index>(enabled_pairs.size()));
  for (size_t k = 0; k < enabled_pairs.size(); ++k) {
    pb.pair_src.col(static_cast<Eigen::Index>(k)) =
        normalizedFromPixel(source_size, enabled_pairs[k]->source.head<2>());
    pb.pair_dst_px.col(static_cast<Eigen::Index>(k)) = enabled_pairs[k]->target.head<2>();
  }
  information += 2 * static_cast<int>(enabled_pairs.size());
  pb.s_t = std::max(target_size.width, target_size.height) / 2.0;
  pb.c_t = Eigen::Vector2d(target_size.width / 2.0, target_size.height / 2.0);
  pb.frame_lo = normalizedFromPixel(source_size, {0.0, 0.0});
  pb.frame_hi = normalizedFromPixel(source_size, {static_cast<double>(source_size.width),
                                                  static_cast<double>(source_size.height)});
  // The radial lens first.
  setRadial(pb);
  {
    // Lines through the centre stay straight under every radial lens: when the bow's
    // derivative in k vanishes on every line, the lines say nothing about the distortion.
    Eigen::VectorXd r;
    Eigen::MatrixXd jq;
    evaluate(pb, pb.q0, r, &jq);
    const double sensitivity = (jq.topRows(pb.points) * pb.basis).norm();
    if (enabled_pairs.empty() && !(sensitivity > 1e-6 * pb.s_t * std::sqrt(pb.points))) {
      out.status = Status::failure(
          "the lines carry no information about the distortion: every one passes through the "
          "frame centre, which a lens keeps straight; trace edges away from the centre");
      return out;
    }
  }
  const Solved radial = solve(pb, options);
  out.radial_k = radial.q[12 + kUU] * -1.0;
  out.bows_before = lineBows(cameraOf(pb.q0, source_size, target_size), lines);

  out.model = LineModel::Radial;
  const int quadratic_needs = 9;  // 17 entries less the 8 a homography would take
  const auto summarise = [&](const Solved& s) {
    out.camera = cameraOf(s.q, source_size, target_size);
    out.bows = lineBows(out.camera, lines);
    bowTotals(out.bows, lines, out.rms_bow_px, out.max_bow_px);
    out.iterations = s.iterations;
    out.undetermined = s.undetermined;
  };
  summarise(radial);
  const double radial_rms = out.rms_bow_px;
  if (options.model == LineModel::Quadratic && information < quadratic_needs) {
    const int more = quadratic_needs - information;
    out.status = Status::failure(
        std::to_string(pb.lines.size()) + " line" + (pb.lines.size() == 1 ? "" : "s") +
        " give " + std::to_string(information) +
        " equations beyond their own positions; the quadratic needs " +
        std::to_string(quadratic_needs) + " (" + std::to_string(more) + " more point" +
        (more == 1 ? "" : "s") + " along the lines would determine it)");
    return out;
  }
  if (options.model != LineModel::Radial && information >= quadratic_needs) {
    const Solved quadratic = solve(quadraticFrom(pb, radial.q, !enabled_pairs.empty()), options);
    LinesFitSummary radial_out = out;
    summarise(quadratic);
    const double quadratic_rms = out.rms_bow_px;
    const auto clearlyBelow = [&](double candidate, double reference) {
      return candidate < options.auto_improvement * reference &&
             reference - candidate >= options.auto_min_gain_px;
    };
    const bool better = clearlyBelow(quadratic_rms, radial_rms);
    // Why auto keeps the radial lens; empty while the quadratic passes every check, each check
    // run only when the cheaper ones before it passed.
    std::string refusal;
    const bool auto_lines_only = options.model == LineModel::Auto && enabled_pairs.empty();
    if (auto_lines_only && !(better && quadratic.undetermined == 0))
      refusal = "the quadratic's RMS bow " + threeFigures(quadratic_rms) +
                " px is not clearly below its " + threeFigures(radial_rms) + " px" +
                (quadratic.undetermined
                     ? " and the lines leave " + std::to_string(quadratic.undetermined) +
                           " of its directions free"
                     : "");
    if (auto_lines_only && refusal.empty()) {
      const HeldOut held =
          heldOutBows(pb, enabled_traces, quadratic_needs, source_size, target_size, options);
      if (!held.possible)
        refusal = "with a line left out the quadratic is not determined, so no line can check it";
      else if (!clearlyBelow(held.quadratic_rms_px, held.radial_rms_px))
        refusal = "on held-out lines (each fitted from the others) the quadratic's RMS bow " +
                  threeFigures(held.quadratic_rms_px) + " px is not clearly below its " +
                  threeFigures(held.radial_rms_px) + " px";
    }
    if (auto_lines_only && refusal.empty()) {
      const double spacing = spacingChange(out.camera, radial_out.camera);
      const double empty_gain = frameCoverage(radial_out.camera) - frameCoverage(out.camera);
      if (!(spacing <= options.auto_max_spacing_change))
        refusal = "the quadratic would change the spacing along rows or columns by " +
                  percent(spacing) + " against it (a keystone or stretch the lines cannot see)";
      else if (!(empty_gain <= options.auto_max_empty_gain))
        refusal = "the quadratic would leave " + percent(empty_gain) + " more of the frame empty";
    }
    if (options.model == LineModel::Quadratic) {
      out.model = LineModel::Quadratic;
      out.reason = "quadratic as asked";
    } else if (!enabled_pairs.empty()) {
      out.model = LineModel::Quadratic;
      out.reason = "quadratic: pairs were given and a radial lens has no freedom to meet them";
    } else if (refusal.empty()) {
      out.model = LineModel::Quadratic;
      out.reason = "auto chose quadratic: RMS bow " + threeFigures(quadratic_rms) +
                   " px against the radial lens's " + threeFigures(radial_rms) +
                   " px, on held-out lines too, with the radial lens's spacing";
    } else {
      out = radial_out;
      out.reason = "auto chose radial (k " + threeFigures(out.radial_k) + "): " + refusal;
    }
  } else if (options.model == LineModel::Radial) {
    out.reason = "radial as asked (k " + threeFigures(out.radial_k) + ")";
  } else {
    out.reason = "auto chose radial (k " + threeFigures(out.radial_k) +
                 "): " + std::to_string(information) +
                 " equations beyond the lines' positions, the quadratic needs " +
                 std::to_string(quadratic_needs);
  }
  for (const PointMatch* m : enabled_pairs) {
    const auto y = targetPixelFromSourcePixel(out.camera, m->source.head<2>());
    out.pair_residuals_px.push_back(y ? (*y - m->target.head<2>()).norm()
                                      : std::numeric_limits<double>::infinity());
  }
  const PoleCheck poles = checkPoles(out.camera);
  if (!poles.pole_free) {
    out.status = Status::failure("the straightened camera would have a pole in the frame (" +
                                 poles.describe() + ")");
    return out;
  }
  out.status = Status();
  return out;
}

FitRecord LinesFitSummary::record() const {
  FitRecord r;
  r.model = std::string(lineModelName(model));
  r.matches = static_cast<int>(pair_residuals_px.size());
  r.residuals_px = pair_residuals_px;
  double sum = 0.0;
  for (double e : pair_residuals_px) {
    sum += e * e;
    r.max_px = std::max(r.max_px, e);
  }
  r.rms_px = pair_residuals_px.empty() ? 0.0 : std::sqrt(sum / pair_residuals_px.size());
  r.reason = "from " + std::to_string(bows.size()) + " straight lines (RMS bow " +
             threeFigures(rms_bow_px) + " px, max " + threeFigures(max_bow_px) + " px); " + reason;
  const PoleCheck poles = checkPoles(camera);
  r.pole_checked = poles.checked;
  r.pole_free = poles.pole_free;
  r.pole_margin = poles.margin;
  return r;
}

std::string LinesFitSummary::report() const {
  if (!status) return status.message;
  int points = 0;
  double before = 0.0;
  for (const LineBow& b : bows) points += b.points;
  for (const LineBow& b : bows_before) before = std::max(before, b.max_px);
  std::ostringstream s;
  s << lineModelName(model) << " from " << bows.size() << " line" << (bows.size() == 1 ? "" : "s")
    << " (" << points << " points): bow RMS " << threeFigures(rms_bow_px) << " px, max "
    << threeFigures(max_bow_px) << " px (before: max " << threeFigures(before) << " px)";
  if (!pair_residuals_px.empty()) {
    const FitRecord r = record();
    s << "; " << pair_residuals_px.size() << " pairs RMS " << threeFigures(r.rms_px) << " px, max "
      << threeFigures(r.max_px) << " px";
  }
  return s.str();
}

}  // namespace artcam
