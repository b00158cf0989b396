// SPDX-License-Identifier: Apache-2.0
#include "ui/colour/colour_fit_job.h"

#include <string>

namespace artcam::ui {

ColourFitJob::ColourFitJob(QObject* parent) : QObject(parent) {}

ColourFitJob::~ColourFitJob() {
  if (job_) job_->cancel();
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
  running_ = true;
  const quint64 tag = request.tag;
  job_ = runInBackground(
      this,
      [r = std::move(request)](JobContext&) { return fitColourSamples(r.samples, r.options); },
      [this, tag](JobOutcome<ColourFitSummary> outcome) {
        ColourFitSummary summary;
        if (outcome.value)
          summary = std::move(*outcome.value);
        else
          summary.status = Status::failure("Colour fit failed: " + outcome.error.toStdString());
        onDone(summary, tag);
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
