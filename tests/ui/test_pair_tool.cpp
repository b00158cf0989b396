// SPDX-License-Identifier: Apache-2.0
// The pair tool on the canvas: clicked pairs become a fitted camera; select, drag, delete,
// rubber band; undo/redo restores the exact document state.
#include "tests/ui/ui_fixtures.h"
#include "ui/canvas.h"
#include "ui/commands.h"
#include "ui/document.h"
#include "ui/tools/pair_tool.h"

#include <QtTest/QtTest>

#include <memory>

using namespace artcam;
using namespace artcam::ui;

namespace {

struct Snapshot {
  std::vector<Pair> pairs;
  ModelClass model;
  std::vector<Eigen::MatrixXd> q;
  bool fit_ok;

  static Snapshot of(const Document& d) {
    return {d.pairs(), d.model(), d.camera().stages().at(0).q, d.fit().status.ok};
  }
  bool operator==(const Snapshot& o) const {
    if (!(pairs == o.pairs) || model != o.model || fit_ok != o.fit_ok || q.size() != o.q.size())
      return false;
    for (size_t i = 0; i < q.size(); ++i)
      if (q[i] != o.q[i]) return false;  // exact: undo must restore bit for bit
    return true;
  }
};

}  // namespace

class TestPairTool : public QObject {
  Q_OBJECT

  std::unique_ptr<Document> doc_;
  std::unique_ptr<Canvas> canvas_;

  void clickPairs(const std::vector<Pair>& pairs) {
    for (const Pair& p : pairs) {
      QTest::mouseClick(canvas_.get(), Qt::LeftButton, Qt::NoModifier,
                        test::widgetPoint(*canvas_, p.source));
      QTest::mouseClick(canvas_.get(), Qt::LeftButton, Qt::NoModifier,
                        test::widgetPoint(*canvas_, p.target));
    }
  }

 private slots:
  void init() {
    doc_ = std::make_unique<Document>();
    canvas_ = std::make_unique<Canvas>(doc_.get());
    canvas_->setTool(std::make_unique<PairTool>(canvas_.get(), doc_.get()));
    canvas_->resize(800, 600);
    canvas_->show();
    QVERIFY(QTest::qWaitForWindowExposed(canvas_.get()));
    doc_->reset(test::syntheticPhoto());
  }

  void cleanup() {
    canvas_.reset();
    doc_.reset();
  }

  void nineClickedPairsGiveAFittedCamera() {
    const std::vector<Pair> wanted = test::ninePairs();
    clickPairs(wanted);
    QCOMPARE(doc_->pairs().size(), size_t{9});
    // Clicks land on whole widget pixels: the pair is within one widget pixel of the aim.
    const double tolerance = 1.0 / canvas_->view().scale();
    for (size_t i = 0; i < wanted.size(); ++i) {
      QVERIFY((doc_->pairs()[i].source - wanted[i].source).norm() <= tolerance);
      QVERIFY((doc_->pairs()[i].target - wanted[i].target).norm() <= tolerance);
    }
    QVERIFY2(doc_->fit().status.ok, doc_->fit().status.message.c_str());
    QCOMPARE(doc_->fit().record.matches, 9);
    QCOMPARE(doc_->pairsNeeded(), 0);
    // The fitted camera takes every clicked source close to its clicked target.
    for (size_t i = 0; i < 9; ++i) QVERIFY(doc_->residual(static_cast<int>(i)) < 3.0);
    QCOMPARE(doc_->undoStack()->count(), 9);
  }

  void quadraticNeedsMorePairsUntilNine() {
    doc_->undoStack()->push(new SetModelCommand(doc_.get(), ModelClass::Quadratic));
    std::vector<Pair> wanted = test::ninePairs();
    wanted.pop_back();
    clickPairs(wanted);
    QCOMPARE(doc_->pairsNeeded(), 1);
    QVERIFY(!doc_->fit().status.ok);
    QVERIFY(QString::fromStdString(doc_->fit().status.message).contains("1 more"));
  }

  void dragMovesOnePointAsOneUndoStep() {
    clickPairs(test::ninePairs());
    const Pair before = doc_->pairs()[4];
    const int steps = doc_->undoStack()->count();
    const QPoint from = test::widgetPoint(*canvas_, before.target);
    test::drag(canvas_.get(), from, from + QPoint(30, -20));
    QCOMPARE(doc_->undoStack()->count(), steps + 1);  // merged drag
    const Pair after = doc_->pairs()[4];
    QCOMPARE(after.source, before.source);
    const double s = canvas_->view().scale();
    QVERIFY(std::abs(after.target.x() - before.target.x() - 30 / s) < 1e-9);
    QVERIFY(std::abs(after.target.y() - before.target.y() + 20 / s) < 1e-9);
    doc_->undoStack()->undo();
    QVERIFY(doc_->pairs()[4] == before);
  }

  void rubberBandSelectsAndDeleteRemoves() {
    clickPairs(test::ninePairs());
    // A band around the whole photo's left third.
    const QPoint a = canvas_->view().widgetFromImage(QPointF(-5, -5)).toPoint();
    const QPoint b = canvas_->view().widgetFromImage(QPointF(0.3 * 320, 245)).toPoint();
    test::drag(canvas_.get(), a, b);
    const std::vector<int> expected = {0, 3, 6};
    QCOMPARE(doc_->selection(), expected);
    QTest::keyClick(canvas_.get(), Qt::Key_Delete);
    QCOMPARE(doc_->pairs().size(), size_t{6});
    doc_->undoStack()->undo();
    QCOMPARE(doc_->pairs().size(), size_t{9});
    QCOMPARE(doc_->selection(), expected);
  }

  void middleDragAndSpaceDragPan() {
    const QPointF before = canvas_->view().offset();
    QWidget* w = canvas_.get();
    test::sendMouse(w, QEvent::MouseButtonPress, QPoint(100, 100), Qt::MiddleButton,
                    Qt::MiddleButton);
    test::sendMouse(w, QEvent::MouseMove, QPoint(130, 90), Qt::NoButton, Qt::MiddleButton);
    test::sendMouse(w, QEvent::MouseButtonRelease, QPoint(130, 90), Qt::MiddleButton, Qt::NoButton);
    QCOMPARE(canvas_->view().offset(), before + QPointF(30, -10));
    QTest::keyPress(w, Qt::Key_Space);
    test::drag(w, QPoint(200, 200), QPoint(190, 240));
    QTest::keyRelease(w, Qt::Key_Space);
    QCOMPARE(canvas_->view().offset(), before + QPointF(20, 30));
    QCOMPARE(doc_->pairs().size(), size_t{0});  // panning never reaches the tool
    auto* tool = dynamic_cast<PairTool*>(canvas_->tool());
    QVERIFY(tool && !tool->hasPendingSource());
  }

  void escapeDropsHalfMadePair() {
    QTest::mouseClick(canvas_.get(), Qt::LeftButton, Qt::NoModifier, QPoint(400, 300));
    auto* tool = dynamic_cast<PairTool*>(canvas_->tool());
    QVERIFY(tool && tool->hasPendingSource());
    QTest::keyClick(canvas_.get(), Qt::Key_Escape);
    QVERIFY(!tool->hasPendingSource());
    QCOMPARE(doc_->pairs().size(), size_t{0});
  }

  void undoRedoRestoresExactState() {
    std::vector<Snapshot> states{Snapshot::of(*doc_)};
    auto record = [&] { states.push_back(Snapshot::of(*doc_)); };
    for (const Pair& p : test::ninePairs()) {
      doc_->undoStack()->push(new AddPairCommand(doc_.get(), p));
      record();
    }
    const QPoint from = test::widgetPoint(*canvas_, doc_->pairs()[2].source);
    test::drag(canvas_.get(), from, from + QPoint(-12, 17));
    QTRY_VERIFY(!doc_->fitPending());  // a drag's moves fit in the worker
    record();
    pushTogglePairsEnabled(doc_.get(), {1});
    record();
    doc_->undoStack()->push(new SetModelCommand(doc_.get(), ModelClass::Homography));
    record();
    doc_->setSelection({0, 5});
    pushDeleteSelection(doc_.get());
    record();
    doc_->undoStack()->push(new SetModelCommand(doc_.get(), ModelClass::Affine));
    record();
    const int n = doc_->undoStack()->count();
    QCOMPARE(n + 1, static_cast<int>(states.size()));
    for (int i = n - 1; i >= 0; --i) {
      doc_->undoStack()->undo();
      QVERIFY2(Snapshot::of(*doc_) == states[static_cast<size_t>(i)],
               qPrintable(QString("undo to %1").arg(i)));
    }
    for (int i = 1; i <= n; ++i) {
      doc_->undoStack()->redo();
      QVERIFY2(Snapshot::of(*doc_) == states[static_cast<size_t>(i)],
               qPrintable(QString("redo to %1").arg(i)));
    }
  }
};

QTEST_MAIN(TestPairTool)
#include "test_pair_tool.moc"
