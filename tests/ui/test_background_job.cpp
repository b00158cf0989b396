// SPDX-License-Identifier: Apache-2.0
// The studio's one-shot job helper (ui/background_job.h): the work runs off the GUI thread and
// its value comes back on it; any exception in the work reaches the GUI as a one-line message,
// never as a crash; cancel() is seen by a polling job; progress arrives in order; a receiver
// destroyed first cancels the job and gets no call. Blocking is ruled out without timing: the
// jobs wait on semaphores the test releases.
#include "ui/background_job.h"

#include <QSemaphore>
#include <QSignalSpy>
#include <QThread>
#include <QtTest/QtTest>

#include <atomic>
#include <memory>
#include <optional>
#include <stdexcept>

using namespace artcam::ui;

class TestBackgroundJob : public QObject {
  Q_OBJECT

 private slots:
  void deliversTheValueOnTheGuiThread() {
    QObject receiver;
    auto gate = std::make_shared<QSemaphore>();
    std::optional<JobOutcome<int>> got;
    QThread* done_thread = nullptr;
    auto work_thread = std::make_shared<std::atomic<QThread*>>(nullptr);
    runInBackground(
        &receiver,
        [gate, work_thread](JobContext&) {
          *work_thread = QThread::currentThread();
          gate->acquire();  // held until the test has checked that start did not wait
          return 6 * 7;
        },
        [&](JobOutcome<int> outcome) {
          done_thread = QThread::currentThread();
          got = std::move(outcome);
        });
    QVERIFY(!got);  // runInBackground returned with the work still blocked
    gate->release();
    QTRY_VERIFY_WITH_TIMEOUT(got.has_value(), 20000);
    QVERIFY(got->value.has_value());
    QCOMPARE(*got->value, 42);
    QVERIFY(got->error.isEmpty());
    QVERIFY(!got->cancelled);
    QCOMPARE(done_thread, QThread::currentThread());
    QVERIFY(work_thread->load() != nullptr);
    QVERIFY(work_thread->load() != QThread::currentThread());
  }

  void anExceptionArrivesAsOneLine() {
    QObject receiver;
    std::optional<JobOutcome<int>> std_error, other_error;
    runInBackground(
        &receiver,
        [](JobContext&) -> int { throw std::runtime_error("disk on fire\nsecond line of detail"); },
        [&](JobOutcome<int> o) { std_error = std::move(o); });
    runInBackground(
        &receiver, [](JobContext&) -> int { throw 17; },
        [&](JobOutcome<int> o) { other_error = std::move(o); });
    QTRY_VERIFY_WITH_TIMEOUT(std_error.has_value() && other_error.has_value(), 20000);
    QVERIFY(!std_error->value);
    QCOMPARE(std_error->error, QStringLiteral("disk on fire"));
    QVERIFY(!other_error->value);
    QCOMPARE(other_error->error, QStringLiteral("unknown error"));
  }

  void cancelIsSeenByAPollingJob() {
    QObject receiver;
    auto started = std::make_shared<QSemaphore>();
    std::optional<JobOutcome<bool>> got;
    QPointer<BackgroundJob> job = runInBackground(
        &receiver,
        [started](JobContext& context) {
          started->release();
          // Stops only when cancelled (or after a minute, so a broken cancel fails, not hangs).
          for (int i = 0; i < 60000 && !context.cancelled(); ++i) QThread::msleep(1);
          return context.cancelled();
        },
        [&](JobOutcome<bool> o) { got = std::move(o); });
    QVERIFY(started->tryAcquire(1, 20000));
    QVERIFY(job);
    QVERIFY(!job->isCancelled());
    job->cancel();
    QTRY_VERIFY_WITH_TIMEOUT(got.has_value(), 20000);
    QVERIFY(got->cancelled);
    QVERIFY(got->value && *got->value);  // the work saw the flag
  }

  void progressArrivesInOrder() {
    QObject receiver;
    bool done = false;
    QPointer<BackgroundJob> job = runInBackground(
        &receiver,
        [](JobContext& context) {
          context.setProgress(0.25);
          context.setProgress(0.25);  // unchanged: not sent again
          context.setProgress(0.5);
          return context.progress(1.0);
        },
        [&](JobOutcome<bool> o) { done = o.value && *o.value; });
    QSignalSpy spy(job.data(), &BackgroundJob::progressChanged);
    QTRY_VERIFY_WITH_TIMEOUT(done, 20000);
    QCOMPARE(spy.count(), 3);
    QCOMPARE(spy.at(0).at(0).toInt(), 25);
    QCOMPARE(spy.at(1).at(0).toInt(), 50);
    QCOMPARE(spy.at(2).at(0).toInt(), 100);
  }

  void aDestroyedReceiverCancelsAndIsNotCalled() {
    const int before = BackgroundJob::runningCount();
    auto receiver = std::make_unique<QObject>();
    auto gate = std::make_shared<QSemaphore>();
    auto saw_cancel = std::make_shared<std::atomic<bool>>(false);
    bool called = false;
    runInBackground(
        receiver.get(),
        [gate, saw_cancel](JobContext& job) {
          gate->acquire();
          *saw_cancel = job.cancelled();
          return 1;
        },
        [&](JobOutcome<int>) { called = true; });
    QCOMPARE(BackgroundJob::runningCount(), before + 1);
    receiver.reset();
    gate->release();
    // The job delivers to nobody and deletes itself.
    QTRY_COMPARE_WITH_TIMEOUT(BackgroundJob::runningCount(), before, 20000);
    QVERIFY(saw_cancel->load());
    QVERIFY(!called);
  }
};

QTEST_MAIN(TestBackgroundJob)
#include "test_background_job.moc"
