// SPDX-License-Identifier: Apache-2.0
#include "core/model/coverage.h"

#include "core/model/compiled_camera.h"
#include "core/model/frames.h"
#include "core/model/structure.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

namespace artcam {
namespace {

// Points per side: 49 (48 × 48 cells) for ordinary cameras. Each point costs one evaluation per
// stage, so a long chain gets a coarser lattice (about 2·10^5 stage evaluations in all, at least
// 5 × 5 points): a file of 3000 stages is checked in milliseconds, not seconds.
int latticeFor(size_t stages) {
  const double side = std::sqrt(2e5 / static_cast<double>(std::max<size_t>(stages, 1)));
  return static_cast<int>(std::clamp(side, 5.0, 49.0));
}

struct Sample {
  Eigen::Vector2d target = Eigen::Vector2d::Zero();  // normalised target position
  double weight = 0.0;                               // the position block's homogeneous element
  bool finite = false;
};

}  // namespace

Coverage measureCoverage(const Camera& camera) {
  const FrameSize s = camera.sourceSize();
  return measureCoverage(camera, Eigen::Vector2d::Zero(), Eigen::Vector2d(s.width, s.height));
}

Coverage measureCoverage(const Camera& camera, const Eigen::Vector2d& lo_px,
                         const Eigen::Vector2d& hi_px) {
  const int block = camera.layout().find(BlockKind::Position);
  if (block < 0 || camera.blocks()[static_cast<size_t>(block)].size != 3 || camera.stages().empty())
    return {};
  return measureCoverage(camera, analyseStructure(camera), lo_px, hi_px);
}

Coverage measureCoverage(const Camera& camera, const CameraStructure& structure) {
  const FrameSize s = camera.sourceSize();
  return measureCoverage(camera, structure, Eigen::Vector2d::Zero(), Eigen::Vector2d(s.width, s.height));
}

Coverage measureCoverage(const Camera& camera, const CameraStructure& structure,
                         const Eigen::Vector2d& lo_px, const Eigen::Vector2d& hi_px) {
  Coverage c;
  const FrameSize source = camera.sourceSize();
  const FrameSize target = camera.targetSize();
  const int block = camera.layout().find(BlockKind::Position);
  if (!source.isImage() || !target.isImage() || block < 0 ||
      camera.blocks()[static_cast<size_t>(block)].size != 3 || camera.stages().empty())
    return c;
  if (structure.geometry_depends_on_attributes) return c;
  c.checked = true;

  // Every block other than position gets a neutral value (mid grey, opaque; depth 1): only
  // used to evaluate the chain, since position does not depend on them here. Compiled, and
  // the last stage's position alone: Camera::evaluateHomogeneous allocates every product and
  // computes every output (per layer, three layers for chromatic aberration, on every
  // render).
  const CompiledCamera compiled(camera);
  const BlockLayout& layout = camera.layout();
  CompiledCamera::Vector x{}, z{};
  std::fill(x.begin(), x.begin() + layout.dimension, 0.5);
  for (size_t b = 0; b < layout.blocks.size(); ++b)
    x[static_cast<size_t>(layout.homogeneousIndex(static_cast<int>(b)))] = 1.0;
  const size_t offset = static_cast<size_t>(layout.offsets[static_cast<size_t>(block)]);
  const size_t weight_index = static_cast<size_t>(layout.homogeneousIndex(block));

  // A part of the frame (a patch) is sampled as densely as the whole frame is: points per side
  // in proportion to its larger share of the frame's sides. A piecewise camera's dozens of
  // patches then cost about one frame's check, not one each (the render checks every call).
  const double share = std::max((hi_px.x() - lo_px.x()) / source.width, (hi_px.y() - lo_px.y()) / source.height);
  const int whole = latticeFor(camera.stages().size());
  const int lattice = std::clamp(static_cast<int>(std::ceil(whole * std::min(1.0, share))), 5, whole);
  std::vector<Sample> samples(static_cast<size_t>(lattice * lattice));
  for (int j = 0; j < lattice; ++j)
    for (int i = 0; i < lattice; ++i) {
      const double t = static_cast<double>(i) / (lattice - 1);
      const double u = static_cast<double>(j) / (lattice - 1);
      const Eigen::Vector2d pixel = lo_px + Eigen::Vector2d(t, u).cwiseProduct(hi_px - lo_px);
      const Eigen::Vector2d n = normalizedFromPixel(source, pixel);
      x[offset] = n.x();
      x[offset + 1] = n.y();
      x[offset + 2] = 1.0;
      compiled.evaluateHomogeneous(x, z, /*position_only=*/true);
      Sample& sample = samples[static_cast<size_t>(j * lattice + i)];
      sample.weight = z[weight_index];
      if (std::isfinite(sample.weight) && sample.weight != 0.0) {
        sample.target = Eigen::Vector2d(z[offset], z[offset + 1]) / sample.weight;
        sample.finite = sample.target.allFinite();
      }
    }

  // The target frame in normalised coordinates: |u| ≤ w/s, |v| ≤ h/s with s = max(w, h)/2.
  const double half = 0.5 * std::max(target.width, target.height);
  const Eigen::Vector2d extent(0.5 * target.width / half, 0.5 * target.height / half);
  const double min_area = 1e-12 * 4.0 * extent.x() * extent.y();
  for (int j = 0; j + 1 < lattice; ++j)
    for (int i = 0; i + 1 < lattice; ++i) {
      const Sample* corner[4] = {&samples[static_cast<size_t>(j * lattice + i)],
                                 &samples[static_cast<size_t>(j * lattice + i + 1)],
                                 &samples[static_cast<size_t>((j + 1) * lattice + i + 1)],
                                 &samples[static_cast<size_t>((j + 1) * lattice + i)]};
      ++c.cells;
      bool positive = false, negative = false, finite = true;
      Eigen::Vector2d box_lo = Eigen::Vector2d::Constant(HUGE_VAL);
      Eigen::Vector2d box_hi = -box_lo;
      for (const Sample* k : corner) {
        positive = positive || k->weight > 0.0;
        negative = negative || k->weight < 0.0;
        finite = finite && k->finite;
        box_lo = box_lo.cwiseMin(k->target);
        box_hi = box_hi.cwiseMax(k->target);
      }
      // The mapped cell's bounding box meets the target frame: a strong zoom maps one cell over
      // the whole frame with every corner outside it.
      const bool lands = box_hi.x() >= -extent.x() && box_lo.x() <= extent.x() &&
                         box_hi.y() >= -extent.y() && box_lo.y() <= extent.y();
      if (positive && negative) {
        if (c.across_pole == 0) {
          const double t = (i + 0.5) / (lattice - 1), u = (j + 0.5) / (lattice - 1);
          c.pole_pixel = lo_px + Eigen::Vector2d(t, u).cwiseProduct(hi_px - lo_px);
        }
        ++c.across_pole;
        continue;
      }
      if (!finite) {
        ++c.non_finite;
        continue;
      }
      double area = 0.0;  // shoelace over the mapped quadrilateral
      for (int k = 0; k < 4; ++k) {
        const Eigen::Vector2d& a = corner[k]->target;
        const Eigen::Vector2d& b = corner[(k + 1) % 4]->target;
        area += a.x() * b.y() - a.y() * b.x();
      }
      if (!(std::abs(0.5 * area) > min_area)) {
        ++c.flat;
        continue;
      }
      if (lands) ++c.covering;
    }
  return c;
}

bool Coverage::missesTarget() const {
  return checked && covering == 0 && flat + non_finite + across_pole < cells;
}

Status Coverage::status() const {
  if (!checked || covering > 0 || missesTarget()) return Status::success();
  std::string cause;
  if (across_pole > 0 && flat + non_finite + across_pole == cells)
    cause = "its pole crosses the whole source frame and no part of it maps onto an area";
  else if (non_finite == cells)
    cause = "no point of the source frame maps to a finite position (its denominator is zero "
            "or its numbers overflow)";
  else
    cause = "it maps the whole source frame onto a line or a point";
  return Status::failure("the camera renders nothing: " + cause);
}

std::string Coverage::warning() const {
  if (missesTarget())
    return "the camera renders nothing inside the target frame: everything it maps lands outside "
           "it, so its pictures in these frames are fully transparent";
  if (!checked || covering == 0 || across_pole == 0) return {};
  char text[200];
  std::snprintf(text, sizeof text,
                "the camera's pole crosses the source frame near pixel (%.0f, %.0f): about %.0f %% "
                "of the frame maps nowhere and is left transparent",
                pole_pixel.x(), pole_pixel.y(),
                100.0 * static_cast<double>(across_pole + non_finite) / cells);
  return text;
}

}  // namespace artcam
