// SPDX-License-Identifier: Apache-2.0
#include "ui/background_job.h"

#include <QCoreApplication>
#include <QRunnable>
#include <QThread>
#include <QThreadPool>

#include <algorithm>
#include <cmath>
#include <set>

namespace artcam::ui {

struct JobContext::Shared {
  std::atomic<bool> cancel{false};
  std::atomic<int> percent{-1};
};

namespace {

std::set<BackgroundJob*>& liveJobs() {  // GUI thread only
  static std::set<BackgroundJob*> jobs;
  return jobs;
}

// The studio's own pool (not the global one core or Qt may use): loads, fits and exports run
// side by side, at most a few at a time, at low priority so previews stay ahead of them.
QThreadPool& jobPool() {
  static QThreadPool* pool = [] {
    auto* p = new QThreadPool;
    p->setMaxThreadCount(std::max(2, QThread::idealThreadCount()));
    p->setThreadPriority(QThread::LowPriority);
    qAddPostRoutine(&BackgroundJob::cancelAllAndWait);
    return p;
  }();
  return *pool;
}

}  // namespace

bool JobContext::cancelled() const { return shared_->cancel.load(); }

void JobContext::setProgress(double fraction) {
  const int percent = static_cast<int>(std::floor(std::clamp(fraction, 0.0, 1.0) * 100.0));
  if (shared_->percent.exchange(percent) == percent) return;
  BackgroundJob* job = job_;
  QMetaObject::invokeMethod(
      job, [job, percent] { emit job->progressChanged(percent); }, Qt::QueuedConnection);
}

BackgroundJob::BackgroundJob(QObject* receiver)
    : QObject(nullptr), shared_(std::make_shared<JobContext::Shared>()) {
  if (receiver) connect(receiver, &QObject::destroyed, this, &BackgroundJob::cancel);
  liveJobs().insert(this);
}

BackgroundJob::~BackgroundJob() { liveJobs().erase(this); }

void BackgroundJob::cancel() { shared_->cancel = true; }

bool BackgroundJob::isCancelled() const { return shared_->cancel.load(); }

int BackgroundJob::runningCount() { return static_cast<int>(liveJobs().size()); }

QString BackgroundJob::oneLine(const char* message) {
  QString line = QString::fromUtf8(message ? message : "").section('\n', 0, 0).trimmed();
  if (line.size() > 300) line = line.left(297) + QStringLiteral("...");
  return line.isEmpty() ? QStringLiteral("unknown error") : line;
}

BackgroundJob* BackgroundJob::start(QObject* receiver, std::function<void(JobContext&)> work) {
  auto* job = new BackgroundJob(receiver);
  JobContext context(job, job->shared_);
  jobPool().start(QRunnable::create([job, context, work = std::move(work)]() mutable {
    work(context);  // never throws: runInBackground's boundary is inside
    QMetaObject::invokeMethod(job, &BackgroundJob::deliver, Qt::QueuedConnection);
  }));
  return job;
}

void BackgroundJob::deliver() {
  emit workEnded();
  deleteLater();
}

void BackgroundJob::cancelAllAndWait() {
  for (BackgroundJob* job : liveJobs()) job->cancel();
  jobPool().waitForDone();
}

}  // namespace artcam::ui
