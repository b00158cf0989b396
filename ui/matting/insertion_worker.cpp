// SPDX-License-Identifier: Apache-2.0
#include "ui/matting/insertion_worker.h"

#include "core/model/camera.h"
#include "core/piecewise/piecewise_render.h"
#include "core/pipeline/insert_graphic.h"
#include "ui/image_convert.h"

#include <QCoreApplication>

#include <algorithm>
#include <chrono>
#include <cmath>

namespace artcam::ui {

namespace {

bool sameFitInputs(const InsertionRequest& a, const InsertionRequest& b) {
  if (a.board_size != b.board_size || a.photo_size != b.photo_size ||
      a.options.max_error_px != b.options.max_error_px || a.matches.size() != b.matches.size())
    return false;
  for (size_t i = 0; i < a.matches.size(); ++i)
    if (a.matches[i].source != b.matches[i].source || a.matches[i].target != b.matches[i].target ||
        a.matches[i].enabled != b.matches[i].enabled)
      return false;
  if (a.table_matches.size() != b.table_matches.size()) return false;
  for (size_t i = 0; i < a.table_matches.size(); ++i)
    if (a.table_matches[i].source != b.table_matches[i].source ||
        a.table_matches[i].target != b.table_matches[i].target)
      return false;
  return true;
}

// The table's homography (Fig 7b) from the request's table clicks, into `fit`.
void describeTable(const InsertionRequest& job, InsertionFit& fit) {
  if (job.table_matches.empty()) return;
  if (job.table_matches.size() < 4) {
    fit.table_report = QCoreApplication::translate("InsertionWorker",
                                                   "table: %n click(s); 4 fix its homography",
                                                   nullptr, int(job.table_matches.size()));
    return;
  }
  const FitSummary table = fitBoardHomography(job.table_matches, job.board_size, job.photo_size);
  if (!table.status) {
    fit.table_report = QCoreApplication::translate("InsertionWorker", "table: %1")
                           .arg(QString::fromStdString(table.status.message));
    return;
  }
  fit.table = std::make_shared<const Camera>(table.camera);
  fit.table_report = QCoreApplication::translate("InsertionWorker", "table: %1")
                         .arg(QString::fromStdString(table.report()));
}

}  // namespace

InsertionWorker::InsertionWorker(QObject* parent)
    : NewestRequestWorker(QStringLiteral("the insertion worker"), parent) {
  qRegisterMetaType<artcam::ui::InsertionFit>();
}

InsertionWorker::~InsertionWorker() { shutdown(); }

InsertionFit InsertionWorker::describe(const PiecewiseSummary& summary) {
  InsertionFit fit;
  fit.ok = summary.status.ok;
  fit.message = QString::fromStdString(summary.status.message);
  if (!fit.ok) return fit;
  fit.report = QString::fromStdString(summary.report());
  fit.matches = summary.matches;
  fit.patches = static_cast<int>(summary.camera.patches.size());
  fit.rms_px = summary.rms_px;
  fit.max_px = summary.max_px;
  fit.seam_gap_px = summary.seam_gap_px;
  fit.single_rms_px = summary.single_rms_px;
  fit.single_max_px = summary.single_max_px;
  fit.converged = summary.converged;
  fit.camera = std::make_shared<const PiecewiseCamera>(summary.camera);
  for (const CameraPatch& patch : summary.camera.patches) {
    // The support hull is where the patch's camera is trusted (its rectangle's corners may
    // lie where no match constrains it); outline it, densified, through the patch's camera.
    std::vector<Eigen::Vector2d> hull = patch.support;
    if (hull.size() < 3)
      hull = {{patch.rect.x0, patch.rect.y0},
              {patch.rect.x1, patch.rect.y0},
              {patch.rect.x1, patch.rect.y1},
              {patch.rect.x0, patch.rect.y1}};
    QPolygonF outline;
    constexpr int kSteps = 8;
    for (size_t i = 0; i < hull.size(); ++i) {
      const Eigen::Vector2d& a = hull[i];
      const Eigen::Vector2d& b = hull[(i + 1) % hull.size()];
      for (int s = 0; s < kSteps; ++s) {
        const auto p = targetPixelFromSourcePixel(patch.camera, a + (b - a) * (double(s) / kSteps));
        if (p) outline << QPointF(p->x(), p->y());
      }
    }
    fit.patch_outlines.push_back(outline);
    fit.patch_max_px.push_back(patch.max_px);
  }
  return fit;
}

PiecewiseCamera InsertionWorker::retarget(const PiecewiseCamera& camera, FrameSize target_size) {
  if (camera.target_size == target_size) return camera;
  PiecewiseCamera out = camera;
  out.target_size = target_size;
  for (CameraPatch& patch : out.patches) patch.camera.setFrames(out.source_size, target_size);
  return out;
}

ImageF InsertionWorker::composite(const ImageF& photo, const ImageF& graphic,
                                  const PiecewiseCamera& camera,
                                  const std::vector<Eigen::Vector2d>& region,
                                  const GraphicPlacement& placement, const Camera* table) {
  InsertionCameras cameras;
  cameras.object = camera;
  if (table) cameras.plane = *table;
  cameras.region = region;
  if (placement.fillsBoard()) return insertGraphic(photo, graphic, cameras);
  return insertGraphic(photo, placeGraphic(graphic, camera.source_size, placement), cameras);
}

ImageF InsertionWorker::compositeMedia(const ImageF& photo, const ImageF& graphic,
                                       const InsertionFit& fit,
                                       const std::vector<Eigen::Vector2d>& region,
                                       const GraphicPlacement& placement) {
  ImageF out = photo;
  const int count = static_cast<int>(fit.other_media.size()) + 1;
  for (int i = 0, other = 0; i < count; ++i) {
    if (i == fit.current_medium) {
      if (fit.ok && fit.camera)
        out = composite(out, graphic, *fit.camera, region, placement, fit.table.get());
      continue;
    }
    const InsertionFit::Medium& m = fit.other_media[static_cast<size_t>(other++)];
    if (m.ok && m.camera)
      out = composite(out, graphic, *m.camera, m.region, placement, m.table.get());
  }
  return out;
}

void InsertionWorker::serve(InsertionRequest& job) {
  if (!last_fit_inputs_ || !sameFitInputs(*last_fit_inputs_, job)) {
    // Forget the last fit first: should this one throw, the next request must fit afresh.
    last_fit_inputs_.reset();
    const auto start = std::chrono::steady_clock::now();
    if (job.matches.empty()) {  // a new medium, the others fitted
      last_fit_ = InsertionFit{};
      last_fit_.message =
          tr("No grid matches in this medium yet: import a grid CSV or click corners.");
    } else {
      last_fit_ = describe(fitPiecewise(job.matches, job.board_size, job.photo_size, job.options));
      if (last_fit_.ok) describeTable(job, last_fit_);
    }
    last_fit_.fit_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
            .count();
    InsertionRequest inputs;
    inputs.matches = job.matches;
    inputs.table_matches = job.table_matches;
    inputs.board_size = job.board_size;
    inputs.photo_size = job.photo_size;
    inputs.options = job.options;
    last_fit_inputs_ = std::move(inputs);
  }
  if (!keepGoing()) return;  // a newer request: it may reuse this fit
  // The other media: each its own fit, reused while its inputs stay.
  InsertionFit fit = last_fit_;
  fit.current_medium = job.current_medium;
  std::vector<std::pair<InsertionRequest, InsertionFit>> fits;
  for (const InsertionRequest::Medium& medium : job.other_media) {
    InsertionRequest inputs;
    inputs.matches = medium.matches;
    inputs.table_matches = medium.table_matches;
    inputs.board_size = job.board_size;
    inputs.photo_size = job.photo_size;
    inputs.options = job.options;
    const auto cached = std::find_if(other_fits_.begin(), other_fits_.end(),
                                     [&](const auto& f) { return sameFitInputs(f.first, inputs); });
    InsertionFit other;
    if (cached != other_fits_.end()) {
      other = cached->second;
    } else if (medium.matches.empty()) {
      other.message = tr("no grid matches");
    } else {
      other = describe(fitPiecewise(inputs.matches, job.board_size, job.photo_size, job.options));
      if (other.ok) describeTable(inputs, other);
    }
    fits.emplace_back(std::move(inputs), other);
    InsertionFit::Medium m;
    m.ok = other.ok;
    m.message = other.message;
    m.patches = other.patches;
    m.max_px = other.max_px;
    m.camera = other.camera;
    m.table = other.table;
    m.region = medium.region;
    fit.other_media.push_back(std::move(m));
    if (!keepGoing()) return;
  }
  other_fits_ = std::move(fits);
  emit fitted(fit, job.generation);
  if (!job.photo || !job.graphic || job.photo->empty() || job.graphic->empty()) return;
  if (!fit.rendersAny()) return;
  const ImageF out = compositeMedia(*job.photo, *job.graphic, fit, job.region, job.placement);
  if (!keepGoing()) return;
  const QImage image = qimageFromLinear(out);
  if (!keepGoing()) return;
  emit rendered(image, job.generation);
}

}  // namespace artcam::ui
