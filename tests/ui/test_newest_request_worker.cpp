// SPDX-License-Identifier: Apache-2.0
// NewestRequestWorker's exception boundary (ui/newest_request_worker.h): a job that throws
// std::runtime_error and one that throws something not derived from std::exception are each
// reported by `failed` with their message and their request's stamp, and the same thread goes
// on serving the next request. The 3D view's renderer, one of the ported workers, does the
// same with an engine refusal: a request it cannot render is `failed`, the next one renders.
#include "core/cloud/sample_clouds.h"
#include "core/cameras/projective_cameras.h"
#include "core/effects/image_warps.h"
#include "ui/cloud_render_worker.h"
#include "ui/newest_request_worker.h"

#include <QSignalSpy>
#include <QtTest/QtTest>

#include <atomic>
#include <stdexcept>
#include <string>

using namespace artcam;
using namespace artcam::ui;

namespace {

struct Job {
  enum Kind { Serve, ThrowStd, ThrowOther };
  quint64 generation = 0;
  Kind kind = Serve;
};

// Not derived from std::exception: what a third-party library may throw.
struct Oddity {
  int code = 0;
};

class ThrowingWorker : public NewestRequestWorker<Job> {
  Q_OBJECT

 public:
  ThrowingWorker() : NewestRequestWorker(QStringLiteral("the test worker")) {}
  ~ThrowingWorker() override { shutdown(); }

  Qt::HANDLE servingThread() const { return serving_thread_.load(); }

 signals:
  void served(quint64 generation);

 protected:
  void serve(Job& job) override {
    serving_thread_ = QThread::currentThreadId();
    if (job.kind == Job::ThrowStd)
      throw std::runtime_error("request " + std::to_string(job.generation) + " is bad");
    if (job.kind == Job::ThrowOther) throw Oddity{7};
    emit served(job.generation);
  }

 private:
  std::atomic<Qt::HANDLE> serving_thread_{nullptr};
};

}  // namespace

class TestNewestRequestWorker : public QObject {
  Q_OBJECT

 private slots:
  void exceptionsAreReportedAndTheWorkerServesOn() {
    ThrowingWorker worker;
    QSignalSpy failed(&worker, &ThrowingWorker::failed);
    QSignalSpy served(&worker, &ThrowingWorker::served);

    worker.request({1, Job::ThrowStd});
    QTRY_COMPARE_WITH_TIMEOUT(failed.size(), 1, 20000);
    QCOMPARE(failed.at(0).at(0).toString(), QString("request 1 is bad"));
    QCOMPARE(failed.at(0).at(1).toULongLong(), quint64{1});
    QVERIFY(worker.isRunning());  // the loop survived: the thread still waits for requests
    const Qt::HANDLE thread = worker.servingThread();

    worker.request({2, Job::ThrowOther});
    QTRY_COMPARE_WITH_TIMEOUT(failed.size(), 2, 20000);
    QCOMPARE(failed.at(1).at(0).toString(), QString("unknown error in the test worker"));
    QCOMPARE(failed.at(1).at(1).toULongLong(), quint64{2});
    QVERIFY(worker.isRunning());

    worker.request({3, Job::Serve});
    QTRY_COMPARE_WITH_TIMEOUT(served.size(), 1, 20000);
    QCOMPARE(served.at(0).at(0).toULongLong(), quint64{3});
    QCOMPARE(worker.servingThread(), thread);  // served by the same thread, not a restart
    QCOMPARE(failed.size(), 2);
    worker.shutdown();
    QVERIFY(!worker.isRunning());
  }

  void cloudRendererReportsARefusalAndRendersTheNext() {
    CubeOfCubesOptions small;
    small.samples_per_edge = 4;
    CloudRenderRequest good;
    good.cloud = std::make_shared<const PointCloud>(cubeOfCubes(small));
    PinholeParams pinhole;
    pinhole.pose = CameraPose::lookAt({2.744, 2.058, -3.430}, {0, 0, 0});
    good.view = pinholeCamera(pinhole);
    good.width = 64;
    good.height = 48;
    CloudRenderRequest bad = good;
    bad.effects = {radialLensCamera(0.1, {64, 48})};  // an image camera: no 3D position block
    bad.generation = 1;
    good.generation = 2;

    CloudRenderWorker worker;
    QSignalSpy failed(&worker, &CloudRenderWorker::failed);
    QSignalSpy rendered(&worker, &CloudRenderWorker::rendered);
    worker.request(bad);
    QTRY_COMPARE_WITH_TIMEOUT(failed.size(), 1, 20000);
    QVERIFY2(failed.at(0).at(0).toString().contains("4-element position block"),
             qPrintable(failed.at(0).at(0).toString()));
    QCOMPARE(failed.at(0).at(1).toULongLong(), quint64{1});
    QCOMPARE(rendered.size(), 0);
    worker.request(good);
    QTRY_VERIFY_WITH_TIMEOUT(!rendered.isEmpty() && rendered.last().at(2).toBool(), 20000);
    QCOMPARE(rendered.last().at(1).toULongLong(), quint64{2});
    QCOMPARE(failed.size(), 1);
  }
};

QTEST_MAIN(TestNewestRequestWorker)
#include "test_newest_request_worker.moc"
