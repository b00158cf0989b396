// SPDX-License-Identifier: Apache-2.0
// Runs core's fitColourSamples off the GUI thread (the GUI never waits for a fit; the
// quadratic candidate with K-fold selection and MSAC can take a while on many samples), as a
// one-shot job of background_job.h. One fit at a time; a request made while one runs waits in
// a single slot where the newest wins. The summary comes back to the GUI thread; an exception
// in the fit becomes a failed summary naming it.
#pragma once

#include "core/fit/fit_colour.h"
#include "ui/background_job.h"

#include <QObject>
#include <QPointer>

#include <optional>
#include <vector>

namespace artcam::ui {

class ColourFitJob : public QObject {
  Q_OBJECT

 public:
  explicit ColourFitJob(QObject* parent = nullptr);
  ~ColourFitJob() override;  // drops the running fit's result; never waits for it

  // GUI thread. `tag` comes back with the result (e.g. the frame the map is for).
  void start(std::vector<PointMatch> samples, ColourFitOptions options, quint64 tag);
  bool isRunning() const { return running_; }

 signals:
  // GUI thread: the summary of the request stamped `tag`.
  void finished(const artcam::ColourFitSummary& summary, quint64 tag);

 private:
  struct Request {
    std::vector<PointMatch> samples;
    ColourFitOptions options;
    quint64 tag = 0;
  };
  void launch(Request request);
  void onDone(const ColourFitSummary& summary, quint64 tag);

  QPointer<BackgroundJob> job_;
  bool running_ = false;            // GUI thread only
  std::optional<Request> pending_;  // GUI thread only
};

}  // namespace artcam::ui
