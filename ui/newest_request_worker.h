// SPDX-License-Identifier: Apache-2.0
// The studio's newest-request worker (after Qt's Mandelbrot example), in one place: a thread
// whose run() takes the newest request from a NewestRequestSlot (newest_request_slot.h, which
// keeps its std::mutex/condition_variable hand-over for ThreadSanitizer), hands it to the
// worker's job, and is the exception boundary. Whatever the job throws, std::exception or
// anything else, becomes a `failed` signal with a one-line message and the request's stamp, and
// the loop goes on to the next request: no job can end the thread silently (later requests
// would never be served) or let an exception out of run() (std::terminate, the studio gone).
//
// A worker derives from NewestRequestWorker<Request> (Request has a `quint64 generation`, the
// stamp its results carry), implements serve(), polls keepGoing() between tiles, and emits its
// own results. Its destructor must call shutdown() before its members go: the thread may be
// inside serve(), which uses them. Users: RenderWorker, CloudRenderWorker, InsertionWorker,
// FitWorker.
#pragma once

#include "ui/newest_request_slot.h"

#include <QString>
#include <QThread>

#include <exception>
#include <optional>
#include <utility>

namespace artcam::ui {

// The signal every newest-request worker shares (moc reads no templates, so it lives here).
class NewestRequestThread : public QThread {
  Q_OBJECT

 public:
  using QThread::QThread;

 signals:
  // The job of the request stamped `generation` threw; `message` says what (for an exception
  // not derived from std::exception, that one came from this worker). Later requests are
  // served as usual.
  void failed(const QString& message, quint64 generation);
};

template <class Request>
class NewestRequestWorker : public NewestRequestThread {
 public:
  // `what` names the worker in the message of an exception that carries none: "the preview
  // renderer" gives "unknown error in the preview renderer".
  explicit NewestRequestWorker(QString what, QObject* parent = nullptr)
      : NewestRequestThread(parent), what_(std::move(what)) {}
  // A worker that did not shut down in its own destructor is stopped here, which is only safe
  // while no job runs (see above).
  ~NewestRequestWorker() override { shutdown(); }

  // GUI thread: replaces the pending request; the job in flight sees keepGoing() turn false.
  void request(Request request) { slot_.put(std::move(request), *this); }
  // GUI thread: drops the pending request, stops the job in flight at its next poll and joins
  // the thread (idempotent).
  void shutdown() { slot_.shutdown(*this); }

 protected:
  // Worker thread: the job for the newest request. Returning ends it; so may any exception.
  virtual void serve(Request& request) = 0;
  // Worker thread, between tiles: false once a newer request or a shutdown arrived.
  bool keepGoing() const { return slot_.keepGoing(); }

 private:
  void run() final {
    for (;;) {
      std::optional<Request> next = slot_.take();
      if (!next) return;
      const quint64 generation = next->generation;
      // The boundary: catching here (and only here) keeps the thread serving whatever one job
      // does. Emitting queues a copy of the message, which cannot throw past this point in
      // practice; if it did, terminating is the honest outcome.
      try {
        serve(*next);
      } catch (const std::exception& e) {
        emit failed(QString::fromUtf8(e.what()), generation);
      } catch (...) {
        emit failed(QStringLiteral("unknown error in ") + what_, generation);
      }
    }
  }

  const QString what_;
  NewestRequestSlot<Request> slot_;
};

}  // namespace artcam::ui
