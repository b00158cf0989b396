// SPDX-License-Identifier: Apache-2.0
// The studio's one helper for one-shot off-thread jobs: loads, fits, writes, exports. (Live
// previews that a newer request supersedes use the other shape, the newest-request worker of
// newest_request_slot.h.)
//
//   runInBackground(receiver, [=](JobContext& job) { ...; return value; },
//                   [=](JobOutcome<T> outcome) { ... });
//
// The work runs on the studio's job pool, never on the GUI thread. Every exception it throws is
// caught here, in one place, and becomes a one-line message (JobOutcome::error). The outcome is
// handed to `done` on the receiver's thread by a queued call; when the receiver is destroyed
// first, the job is cancelled and `done` never runs. The work polls JobContext::cancelled()
// (core's progress hooks: `return job.progress(f);`) and reports progress, which arrives as
// BackgroundJob::progressChanged in whole percents.
//
// Nothing waits for a job on the GUI thread. At application exit (QCoreApplication's
// destructor) the running jobs are cancelled and waited for, so no job outlives the
// application it delivers to.
#pragma once

#include <QMetaObject>
#include <QObject>
#include <QPointer>
#include <QString>

#include <atomic>
#include <exception>
#include <functional>
#include <memory>
#include <optional>
#include <type_traits>
#include <utility>

namespace artcam::ui {

class BackgroundJob;

// What the running work sees (its own thread).
class JobContext {
 public:
  bool cancelled() const;
  // `fraction` of the work done, 0…1; reaches the GUI thread when the whole percent changes.
  void setProgress(double fraction);
  // Shaped for core's progress callbacks: reports, then returns whether to keep going.
  bool progress(double fraction) {
    setProgress(fraction);
    return !cancelled();
  }

 private:
  friend class BackgroundJob;
  struct Shared;
  JobContext(BackgroundJob* job, std::shared_ptr<Shared> shared)
      : job_(job), shared_(std::move(shared)) {}
  BackgroundJob* job_;  // alive until the job's delivery, which comes after all progress
  std::shared_ptr<Shared> shared_;
};

template <class T>
struct JobOutcome {
  std::optional<T> value;  // what the work returned (empty when it threw)
  QString error;           // one line: what the work threw (empty when it returned)
  bool cancelled = false;  // cancel() was called before the work ended
};

// The handle of one job, on the thread that started it. It deletes itself after the delivery:
// hold it in a QPointer.
class BackgroundJob : public QObject {
  Q_OBJECT

 public:
  // Any thread: the work sees cancelled() turn true (it stops at its next poll).
  void cancel();
  bool isCancelled() const;

  // The work, with the exception boundary; `deliver` runs later on this object's thread.
  // Use runInBackground rather than this.
  static BackgroundJob* start(QObject* receiver, std::function<void(JobContext&)> work);

  // At application exit only (installed as a QCoreApplication post routine): cancels every
  // job and waits for the pool.
  static void cancelAllAndWait();
  // Jobs started and not yet delivered (GUI thread).
  static int runningCount();

  // One line from an exception's message (the first line, at most 300 characters).
  static QString oneLine(const char* message);

 signals:
  void progressChanged(int percent);
  // Emitted on this object's thread after the work ended, before `done` runs; internal.
  void workEnded();

 private:
  explicit BackgroundJob(QObject* receiver);
  ~BackgroundJob() override;
  void deliver();

  std::shared_ptr<JobContext::Shared> shared_;
};

// Runs `work(JobContext&) -> T` off the GUI thread and `done(JobOutcome<T>)` on the receiver's
// thread (see the top of this file). T must not be void (return a Status or a bool).
template <class Work, class Done>
QPointer<BackgroundJob> runInBackground(QObject* receiver, Work work, Done done) {
  using T = std::decay_t<std::invoke_result_t<Work&, JobContext&>>;
  static_assert(!std::is_void_v<T>, "a background job returns its result");
  auto outcome = std::make_shared<JobOutcome<T>>();
  BackgroundJob* job = BackgroundJob::start(
      receiver, [outcome, work = std::move(work)](JobContext& context) mutable {
        // The one exception boundary of the studio's one-shot jobs.
        try {
          outcome->value.emplace(work(context));
        } catch (const std::exception& e) {
          outcome->error = BackgroundJob::oneLine(e.what());
        } catch (...) {
          outcome->error = QStringLiteral("unknown error");
        }
        outcome->cancelled = context.cancelled();
      });
  // The context object is the receiver: once it is destroyed, `done` is not called.
  QObject::connect(job, &BackgroundJob::workEnded, receiver,
                   [outcome, done = std::move(done)]() mutable { done(std::move(*outcome)); });
  return job;
}

}  // namespace artcam::ui
