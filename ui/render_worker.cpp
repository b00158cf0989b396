#include "ui/render_worker.h"

#include "core/render/warp.h"
#include "ui/image_convert.h"

#include <QMutexLocker>

#include <algorithm>
#include <exception>

namespace artcam::ui {

WarpOptions RenderWorker::passOptions(int width, int height) {
  WarpOptions options;
  options.width = width;
  options.height = height;
  // The preview shares the cores with the GUI; leave it one.
  options.threads = std::max(1, QThread::idealThreadCount() - 1);
  return options;
}

RenderWorker::RenderWorker(QObject* parent) : QThread(parent) {}

RenderWorker::~RenderWorker() { shutdown(); }

void RenderWorker::request(RenderRequest request) {
  QMutexLocker locker(&mutex_);
  pending_ = std::move(request);
  if (!isRunning()) {
    abort_ = false;
    start(QThread::LowPriority);
  } else {
    restart_ = true;
    condition_.wakeOne();
  }
}

void RenderWorker::shutdown() {
  {
    QMutexLocker locker(&mutex_);
    abort_ = true;
    pending_.reset();
    condition_.wakeOne();
  }
  wait();
}

void RenderWorker::run() {
  for (;;) {
    RenderRequest job;
    {
      QMutexLocker locker(&mutex_);
      while (!pending_ && !abort_) condition_.wait(&mutex_);
      if (abort_) return;
      job = std::move(*pending_);
      pending_.reset();
      restart_ = false;
    }
    try {
      if (!job.source || job.source->empty() || job.width <= 0 || job.height <= 0) continue;
      const bool coarse_worth_it = std::min(job.width, job.height) >= 8 * kCoarseFactor;
      for (int pass = coarse_worth_it ? 0 : 1; pass < 2 && keepGoing(); ++pass) {
        const bool final_pass = pass == 1;
        WarpOptions options = final_pass ? passOptions(job.width, job.height)
                                         : passOptions(std::max(1, job.width / kCoarseFactor),
                                                       std::max(1, job.height / kCoarseFactor));
        options.progress = [this](double) { return keepGoing(); };
        WarpSummary summary;
        const ImageF out = warpImage(*job.source, job.camera, options, &summary);
        if (summary.cancelled || !keepGoing()) break;
        const QImage image = qimageFromLinear(out);
        if (!keepGoing()) break;  // a newer request arrived while converting: drop this one
        emit rendered(image, job.generation, final_pass, summary.render_ms);
      }
    } catch (const std::exception& e) {
      emit failed(QString::fromUtf8(e.what()), job.generation);
    } catch (...) {
      emit failed(QStringLiteral("unknown error in the preview renderer"), job.generation);
    }
  }
}

}  // namespace artcam::ui
