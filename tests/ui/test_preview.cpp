// SPDX-License-Identifier: Apache-2.0
// The live preview: edits reach the RenderWorker with rising generations, the newest request
// wins, the final image equals a direct warpImage render, and the worker stops mid-render.
#include "core/render/warp.h"
#include "tests/ui/ui_fixtures.h"
#include "ui/canvas.h"
#include "ui/commands.h"
#include "ui/document.h"
#include "ui/image_convert.h"
#include "ui/preview_controller.h"
#include "ui/render_worker.h"
#include "ui/tools/pair_tool.h"

#include <QElapsedTimer>
#include <QSignalSpy>
#include <QtTest/QtTest>

#include <memory>
#include <random>

using namespace artcam;
using namespace artcam::ui;

namespace {

bool waitForNewest(const PreviewController& c) { return artcam::ui::test::waitForNewestPreview(c); }
QImage directRender(const Document& d) { return artcam::ui::test::directPreviewRender(d); }

// A first request (generation 1) for the whole preview copy of `photo` through `doc`'s camera.
RenderRequest wholePreviewRequest(const PhotoPtr& photo, const Document& doc) {
  RenderRequest r;
  r.source = std::shared_ptr<const ImageF>(photo, &photo->preview);
  r.camera = doc.artcam();
  r.width = photo->preview.width;
  r.height = photo->preview.height;
  r.generation = 1;
  return r;
}

}  // namespace

class TestPreview : public QObject {
  Q_OBJECT

 private slots:
  void draggingAPointUpdatesThePreview() {
    Document doc;
    PreviewController preview(&doc);
    Canvas canvas(&doc);
    canvas.setTool(std::make_unique<PairTool>(&canvas, &doc));
    canvas.resize(800, 600);
    canvas.show();
    QVERIFY(QTest::qWaitForWindowExposed(&canvas));
    doc.reset(test::syntheticPhoto(), test::ninePairs());
    QVERIFY(waitForNewest(preview));
    const QImage first = preview.image();
    const quint64 first_generation = preview.imageGeneration();
    QCOMPARE(first, directRender(doc));

    const QPoint from = test::widgetPoint(canvas, doc.pairs()[4].target);
    test::drag(&canvas, from, from + QPoint(25, 15));
    QTRY_VERIFY(!doc.fitPending());  // a drag's moves fit in the worker; then the preview
    QVERIFY(waitForNewest(preview));
    QVERIFY(preview.imageGeneration() > first_generation);
    QVERIFY(preview.image() != first);
    QCOMPARE(preview.image(), directRender(doc));
  }

  void thousandRapidEditsEndOnTheFinalCamera() {
    Document doc;
    PreviewController preview(&doc);
    doc.reset(test::syntheticPhoto(), test::ninePairs());
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> jitter(-2.0, 2.0);
    std::uniform_int_distribution<int> pick(0, 8);
    for (int k = 0; k < 1000; ++k) {
      const int i = pick(rng);
      Pair p = doc.pairs()[static_cast<size_t>(i)];
      const Pair before = p;
      p.target += Eigen::Vector2d(jitter(rng), jitter(rng));
      doc.undoStack()->push(new MovePairsCommand(&doc, {i}, {before}, {p}, 0, "jitter"));
      if (k % 50 == 0) QCoreApplication::processEvents();  // let some results through
    }
    QCOMPARE(preview.requestedGeneration(), quint64{1001});  // reset + 1000 edits
    QVERIFY(waitForNewest(preview));
    QCOMPARE(preview.image(), directRender(doc));
  }

  void workerShutsDownMidRender() {
    // A rational camera on a large source keeps the worker busy long enough to interrupt it.
    const PhotoPtr photo = test::syntheticPhoto(1024, 1024);
    Document doc;
    doc.reset(photo, test::ninePairs(1024, 1024));
    QVERIFY(doc.fit().status.ok);
    int interrupted = 0;
    for (int round = 0; round < 5; ++round) {
      auto worker = std::make_unique<RenderWorker>();
      QSignalSpy spy(worker.get(), &RenderWorker::rendered);
      RenderRequest r;
      r.source = std::shared_ptr<const ImageF>(photo, &photo->preview);
      r.camera = doc.artcam();
      r.width = 2048;
      r.height = 2048;
      r.generation = 1;
      worker->request(r);
      QTest::qWait(round * 3);
      QElapsedTimer t;
      t.start();
      worker.reset();  // the destructor aborts between tiles and joins
      QVERIFY2(t.elapsed() < 5000, "worker took too long to stop");
      bool final_seen = false;
      for (const QList<QVariant>& args : spy) final_seen = final_seen || args.at(2).toBool();
      if (!final_seen) ++interrupted;
    }
    QVERIFY2(interrupted > 0, "no round stopped before its final pass: the test proves nothing");
  }

  void coarsePassComesFirst() {
    const PhotoPtr photo = test::syntheticPhoto();
    Document doc;
    doc.reset(photo, test::ninePairs());
    RenderWorker worker;
    QList<QPair<bool, int>> passes;  // (final, width)
    double final_ms = 0.0;
    connect(&worker, &RenderWorker::rendered, this,
            [&](const QImage& image, quint64, bool final_pass, double ms) {
              passes << qMakePair(final_pass, image.width());
              if (final_pass) final_ms = ms;
            });
    RenderRequest r = wholePreviewRequest(photo, doc);
    worker.request(r);
    QTRY_COMPARE_WITH_TIMEOUT(passes.size(), 2, 30000);
    QCOMPARE(passes[0], qMakePair(false, 320 / RenderWorker::kCoarseFactor));
    QCOMPARE(passes[1], qMakePair(true, 320));

    // The next request skips the coarse pass exactly when that final pass was fast.
    passes.clear();
    r.generation = 2;
    worker.request(r);
    QTRY_VERIFY_WITH_TIMEOUT(!passes.isEmpty() && passes.back().first, 30000);
    const int expected = final_ms > RenderWorker::kCoarseAboveMs ? 2 : 1;
    QCOMPARE(passes.size(), expected);
  }

  // With a finish the picture without marks comes first (G'MIC's marks take a good part of a
  // second and cannot be cancelled, so a drag stays live), then the marked final pass.
  void finishComesAfterThePlainPicture() {
    const PhotoPtr photo = test::syntheticPhoto();
    Document doc;
    doc.reset(photo, test::ninePairs());
    RenderWorker worker;
    QList<QPair<bool, QImage>> passes;
    connect(&worker, &RenderWorker::rendered, this,
            [&](const QImage& image, quint64, bool final_pass, double) {
              passes << qMakePair(final_pass, image);
            });
    RenderRequest r = wholePreviewRequest(photo, doc);
    r.finish = "pencil";
    worker.request(r);
    QTRY_VERIFY_WITH_TIMEOUT(!passes.isEmpty() && passes.back().first, 30000);
    QVERIFY(passes.size() >= 2);
    const QImage plain = passes[passes.size() - 2].second, marked = passes.back().second;
    QVERIFY(!passes[passes.size() - 2].first);
    RenderRequest unmarked = r;
    unmarked.finish.clear();
    QCOMPARE(plain, RenderWorker::renderPass(unmarked, RenderWorker::passOptions(r.width, r.height),
                                             nullptr));
    QCOMPARE(marked,
             RenderWorker::renderPass(r, RenderWorker::passOptions(r.width, r.height), nullptr));
    QVERIFY(marked != plain);
  }

  void newestRequestWins() {
    const PhotoPtr photo = test::syntheticPhoto();
    Document doc;
    doc.reset(photo, test::ninePairs());
    RenderWorker worker;
    QList<quint64> finals;
    connect(&worker, &RenderWorker::rendered, this,
            [&](const QImage&, quint64 g, bool final_pass, double) {
              if (final_pass) finals << g;
            });
    for (quint64 g = 1; g <= 50; ++g) {
      RenderRequest r;
      r.source = std::shared_ptr<const ImageF>(photo, &photo->preview);
      r.camera = doc.artcam();
      r.width = photo->preview.width;
      r.height = photo->preview.height;
      r.generation = g;
      worker.request(r);
    }
    QTRY_VERIFY_WITH_TIMEOUT(!finals.isEmpty() && finals.back() == 50, 30000);
    QVERIFY(finals.size() < 50);  // stale requests were dropped, not all rendered
  }
};

QTEST_MAIN(TestPreview)
#include "test_preview.moc"
