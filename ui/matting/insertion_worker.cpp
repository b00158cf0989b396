// SPDX-License-Identifier: Apache-2.0
#include "ui/matting/insertion_worker.h"

#include "core/model/camera.h"
#include "core/piecewise/piecewise_render.h"
#include "core/pipeline/render.h"
#include "ui/image_convert.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>

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
  return true;
}

}  // namespace

InsertionWorker::InsertionWorker(QObject* parent) : QThread(parent) {
  qRegisterMetaType<artcam::ui::InsertionFit>();
}

InsertionWorker::~InsertionWorker() { shutdown(); }

void InsertionWorker::request(InsertionRequest request) { slot_.put(std::move(request), *this); }

void InsertionWorker::shutdown() { slot_.shutdown(*this); }

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

void InsertionWorker::limitToPolygon(ImageF& image, const std::vector<Eigen::Vector2d>& polygon) {
  if (polygon.size() < 3) return;
  std::vector<double> crossings;
  for (int y = 0; y < image.height; ++y) {
    const double yc = y + 0.5;
    crossings.clear();
    for (size_t i = 0; i < polygon.size(); ++i) {
      const Eigen::Vector2d& a = polygon[i];
      const Eigen::Vector2d& b = polygon[(i + 1) % polygon.size()];
      if ((a.y() <= yc) != (b.y() <= yc))
        crossings.push_back(a.x() + (yc - a.y()) / (b.y() - a.y()) * (b.x() - a.x()));
    }
    std::sort(crossings.begin(), crossings.end());
    // Pixel x is inside when its centre lies between an odd crossing and the next one.
    size_t k = 0;
    bool inside = false;
    for (int x = 0; x < image.width; ++x) {
      const double xc = x + 0.5;
      while (k < crossings.size() && crossings[k] <= xc) {
        inside = !inside;
        ++k;
      }
      if (!inside) std::fill_n(image.pixel(x, y), image.channels, 0.0f);
    }
  }
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
                                  const GraphicPlacement& placement) {
  const FrameSize size{photo.width, photo.height};
  // Through core's render front door, on the photo's size (the output-frame rule scales the
  // camera's target frame to it).
  Artcam lens(camera.patches.front().camera);
  lens.pieces = camera;
  RenderOptions options;
  options.warp.width = size.width;
  options.warp.height = size.height;
  ImageF top = placement.fillsBoard()
                   ? render(RenderInputs::of(graphic), lens, options)
                   : render(RenderInputs::of(placeGraphic(graphic, camera.source_size, placement)),
                            lens, options);
  if (region.size() >= 3 && size != camera.target_size) {
    // The region is in full-resolution photo pixels.
    const double sx = double(size.width) / camera.target_size.width;
    const double sy = double(size.height) / camera.target_size.height;
    std::vector<Eigen::Vector2d> scaled;
    for (const Eigen::Vector2d& p : region) scaled.emplace_back(p.x() * sx, p.y() * sy);
    limitToPolygon(top, scaled);
  } else {
    limitToPolygon(top, region);
  }
  ImageF out = photo;
  compositeOver(top, out);
  return out;
}

void InsertionWorker::run() {
  for (;;) {
    std::optional<InsertionRequest> next = slot_.take();
    if (!next) return;
    InsertionRequest job = std::move(*next);
    try {
      if (!last_fit_inputs_ || !sameFitInputs(*last_fit_inputs_, job)) {
        const auto start = std::chrono::steady_clock::now();
        const PiecewiseSummary summary =
            fitPiecewise(job.matches, job.board_size, job.photo_size, job.options);
        last_fit_ = describe(summary);
        last_fit_.fit_ms =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                .count();
        InsertionRequest inputs;
        inputs.matches = job.matches;
        inputs.board_size = job.board_size;
        inputs.photo_size = job.photo_size;
        inputs.options = job.options;
        last_fit_inputs_ = std::move(inputs);
      }
      if (!keepGoing()) continue;  // a newer request: it may reuse this fit
      emit fitted(last_fit_, job.generation);
      if (!last_fit_.ok || !job.photo || !job.graphic || job.photo->empty() || job.graphic->empty())
        continue;
      const ImageF out =
          composite(*job.photo, *job.graphic, *last_fit_.camera, job.region, job.placement);
      if (!keepGoing()) continue;
      const QImage image = qimageFromLinear(out);
      if (!keepGoing()) continue;
      emit rendered(image, job.generation);
    } catch (const std::exception& e) {
      emit failed(QString::fromUtf8(e.what()), job.generation);
    } catch (...) {
      emit failed(QStringLiteral("unknown error in the insertion worker"), job.generation);
    }
  }
}

}  // namespace artcam::ui
