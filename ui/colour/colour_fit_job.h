// Runs core's fitColourSamples off the GUI thread (the GUI thread never waits for a fit; the
// quadratic candidate with K-fold selection and MSAC can take a while on many samples). One
// fit at a time; a request made while one runs waits in a single slot where the newest wins.
// The summary comes back to the GUI thread by a queued call; no exception leaves the thread.
#pragma once

#include "core/fit/fit_colour.h"

#include <QObject>

#include <mutex>
#include <optional>
#include <thread>
#include <vector>

namespace artcam::ui {

class ColourFitJob : public QObject {
  Q_OBJECT

 public:
  explicit ColourFitJob(QObject* parent = nullptr);
  ~ColourFitJob() override;  // joins

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

  std::thread thread_;
  bool running_ = false;            // GUI thread only
  std::optional<Request> pending_;  // GUI thread only
};

}  // namespace artcam::ui
