// SPDX-License-Identifier: Apache-2.0
#include "core/fit/robust.h"

#include "core/model/frames.h"

#include <algorithm>
#include <optional>
#include <string>
#include <utility>

namespace artcam {
namespace {

// The matches in the normalised frames, once: scoring runs over every match for every sample,
// and the generic per-point camera evaluation (dynamic vectors) dominated the search.
struct NormalisedMatches {
  std::vector<Eigen::Vector3d> src;  // (u, v, 1)
  std::vector<Eigen::Vector2d> dst;
  double target_pixels_per_unit = 1.0;
};

NormalisedMatches normalise(const std::vector<PointMatch>& matches, FrameSize source_size,
                            FrameSize target_size) {
  NormalisedMatches n;
  n.target_pixels_per_unit = std::max(target_size.width, target_size.height) / 2.0;
  for (const PointMatch& m : matches) {
    const Eigen::Vector2d s = normalizedFromPixel(source_size, m.source.head<2>());
    n.src.emplace_back(s.x(), s.y(), 1.0);
    n.dst.push_back(normalizedFromPixel(target_size, m.target.head<2>()));
  }
  return n;
}

MsacScore score(const Camera& camera, const NormalisedMatches& matches, double threshold) {
  MsacScore s;
  const double t2 = threshold * threshold;
  const Eigen::Matrix3d q0 = camera.stages()[0].q[0], q1 = camera.stages()[0].q[1],
                        q2 = camera.stages()[0].q[2];
  const double scale2 = matches.target_pixels_per_unit * matches.target_pixels_per_unit;
  for (size_t k = 0; k < matches.src.size(); ++k) {
    const Eigen::Vector3d& x = matches.src[k];
    const double w = x.dot(q2 * x);
    const Eigen::Vector2d y(x.dot(q0 * x) / w, x.dot(q1 * x) / w);
    s.add(static_cast<int>(k), (y - matches.dst[k]).squaredNorm() * scale2, t2);  // target px²
  }
  return s;
}

std::vector<PointMatch> pick(const std::vector<PointMatch>& matches, const std::vector<int>& idx) {
  std::vector<PointMatch> out;
  out.reserve(idx.size());
  for (int k : idx) out.push_back(matches[k]);
  return out;
}

}  // namespace

RobustResult findInliers(const std::vector<PointMatch>& matches, FrameSize source_size,
                         FrameSize target_size, ModelClass model, const RobustOptions& options) {
  RobustResult result;
  const ModelClass sampled = model == ModelClass::Auto ? ModelClass::Quadratic : model;
  const int sample_size = minimumMatches(sampled, 2);
  const int m = static_cast<int>(matches.size());
  if (m < sample_size) {
    result.status = Status::failure("robust fitting of the " + std::string(modelClassName(sampled)) +
                                    " model needs at least " + std::to_string(sample_size) +
                                    " matches, have " + std::to_string(m));
    return result;
  }
  FitOptions exact;
  exact.model = sampled;
  exact.refine = false;
  exact.require_pole_free = false;
  exact.diagnostics = false;

  const NormalisedMatches normalised = normalise(matches, source_size, target_size);
  // The minimal sets and the local optimisation's re-fits are the same exact fit.
  const auto fit = [&](const std::vector<int>& set) -> std::optional<MsacScore> {
    const FitSummary f = fitImageCamera(pick(matches, set), source_size, target_size, exact);
    if (!f.status) return std::nullopt;
    return score(f.camera, normalised, options.threshold_px);
  };
  MsacResult best = runMsac({m, sample_size, fit, fit}, options.search);
  result.iterations = best.iterations;
  if (static_cast<int>(best.inliers.size()) < sample_size) {
    result.status = Status::failure("no " + std::string(modelClassName(sampled)) +
                                    " explains more than " + std::to_string(best.inliers.size()) +
                                    " of the " + std::to_string(m) + " matches within " +
                                    std::to_string(options.threshold_px) + " px");
    return result;
  }
  result.inliers = std::move(best.inliers);
  return result;
}

}  // namespace artcam
