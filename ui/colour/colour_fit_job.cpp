#include "ui/colour/colour_fit_job.h"

#include <QMetaObject>

#include <exception>

namespace artcam::ui {

ColourFitJob::ColourFitJob(QObject* parent) : QObject(parent) {}

ColourFitJob::~ColourFitJob() {
  if (thread_.joinable()) thread_.join();
}

void ColourFitJob::start(std::vector<PointMatch> samples, ColourFitOptions options, quint64 tag) {
  Request r{std::move(samples), options, tag};
  if (running_) {
    pending_ = std::move(r);
    return;
  }
  launch(std::move(r));
}

void ColourFitJob::launch(Request request) {
  if (thread_.joinable()) thread_.join();  // finished already: its result was delivered
  running_ = true;
  thread_ = std::thread([this, r = std::move(request)] {
    ColourFitSummary summary;
    try {
      summary = fitColourSamples(r.samples, r.options);
    } catch (const std::exception& e) {
      summary = ColourFitSummary{};
      summary.status = Status::failure(std::string("Colour fit failed: ") + e.what());
    } catch (...) {
      summary = ColourFitSummary{};
      summary.status = Status::failure("Colour fit failed: unknown error");
    }
    const quint64 tag = r.tag;
    QMetaObject::invokeMethod(
        this, [this, summary, tag] { onDone(summary, tag); }, Qt::QueuedConnection);
  });
}

void ColourFitJob::onDone(const ColourFitSummary& summary, quint64 tag) {
  running_ = false;
  if (pending_) {
    // A newer request is waiting: this result is stale, fit the newest instead.
    Request next = std::move(*pending_);
    pending_.reset();
    launch(std::move(next));
    return;
  }
  emit finished(summary, tag);
}

}  // namespace artcam::ui
