// SPDX-License-Identifier: Apache-2.0
// A drag of one point among 300 pairs: the GUI thread only records the mouse moves; the fits
// run in the document's FitWorker (counted by thread, not timed), the camera settles on the
// same fit a direct fitImageCamera of the dropped pairs gives, and undo refits at once.
#include "core/fit/fit_image.h"
#include "tests/ui/ui_fixtures.h"
#include "ui/canvas.h"
#include "ui/document.h"
#include "ui/document_fit.h"
#include "ui/tools/pair_tool.h"

#include <QtTest/QtTest>

#include <memory>
#include <vector>

using namespace artcam;
using namespace artcam::ui;

namespace {

// 300 pairs on a 20×15 grid over a 640×480 photo, targets under a mild lens about the centre.
std::vector<Pair> gridPairs(int w, int h) {
  std::vector<Pair> out;
  for (int j = 0; j < 15; ++j)
    for (int i = 0; i < 20; ++i) {
      Pair p;
      p.source = {(i + 0.5) * w / 20.0, (j + 0.5) * h / 15.0};
      const Eigen::Vector2d c(0.5 * w, 0.5 * h);
      const Eigen::Vector2d d = (p.source - c) / c.norm();
      p.target = c + (p.source - c) * (1.0 + 0.1 * d.squaredNorm());
      out.push_back(p);
    }
  return out;
}

bool sameQ(const Camera& a, const Camera& b) {
  const auto& qa = a.stages().at(0).q;
  const auto& qb = b.stages().at(0).q;
  if (qa.size() != qb.size()) return false;
  for (size_t i = 0; i < qa.size(); ++i)
    if (qa[i] != qb[i]) return false;
  return true;
}

}  // namespace

class TestDragFit : public QObject {
  Q_OBJECT

 private slots:
  void aDragFitsInTheWorkerNotOnTheGuiThread() {
    Document doc;
    Canvas canvas(&doc);
    canvas.setTool(std::make_unique<PairTool>(&canvas, &doc));
    canvas.resize(900, 700);
    canvas.show();
    QVERIFY(QTest::qWaitForWindowExposed(&canvas));
    const std::vector<Pair> pairs = gridPairs(640, 480);
    doc.reset(test::syntheticPhoto(640, 480), pairs, ModelClass::Quadratic);
    QVERIFY2(doc.fit().status.ok, doc.fit().status.message.c_str());
    const Camera before_camera = doc.camera();
    const int steps = doc.undoStack()->count();

    // A corner pair: its target is farthest from its source, so the press grabs the target.
    const QPoint from = test::widgetPoint(canvas, pairs[0].target);
    const FitThreadCounts start = fitThreadCounts();
    test::drag(&canvas, from, from + QPoint(40, 25), 40);
    const FitThreadCounts after_drag = fitThreadCounts();
    QCOMPARE(after_drag.gui_thread, start.gui_thread);  // 40 moves, no fit on the GUI thread
    QVERIFY(!(doc.pairs()[0] == pairs[0]));
    QCOMPARE(doc.undoStack()->count(), steps + 1);

    QTRY_VERIFY_WITH_TIMEOUT(!doc.fitPending(), 20000);
    const FitThreadCounts settled = fitThreadCounts();
    QCOMPARE(settled.gui_thread, start.gui_thread);
    QVERIFY(settled.other_threads > start.other_threads);
    // The worker's camera is the fit of the dropped pairs (an independent direct fit).
    FitOptions options;
    options.model = ModelClass::Quadratic;
    const FitSummary direct = fitImageCamera(doc.matches(), doc.frame(), doc.frame(), options);
    QVERIFY(direct.status.ok);
    QVERIFY(sameQ(doc.camera(), direct.camera));
    QVERIFY(!sameQ(doc.camera(), before_camera));
    QCOMPARE(doc.cameraRevision(), doc.editRevision());

    // Undo is a discrete edit: it refits before returning, back to the exact camera.
    doc.undoStack()->undo();
    QVERIFY(!doc.fitPending());
    QVERIFY(sameQ(doc.camera(), before_camera));
    QCOMPARE(fitThreadCounts().gui_thread, settled.gui_thread + 1);
  }

  // A discrete edit made while a worker fit is on its way wins: the late result is dropped.
  void aLateWorkerFitDoesNotOverwriteANewerEdit() {
    Document doc;
    doc.reset(test::syntheticPhoto(640, 480), gridPairs(640, 480), ModelClass::Quadratic);
    Pair moved = doc.pairs()[5];
    moved.target += Eigen::Vector2d(9.0, -4.0);
    const long worker_fits = fitThreadCounts().other_threads;
    doc.setPairs({5}, {moved}, Document::Refit::InWorker);
    QVERIFY(doc.fitPending());
    doc.setModel(ModelClass::Affine);  // refits now, with the moved pair
    QVERIFY(!doc.fitPending());
    const Camera affine = doc.camera();
    // The worker's (quadratic) fit ends, and its queued result reaches the document.
    QTRY_VERIFY_WITH_TIMEOUT(fitThreadCounts().other_threads > worker_fits, 20000);
    QTest::qWait(100);
    QVERIFY(sameQ(doc.camera(), affine));
    QCOMPARE(doc.fit().record.model, std::string("affine"));
  }
};

QTEST_MAIN(TestDragFit)
#include "test_drag_fit.moc"
