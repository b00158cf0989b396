// SPDX-License-Identifier: Apache-2.0
// Fits the document's camera off the GUI thread for a drag's mouse moves: a newest-request
// worker (newest_request_worker.h, after Qt's Mandelbrot example). One thread; a request made
// while a fit runs replaces the pending one, so a fast drag fits only the newest pairs. A fit
// has no cancellation hook, so the running one finishes (a few ms) and its result is dropped
// by the document when a newer edit exists (revision stamps). Results come back by a queued
// call to the GUI thread. fitDocumentCamera turns the engine's exceptions into a failed fit;
// anything else that escapes a fit is the worker's `failed(message, revision)`, after which the
// next request is served.
#pragma once

#include "ui/document_fit.h"
#include "ui/newest_request_worker.h"

#include <functional>

namespace artcam::ui {

struct FitRequest {
  FitInputs inputs;
  quint64 generation = 0;  // the document's edit revision the inputs are
};

class FitWorker : public NewestRequestWorker<FitRequest> {
 public:
  using Delivery = std::function<void(FittedCamera fitted, quint64 revision)>;
  // `deliver` runs on the GUI thread (this object's thread) for every finished fit.
  explicit FitWorker(Delivery deliver, QObject* parent = nullptr);
  ~FitWorker() override;  // drops the pending request and joins (at shutdown only)

 protected:
  void serve(FitRequest& request) override;

 private:
  Delivery deliver_;
};

}  // namespace artcam::ui
