// SPDX-License-Identifier: Apache-2.0
#include "core/lens/vignetting.h"

#include "core/model/frames.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

namespace artcam {

double RadialGain::operator()(const Eigen::Vector2d& source_px) const {
  const double s = t(source_px);
  return (numerator[0] + s * (numerator[1] + s * numerator[2])) /
         (1.0 + s * (denominator[0] + s * denominator[1]));
}

namespace {

// The largest t over the frame: at a corner.
double maxT(const RadialGain& g, FrameSize frame) {
  double out = 0.0;
  for (double x : {0.0, double(frame.width)})
    for (double y : {0.0, double(frame.height)}) out = std::max(out, g.t({x, y}));
  return out;
}

// The smallest of 1 + d1 t + d2 t² over [0, t_max]: at an end or at the vertex.
double minDenominator(const Eigen::Vector2d& d, double t_max) {
  const auto at = [&](double t) { return 1.0 + t * (d[0] + t * d[1]); };
  double m = std::min(at(0.0), at(t_max));
  if (d[1] != 0.0) {
    const double v = -d[0] / (2.0 * d[1]);
    if (v > 0.0 && v < t_max) m = std::min(m, at(v));
  }
  return m;
}

// The centre: g ≈ a0 + a1 t + a2 t² + a3 t³ with t from the centre, Gauss–Newton (damped) on
// (a, centre) from the frame's centre. A flat gain leaves the centre undetermined: the damping
// keeps it where it started.
Eigen::Vector2d fitCentre(const std::vector<GainSample>& samples, FrameSize frame, double radius) {
  Eigen::Vector2d c(0.5 * frame.width, 0.5 * frame.height);
  const int n = static_cast<int>(samples.size());
  double lambda = 1e-3;
  const auto residuals = [&](const Eigen::Vector2d& centre, Eigen::Vector4d& a) {
    Eigen::MatrixXd A(n, 4);
    Eigen::VectorXd b(n);
    for (int i = 0; i < n; ++i) {
      const double t = (samples[size_t(i)].source_px - centre).squaredNorm() / (radius * radius);
      A.row(i) << 1.0, t, t * t, t * t * t;
      b[i] = samples[size_t(i)].gain;
    }
    a = A.colPivHouseholderQr().solve(b);
    return (A * a - b).squaredNorm();
  };
  Eigen::Vector4d a;
  double cost = residuals(c, a);
  for (int iteration = 0; iteration < 30; ++iteration) {
    Eigen::MatrixXd J(n, 6);
    Eigen::VectorXd r(n);
    for (int i = 0; i < n; ++i) {
      const Eigen::Vector2d d = samples[size_t(i)].source_px - c;
      const double t = d.squaredNorm() / (radius * radius);
      const double dg_dt = a[1] + t * (2.0 * a[2] + t * 3.0 * a[3]);
      // The centre's step is in units of R: dt/dc = -2 d / R.
      J.row(i) << 1.0, t, t * t, t * t * t, -2.0 * dg_dt * d.x() / radius,
          -2.0 * dg_dt * d.y() / radius;
      r[i] = a[0] + t * (a[1] + t * (a[2] + t * a[3])) - samples[size_t(i)].gain;
    }
    Eigen::MatrixXd H = J.transpose() * J;
    const Eigen::VectorXd g = J.transpose() * r;
    bool improved = false;
    for (int tries = 0; tries < 10 && !improved; ++tries) {
      Eigen::MatrixXd damped = H;
      damped.diagonal() += lambda * (H.diagonal().array() + 1e-12).matrix();
      const Eigen::VectorXd step = damped.ldlt().solve(-g);
      const Eigen::Vector2d next = c + radius * step.tail<2>();
      Eigen::Vector4d a_next;
      const double next_cost = residuals(next, a_next);
      if (std::isfinite(next_cost) && next_cost < cost) {
        improved = (cost - next_cost) > 1e-15 * std::max(1.0, cost);
        c = next;
        a = a_next;
        cost = next_cost;
        lambda = std::max(1e-9, lambda / 10);
        if (!improved) return c;
      } else {
        lambda *= 10;
      }
    }
    if (!improved) break;
  }
  return c;
}

// The ratio of quadratics in t on the relative error, reweighted (Sanathanan–Koerner); with
// `rational` false the quadratic polynomial.
RadialGain fitRatio(const std::vector<GainSample>& samples, RadialGain g, bool rational) {
  const int n = static_cast<int>(samples.size());
  const int k = rational ? 5 : 3;
  std::vector<double> weight(size_t(n), 1.0);
  for (int iteration = 0; iteration < (rational ? 8 : 1); ++iteration) {
    Eigen::MatrixXd A(n, k);
    Eigen::VectorXd b(n);
    for (int i = 0; i < n; ++i) {
      const double t = g.t(samples[size_t(i)].source_px), v = samples[size_t(i)].gain;
      const double w = weight[size_t(i)] / v;  // relative error
      A(i, 0) = w;
      A(i, 1) = w * t;
      A(i, 2) = w * t * t;
      if (rational) {
        A(i, 3) = -w * v * t;
        A(i, 4) = -w * v * t * t;
      }
      b[i] = w * v;
    }
    Eigen::JacobiSVD<Eigen::MatrixXd> svd(A, Eigen::ComputeThinU | Eigen::ComputeThinV);
    svd.setThreshold(1e-10);  // a flat gain leaves the ratio free: the least-norm answer
    const Eigen::VectorXd x = svd.solve(b);
    g.numerator = x.head<3>();
    g.denominator = rational ? Eigen::Vector2d(x[3], x[4]) : Eigen::Vector2d::Zero();
    for (int i = 0; i < n; ++i) {
      const double t = g.t(samples[size_t(i)].source_px);
      weight[size_t(i)] =
          1.0 / std::max(1e-6, std::abs(1.0 + t * (g.denominator[0] + t * g.denominator[1])));
    }
  }
  return g;
}

void measure(GainFitSummary& s, const std::vector<GainSample>& check) {
  double sum = 0.0, worst = 0.0;
  for (const GainSample& c : check) {
    const double e = std::abs(s.gain(c.source_px) / c.gain - 1.0);
    sum += e * e;
    worst = std::max(worst, std::isfinite(e) ? e : std::numeric_limits<double>::infinity());
  }
  s.checked = static_cast<int>(check.size());
  s.rms_percent = check.empty() ? 0.0 : 100.0 * std::sqrt(sum / double(check.size()));
  s.max_percent = 100.0 * worst;
}

}  // namespace

std::string GainFitSummary::report() const {
  char b[200];
  std::snprintf(b, sizeof b, "max %.3g %%, RMS %.3g %% over %d points%s", max_percent, rms_percent,
                checked, rational ? "" : " (a quadratic in r²: the ratio had a pole)");
  return b;
}

GainFitSummary fitRadialGain(const std::vector<GainSample>& fit,
                             const std::vector<GainSample>& check, FrameSize frame) {
  GainFitSummary s;
  if (!frame.isImage()) {
    s.status = Status::failure("the frame has no size");
    return s;
  }
  if (fit.size() < 16) {
    s.status = Status::failure("too few gain samples to fit (" + std::to_string(fit.size()) + ")");
    return s;
  }
  for (const std::vector<GainSample>* set : {&fit, &check})
    for (const GainSample& g : *set)
      if (!(g.gain > 0.0) || !std::isfinite(g.gain) || !g.source_px.allFinite()) {
        s.status = Status::failure("a gain sample is not a positive finite number");
        return s;
      }
  RadialGain g;
  g.radius_px = 0.5 * std::hypot(double(frame.width), double(frame.height));
  g.centre_px = fitCentre(fit, frame, g.radius_px);
  if (!g.centre_px.allFinite() ||
      (g.centre_px - Eigen::Vector2d(0.5 * frame.width, 0.5 * frame.height)).norm() > g.radius_px)
    g.centre_px = {0.5 * frame.width, 0.5 * frame.height};  // a centre off the frame is no fit
  const double t_max = maxT(g, frame);
  s.gain = fitRatio(fit, g, true);
  if (!(minDenominator(s.gain.denominator, t_max) > 1e-3) || !s.gain.numerator.allFinite() ||
      !s.gain.denominator.allFinite()) {
    s.gain = fitRatio(fit, g, false);
    s.rational = false;
  }
  measure(s, check);
  s.status = Status::success();
  return s;
}

bool hasShading(const Camera& camera) { return camera.layout().find(BlockKind::Shading) >= 0; }

Camera withRadialGain(const Camera& camera, const RadialGain& gain) {
  const std::vector<Block>& in = camera.blocks();
  const bool position_only = in.size() == 1 && in[0] == Block{BlockKind::Position, 3};
  const bool with_colour = in.size() == 2 && in[0] == Block{BlockKind::Position, 3} &&
                           in[1] == Block{BlockKind::Colour, 4};
  if (!position_only && !with_colour)
    throw std::invalid_argument(
        "vignetting goes on a camera of [position 3] or [position 3 | "
        "colour 4] blocks");
  const std::vector<Block> blocks{
      {BlockKind::Position, 3}, {BlockKind::Colour, 4}, {BlockKind::Shading, 2}};
  constexpr int kW = 2, kR = 3, kA = 6, kS = 7, kSW = 8, kN = 9;
  const auto e = [](int i) { return Eigen::VectorXd::Unit(kN, i); };
  const Camera id = Camera::identity(blocks, camera.sourceSize(), camera.targetSize());

  // The camera's stages over the wider blocks: its tensors in place, colour passed on where it
  // had none, shading passed on.
  std::vector<Stage> stages;
  const int own = camera.dimension();
  for (const Stage& st : camera.stages()) {
    Stage s = id.stages()[0];
    for (int i = 0; i < own; ++i) {
      Eigen::MatrixXd q = Eigen::MatrixXd::Zero(kN, kN);
      q.topLeftCorner(own, own) = st.q[size_t(i)];
      s.q[size_t(i)] = std::move(q);
    }
    stages.push_back(std::move(s));
  }
  // 1. shading ← (t, 1) from the source position, t = |p − c|²/R² with p = P (u, v, 1)ᵀ.
  const Eigen::Matrix3d P = pixelFromNormalizedMatrix(camera.sourceSize());
  Eigen::Matrix<double, 2, 3> L;
  L.row(0) = (P.row(0) - gain.centre_px.x() * P.row(2)) / gain.radius_px;
  L.row(1) = (P.row(1) - gain.centre_px.y() * P.row(2)) / gain.radius_px;
  Eigen::MatrixXd qt = Eigen::MatrixXd::Zero(kN, kN);
  qt.topLeftCorner(3, 3) = L.transpose() * L;
  stages.front().q[kS] = qt;
  stages.front().q[kSW] = symmetricOuter(e(kW), e(kW));
  // 2. shading ← (N(s), D(s)).
  Stage ratio = id.stages()[0];
  const auto quadratic = [&](double c0, double c1, double c2) {
    return Eigen::MatrixXd(c0 * symmetricOuter(e(kSW), e(kSW)) +
                           c1 * symmetricOuter(e(kS), e(kSW)) + c2 * symmetricOuter(e(kS), e(kS)));
  };
  ratio.q[kS] = quadratic(gain.numerator[0], gain.numerator[1], gain.numerator[2]);
  ratio.q[kSW] = quadratic(1.0, gain.denominator[0], gain.denominator[1]);
  stages.push_back(std::move(ratio));
  // 3. colour ← s · colour, alpha kept.
  Stage apply = id.stages()[0];
  for (int k = 0; k < 3; ++k) apply.q[size_t(kR + k)] = symmetricOuter(e(kR + k), e(kS));
  apply.q[kA] = symmetricOuter(e(kA), e(kW));
  stages.push_back(std::move(apply));
  Camera out(blocks, std::move(stages), camera.sourceSize(), camera.targetSize());
  out.validate();
  return out;
}

FlatFieldSummary fitFlatField(const ImageF& flat, const FlatFieldOptions& options) {
  FlatFieldSummary out;
  const FrameSize frame{flat.width, flat.height};
  if (!frame.isImage() || flat.channels < 1) {
    out.fit.status = Status::failure("the flat field has no pixels");
    return out;
  }
  const int longer = std::max(flat.width, flat.height);
  const int cells = std::clamp(options.cells, 4, 512);
  const int nx = std::max(2, static_cast<int>(std::lround(double(cells) * flat.width / longer)));
  const int ny = std::max(2, static_cast<int>(std::lround(double(cells) * flat.height / longer)));
  if (flat.width < nx || flat.height < ny) {
    out.fit.status = Status::failure("the flat field is smaller than its " + std::to_string(nx) +
                                     "×" + std::to_string(ny) + " cells");
    return out;
  }
  // Each cell's mean level over the colour channels (alpha left out: a flat field is opaque).
  struct Cell {
    Eigen::Vector2d centre;
    double level;
  };
  std::vector<Cell> grid;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int x0 = i * flat.width / nx, x1 = (i + 1) * flat.width / nx;
      const int y0 = j * flat.height / ny, y1 = (j + 1) * flat.height / ny;
      double sum = 0.0;
      long long count = 0;
      for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) {
          const float* p = flat.pixel(x, y);
          for (int c = 0; c < flat.channels; ++c)
            if (c != flat.alpha_channel) {
              sum += p[c];
              ++count;
            }
        }
      const double level = count ? sum / double(count) : 0.0;
      if (!(level > 0.0) || !std::isfinite(level)) {
        out.fit.status = Status::failure("the flat field is black or not finite near pixel (" +
                                         std::to_string(x0) + ", " + std::to_string(y0) +
                                         "): no gain can make it flat");
        return out;
      }
      grid.push_back({{0.5 * (x0 + x1), 0.5 * (y0 + y1)}, level});
    }
  // The reference: the brightest of the cells nearest the frame's centre (a lens is brightest
  // on its axis; a shifted axis is what the fit's centre is for).
  const Eigen::Vector2d middle(0.5 * flat.width, 0.5 * flat.height);
  double reference = 0.0, darkest = std::numeric_limits<double>::infinity();
  const double near = 1.5 * std::max(double(flat.width) / nx, double(flat.height) / ny);
  for (const Cell& c : grid) {
    if ((c.centre - middle).norm() <= near) reference = std::max(reference, c.level);
    darkest = std::min(darkest, c.level);
  }
  std::vector<GainSample> samples;
  for (const Cell& c : grid) samples.push_back({c.centre, reference / c.level});
  out.fit = fitRadialGain(samples, samples, frame);
  if (!out.fit.status) return out;
  // 1 at the lens's axis, as lensfun's model is.
  const double at_centre = out.fit.gain(out.fit.gain.centre_px);
  out.fit.gain.numerator /= at_centre;
  for (GainSample& s : samples) s.gain /= at_centre;
  measure(out.fit, samples);
  out.darkest = darkest / reference * at_centre;
  out.camera =
      withRadialGain(Camera::identity({Block{BlockKind::Position, 3}}, frame, frame), out.fit.gain);
  return out;
}

}  // namespace artcam
