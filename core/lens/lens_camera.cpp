// SPDX-License-Identifier: Apache-2.0
#include "core/lens/lens_camera.h"

#include "core/effects/chromatic.h"
#include "core/fit/fit_image.h"
#include "core/piecewise/piecewise_fit.h"

#include <lensfun/lensfun.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <optional>

namespace artcam {

namespace {

// Samples of lensfun's map: for each target pixel of a grid, where lensfun reads the source,
// per channel (one entry when there is no TCA).
struct MapSamples {
  std::vector<Eigen::Vector2d> target;
  std::vector<std::array<Eigen::Vector2d, 3>> source;  // red, green, blue (all equal: no TCA)
  // The largest source distance between grid neighbours (green): how sparse the samples get
  // where the map magnifies.
  double max_source_spacing_px = 0.0;
};

// Pixel centres from 0.5 to size - 0.5, about `n` along the longer side. The count is odd so
// the frame's centre lines are sampled: a symmetric barrel's correction reads furthest out at
// the middle of each edge, and a grid that missed it would leave the patches a sliver short.
std::vector<double> axis(int size, int n, int longer) {
  const int count =
      std::max(3, 2 * static_cast<int>(std::lround(0.5 * double(n) * size / longer)) + 1);
  std::vector<double> out;
  for (int k = 0; k < count; ++k) out.push_back(0.5 + (size - 1.0) * k / (count - 1));
  return out;
}

class LensfunMap {
 public:
  LensfunMap(const lfLens* lens, const LensCameraOptions& o, double crop, bool tca)
      : modifier_(lens, static_cast<float>(crop), o.size.width, o.size.height) {
    int flags = LF_MODIFY_DISTORTION | LF_MODIFY_GEOMETRY;
    if (tca) flags |= LF_MODIFY_TCA;
    // Aperture and distance matter only for vignetting, which VignettingMap samples.
    applied_ = modifier_.Initialize(lens, LF_PF_F32, static_cast<float>(o.focal_mm), 8.0f,
                                    1000.0f, 1.0f, LF_RECTILINEAR, flags, o.distort);
  }
  int applied() const { return applied_; }

  MapSamples sample(FrameSize size, int n) const {
    const int longer = std::max(size.width, size.height);
    const std::vector<double> xs = axis(size.width, n, longer), ys = axis(size.height, n, longer);
    MapSamples out;
    const bool tca = applied_ & LF_MODIFY_TCA;
    // The green source of the row above and of the left neighbour; NaN where there was none.
    const Eigen::Vector2d none(std::nan(""), std::nan(""));
    std::vector<Eigen::Vector2d> above(xs.size(), none);
    for (double y : ys) {
      Eigen::Vector2d left = none;
      for (size_t col = 0; col < xs.size(); ++col) {
        const double x = xs[col];
        // artcam pixel centres are lensfun's integers + 0.5.
        const float xl = static_cast<float>(x - 0.5), yl = static_cast<float>(y - 0.5);
        std::array<Eigen::Vector2d, 3> src;
        bool ok = true;
        if (tca) {
          float r[6];
          ok = modifier_.ApplySubpixelGeometryDistortion(xl, yl, 1, 1, r);
          for (size_t c = 0; c < 3; ++c) src[c] = {r[2 * c] + 0.5, r[2 * c + 1] + 0.5};
        } else {
          float r[2];
          ok = modifier_.ApplyGeometryDistortion(xl, yl, 1, 1, r);
          src.fill(Eigen::Vector2d(r[0] + 0.5, r[1] + 0.5));
        }
        // A point with no preimage (beyond a fisheye's half sphere) comes back non-finite or
        // far away: it holds no picture, so it is no sample.
        for (const Eigen::Vector2d& p : src)
          ok = ok && p.allFinite() && std::abs(p.x()) < 10.0 * longer &&
               std::abs(p.y()) < 10.0 * longer;
        if (!ok) {
          left = above[col] = none;
          continue;
        }
        for (const Eigen::Vector2d& neighbour : {left, above[col]})
          if (neighbour.allFinite())
            out.max_source_spacing_px =
                std::max(out.max_source_spacing_px, (src[1] - neighbour).norm());
        left = above[col] = src[1];
        out.target.emplace_back(x, y);
        out.source.push_back(src);
      }
    }
    return out;
  }

 private:
  lfModifier modifier_;
  int applied_ = 0;
};

// lensfun's vignetting gain: its colour modifier run on one white pixel at a time, so the gain
// is read at any point (lensfun takes the pixel's coordinates as floats).
class VignettingMap {
 public:
  VignettingMap(const lfLens* lens, const LensCameraOptions& o, double crop)
      : modifier_(lens, static_cast<float>(crop), o.size.width, o.size.height) {
    applied_ =
        modifier_.Initialize(lens, LF_PF_F32, static_cast<float>(o.focal_mm),
                             static_cast<float>(o.aperture), static_cast<float>(o.distance_m), 1.0f,
                             LF_RECTILINEAR, LF_MODIFY_VIGNETTING, o.distort) &
        LF_MODIFY_VIGNETTING;
  }
  bool applied() const { return applied_ != 0; }
  // The gain at artcam pixel point p (lensfun's pixel centres are integers).
  double gain(const Eigen::Vector2d& p) const {
    alignas(16) float rgb[4] = {1.0f, 1.0f, 1.0f, 1.0f};
    modifier_.ApplyColorModification(rgb, static_cast<float>(p.x() - 0.5),
                                     static_cast<float>(p.y() - 0.5), 1, 1,
                                     LF_CR_3(RED, GREEN, BLUE), 3 * sizeof(float));
    return rgb[1];
  }
  // Gain samples for the camera: at each sample's source point, the gain at that point
  // (correcting) or at its target pixel (simulating). Sources outside the frame are left out.
  std::vector<GainSample> samples(const MapSamples& m, FrameSize size, bool distort) const {
    std::vector<GainSample> out;
    for (size_t i = 0; i < m.target.size(); ++i) {
      const Eigen::Vector2d& src = m.source[i][1];
      if (src.x() < 0 || src.y() < 0 || src.x() > size.width || src.y() > size.height) continue;
      out.push_back({src, gain(distort ? m.target[i] : src)});
    }
    return out;
  }

 private:
  lfModifier modifier_;
  int applied_ = 0;
};

// The samples of one channel whose source lies in the frame grown by `margin` px (negative: all).
std::vector<PointMatch> matchesOf(const MapSamples& s, int channel, double margin,
                                  FrameSize size) {
  std::vector<PointMatch> out;
  for (size_t i = 0; i < s.target.size(); ++i) {
    const Eigen::Vector2d& src = s.source[i][static_cast<size_t>(channel)];
    if (margin >= 0 && (src.x() < -margin || src.y() < -margin || src.x() > size.width + margin ||
                        src.y() > size.height + margin))
      continue;
    PointMatch m;
    m.source = src;
    m.target = s.target[i];
    out.push_back(std::move(m));
  }
  return out;
}

// Over the check points the camera maps; those it does not (a pole, outside every patch) are
// counted apart, so no figure is infinite and none hides them.
struct ErrorFigures {
  double rms = 0.0, max = 0.0;
  int count = 0;
  int unmapped = 0;
};

ErrorFigures figures(const std::vector<double>& residuals) {
  ErrorFigures f;
  double sum = 0.0;
  for (double r : residuals) {
    if (!std::isfinite(r)) {
      ++f.unmapped;
      continue;
    }
    sum += r * r;
    f.max = std::max(f.max, r);
    ++f.count;
  }
  f.rms = f.count ? std::sqrt(sum / f.count) : 0.0;
  return f;
}

ErrorFigures piecewiseFigures(const PiecewiseCamera& camera, const std::vector<PointMatch>& m) {
  std::vector<double> residuals;
  for (const PointMatch& p : m) {
    const auto t = camera.targetPixelFromSourcePixel(p.source);
    residuals.push_back(t ? (*t - Eigen::Vector2d(p.target)).norm()
                          : std::numeric_limits<double>::infinity());
  }
  return figures(residuals);
}

// A position-only camera's single stage as the position part of layer `channel`.
Camera tcaLayer(const Camera& position, int channel) {
  using namespace layout_pc;
  Stage stage;
  stage.q.assign(kN, Eigen::MatrixXd::Zero(kN, kN));
  for (int i = 0; i < 3; ++i)
    stage.q[static_cast<size_t>(i)].topLeftCorner(3, 3) =
        position.stages().front().q[static_cast<size_t>(i)];
  const auto unit = [](int i) { return Eigen::VectorXd::Unit(kN, i); };
  for (int k = 0; k < 3; ++k)
    if (k == channel) stage.q[static_cast<size_t>(kR + k)] = symmetricOuter(unit(kR + k), unit(kW));
  stage.q[kA] = symmetricOuter(unit(kA), unit(kW));
  return Camera({Block{BlockKind::Position, 3}, Block{BlockKind::Colour, 4}}, {stage},
                position.sourceSize(), position.targetSize());
}

std::string px(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.3g px", v);
  return b;
}

LensCameraSummary failure(LensCameraSummary s, std::string message) {
  s.status = Status::failure(std::move(message));
  return s;
}

}  // namespace

std::string LensCameraSummary::report() const {
  char head[160];
  std::snprintf(head, sizeof head, " at %g mm, crop %g", focal_mm, crop);
  std::string out = lens.model + head + "\n";
  if (piecewise)
    out += "piecewise camera: " + std::to_string(patches) + " patches, max " + px(max_px) +
           ", RMS " + px(rms_px) + " against lensfun over " + std::to_string(checked) +
           " points (the single camera's max was " + px(single_max_px) + ")";
  else
    out += "single camera: max " + px(max_px) + ", RMS " + px(rms_px) + " against lensfun over " +
           std::to_string(checked) + " points";
  if (unmapped > 0) out += "; " + std::to_string(unmapped) + " more have no image";
  out += within_tolerance ? "" : " (ABOVE the threshold)";
  if (tca) out += "\nTCA: three colour layers, worst channel max " + px(tca_max_px);
  if (vignetting) {
    char f[32];
    std::snprintf(f, sizeof f, "f/%g", aperture);
    out += std::string("\nvignetting at ") + f + ": gain " + vignetting_fit.report() +
           " against lensfun";
  }
  for (const std::string& n : notes) out += "\nnote: " + n;
  return out;
}

LensCameraSummary lensCamera(const LensDatabase& database, const LensCameraOptions& options) {
  LensCameraSummary s;
  if (!options.size.isImage()) return failure(s, "the photo size must be positive");
  if (!(options.focal_mm > 0) || !std::isfinite(options.focal_mm))
    return failure(s, "the focal length must be a positive number of millimetres");
  if (options.crop < 0 || !std::isfinite(options.crop))
    return failure(s, "the crop factor must be positive");
  const Result<LensEntry> entry = database.find(options.lens, options.crop);
  if (!entry) return failure(s, entry.status.message);
  s.lens = *entry;
  s.crop = options.crop > 0 ? options.crop : entry->crop_factor;
  s.focal_mm = options.focal_mm;
  const lfLens* lens = database.lens(entry->index);
  if (options.focal_mm < entry->min_focal_mm - 0.05 || options.focal_mm > entry->max_focal_mm + 0.05) {
    char range[96];
    std::snprintf(range, sizeof range, "%g mm is outside the lens's %g-%g mm", options.focal_mm,
                  entry->min_focal_mm, entry->max_focal_mm);
    return failure(s, entry->model + ": " + range);
  }
  const bool fisheye = lens->Type != LF_RECTILINEAR && lens->Type != LF_UNKNOWN;
  if (!entry->distortion && !fisheye)
    return failure(s, entry->model + ": the database has no distortion calibration for it, so "
                                     "its correction is the identity");

  const bool want_tca = options.tca && entry->tca;
  const LensfunMap map(lens, options, s.crop, want_tca);
  if (!(map.applied() & (LF_MODIFY_DISTORTION | LF_MODIFY_GEOMETRY)))
    return failure(s, entry->model + ": lensfun has no distortion model at " +
                          std::to_string(options.focal_mm) + " mm");
  const bool tca = (map.applied() & LF_MODIFY_TCA) != 0;
  if (options.aperture < 0 || !std::isfinite(options.aperture))
    return failure(s, "the aperture must be a positive f-number");
  if (!(options.distance_m > 0) || !std::isfinite(options.distance_m))
    return failure(s, "the focus distance must be a positive number of metres");
  s.aperture = options.aperture;
  const bool want_vignetting = options.vignetting && entry->vignetting;
  if (want_vignetting && !(options.aperture > 0))
    s.notes.push_back(
        "vignetting is in the database but not applied: give the aperture "
        "(the f-number the photo was taken at) to correct it");
  if (options.tca && entry->tca && !tca)
    s.notes.push_back("TCA is in the database but lensfun has none at this focal length");

  const FrameSize size = options.size;
  const MapSamples fit_samples = map.sample(size, options.fit_samples);
  const MapSamples check_samples = map.sample(size, options.check_samples);
  const int green = 1;
  const std::vector<PointMatch> fit_matches = matchesOf(fit_samples, green, -1, size);
  const std::vector<PointMatch> check_matches = matchesOf(check_samples, green, -1, size);
  if (fit_matches.size() < 16)
    return failure(s, entry->model + ": lensfun maps too few pixels of the frame");

  FitOptions fit_options;
  fit_options.model = ModelClass::Quadratic;
  fit_options.diagnostics = false;
  const FitSummary single = fitImageCamera(fit_matches, size, size, fit_options);
  if (single.status) {
    const ErrorFigures f = figures(reprojectionResiduals(single.camera, check_matches));
    s.single_rms_px = f.rms;
    s.single_max_px = f.max;
    s.rms_px = f.rms;
    s.max_px = f.max;
    s.checked = f.count;
    s.unmapped = f.unmapped;
  }
  s.within_tolerance = single.status && s.unmapped == 0 && s.single_max_px <= options.max_error_px;

  if (s.within_tolerance) {
    s.camera = Artcam(single.camera);
    s.camera.frame = CameraFrame::Sensor;  // the lens draws on the sensor, however it was held
    s.camera.matches = fit_matches;
    s.camera.fit = single.record;
    if (tca) {
      std::vector<Camera> layers;
      double worst = 0.0;
      for (int c = 0; c < 3; ++c) {
        const FitSummary layer =
            c == green ? single
                       : fitImageCamera(matchesOf(fit_samples, c, -1, size), size, size,
                                        fit_options);
        if (!layer.status) {
          layers.clear();
          break;
        }
        worst = std::max(worst, figures(reprojectionResiduals(
                                            layer.camera, matchesOf(check_samples, c, -1, size)))
                                    .max);
        layers.push_back(tcaLayer(layer.camera, c));
      }
      if (layers.size() == 3) {
        s.camera.layers = std::move(layers);
        s.tca = true;
        s.tca_max_px = worst;
        s.within_tolerance = worst <= options.max_error_px;
      } else {
        s.notes.push_back("TCA left out: a colour channel's camera could not be fitted");
      }
    }
    if (want_vignetting && options.aperture > 0) {
      const VignettingMap vignetting(lens, options, s.crop);
      if (!vignetting.applied()) {
        s.notes.push_back(
            "vignetting is in the database but lensfun has none at this focal "
            "length and aperture");
      } else {
        s.vignetting_fit =
            fitRadialGain(vignetting.samples(fit_samples, size, options.distort),
                          vignetting.samples(check_samples, size, options.distort), size);
        if (s.vignetting_fit.status) {
          for (Camera& layer : s.camera.layers)
            layer = withRadialGain(layer, s.vignetting_fit.gain);
          s.vignetting = true;
        } else {
          s.notes.push_back("vignetting left out: " + s.vignetting_fit.status.message);
        }
      }
    }
    s.status = Status::success();
    return s;
  }

  // Beyond one camera: patches over the source frame, fitted on a denser grid.
  // The patches tile the region the samples cover. lensfun's map reads furthest out between
  // grid lines (the middle of an edge for a barrel, off-centre for a moustache), so that
  // region stops short of the frame's edge by a fraction of a grid step, or passes it: samples
  // up to a step outside the frame are kept, and the outer edges of the tiling are then put on
  // the frame's edges, which is all a patch may cover and where the photo has pixels.
  const MapSamples dense = map.sample(size, 2 * options.fit_samples);
  const double step = std::max(size.width, size.height) / (2.0 * options.fit_samples);
  const std::vector<PointMatch> inside = matchesOf(dense, green, step, size);
  PiecewiseOptions piecewise_options;
  piecewise_options.max_error_px = options.max_error_px;
  // The fit snaps the tiling's outer edges within a step onto the frame's and clips it there
  // (piecewise_fit.h), the one rule of every fitting path.
  piecewise_options.outside_frame_px = step;
  piecewise_options.snap_to_frame_px = step;
  PiecewiseSummary pieces = fitPiecewise(inside, size, size, piecewise_options);
  if (!pieces.status)
    return failure(s, entry->model + ": no piecewise camera: " + pieces.status.message);
  if (pieces.patch_limited_depth >= 0)
    s.notes.push_back("the threshold cannot be met everywhere" +
                      patchLimitNote(pieces.patch_limited_depth));
  // The fit's margin, 1.5 median spacings, suits clicked matches spread evenly; lensfun's grid
  // is even in the target, so where the map magnifies (a fisheye's centre) its source samples
  // are further apart than that. Every point of the map is known, so the patches are trusted
  // over 1.5 of the largest spacing, and the check below measures them there.
  pieces.camera.support_margin_px =
      std::max(pieces.camera.support_margin_px, 1.5 * dense.max_source_spacing_px);
  const ErrorFigures f =
      piecewiseFigures(pieces.camera, matchesOf(check_samples, green, 0.0, size));
  s.piecewise = true;
  s.patches = static_cast<int>(pieces.camera.patches.size());
  s.rms_px = f.rms;
  s.max_px = f.max;
  s.checked = f.count;
  s.unmapped = f.unmapped;
  s.within_tolerance = f.unmapped == 0 && f.max <= options.max_error_px;
  s.camera = Artcam(single.status ? single.camera : pieces.camera.patches.front().camera);
  s.camera.frame = CameraFrame::Sensor;
  if (single.status) s.camera.fit = single.record;
  s.camera.matches = inside;
  s.camera.pieces = pieces.camera;
  if (tca)
    s.notes.push_back("TCA is in the database but left out: a piecewise camera cannot be layered");
  if (want_vignetting && options.aperture > 0)
    s.notes.push_back(
        "vignetting is in the database but left out: a piecewise camera's patches "
        "are position-only");
  s.status = Status::success();
  return s;
}

}  // namespace artcam
