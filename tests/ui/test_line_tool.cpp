// SPDX-License-Identifier: Apache-2.0
// The line tool on the canvas: points clicked along the edges of a photo made through a known
// barrel lens become lines (Enter ends one, refused below 3 points; Esc drops one; Delete
// removes the selected one), every edit undoes and redoes bit for bit, the document's camera is
// core's line fit of the same points and straightens edges that were not traced, a drag refits
// in the worker, and the lines survive the project file through the studio's session.
//
// The truth is the lens that made the photo: scene = photo / (1 - k |photo|²) in the normalised
// frame (core/fit/fit_lines.h's radial model), so a straight scene edge is a curve in the photo.
#include "core/fit/fit_lines.h"
#include "core/io/image_io.h"
#include "core/model/frames.h"
#include "core/project/studio_project.h"
#include "core/render/attributed.h"
#include "tests/ui/session_wait.h"
#include "tests/ui/ui_fixtures.h"
#include "ui/canvas.h"
#include "ui/document.h"
#include "ui/line_commands.h"
#include "ui/preview_controller.h"
#include "ui/session.h"
#include "ui/tools/line_tool.h"
#include "ui/tools/pair_tool.h"

#include <QSignalSpy>
#include <QStandardPaths>
#include <QTemporaryDir>
#include <QtTest/QtTest>

#include <cmath>
#include <memory>

using namespace artcam;
using namespace artcam::ui;

namespace {

const FrameSize kFrame{480, 320};
const double kK = 0.1;

Eigen::Vector2d photoFromScene(const Eigen::Vector2d& scene_px) {
  const Eigen::Vector2d s = normalizedFromPixel(kFrame, scene_px);
  return pixelFromNormalized(kFrame, s * (2.0 / (1.0 + std::sqrt(1.0 + 4.0 * kK * s.squaredNorm()))));
}

Eigen::Vector2d sceneFromPhoto(const Eigen::Vector2d& photo_px) {
  const Eigen::Vector2d p = normalizedFromPixel(kFrame, photo_px);
  return pixelFromNormalized(kFrame, p / (1.0 - kK * p.squaredNorm()));
}

// A grid every 40 scene px, seen through the lens: its lines bow in the photo.
PhotoPtr distortedGridPhoto() {
  ImageF img(kFrame.width, kFrame.height, 3);
  for (int y = 0; y < kFrame.height; ++y)
    for (int x = 0; x < kFrame.width; ++x) {
      const Eigen::Vector2d s = sceneFromPhoto({x + 0.5, y + 0.5});
      const double gx = std::abs(std::remainder(s.x(), 40.0));
      const double gy = std::abs(std::remainder(s.y(), 40.0));
      const float v = (gx < 1.0 || gy < 1.0) ? 1.0f : 0.2f;
      float* p = img.pixel(x, y);
      p[0] = v;
      p[1] = v;
      p[2] = v;
    }
  LoadedImage loaded;
  loaded.image = std::move(img);
  loaded.info.path = "grid.png";
  return makePhoto(QStringLiteral("grid.png"), std::move(loaded));
}

// n points of the scene segment a → b, in photo pixels.
std::vector<Eigen::Vector2d> edge(Eigen::Vector2d a, Eigen::Vector2d b, int n) {
  std::vector<Eigen::Vector2d> out;
  for (int k = 0; k < n; ++k) out.push_back(photoFromScene(a + (b - a) * (k / (n - 1.0))));
  return out;
}

// Traced edges (off the centre: a radial lens keeps lines through it straight; no two share a
// point, which a click would grab instead of adding) and edges kept back to check the camera on.
std::vector<std::vector<Eigen::Vector2d>> tracedEdges() {
  return {edge({40, 40}, {440, 40}, 7), edge({40, 280}, {440, 280}, 7),
          edge({30, 70}, {30, 250}, 6), edge({450, 70}, {450, 250}, 6),
          edge({80, 250}, {300, 60}, 6)};
}

std::vector<LineTrace> heldOutEdges() {
  return {{"h1", edge({30, 80}, {450, 80}, 15), true},
          {"h2", edge({400, 20}, {400, 300}, 15), true},
          {"h3", edge({60, 60}, {420, 300}, 15), true}};
}

double maxBow(const std::vector<LineBow>& bows) {
  double m = 0.0;
  for (const LineBow& b : bows) m = std::max(m, b.max_px);
  return m;
}

bool sameLines(const std::vector<LineTrace>& a, const std::vector<LineTrace>& b) {
  return LineSet{a, {}} == LineSet{b, {}};
}

}  // namespace

class TestLineTool : public QObject {
  Q_OBJECT

  QTemporaryDir dir_;
  std::unique_ptr<Document> doc_;
  std::unique_ptr<Canvas> canvas_;

  void clickPoints(const std::vector<Eigen::Vector2d>& points) {
    for (const Eigen::Vector2d& p : points) test::click(canvas_.get(), test::widgetPoint(*canvas_, p));
  }

  void traceAll() {
    for (const auto& e : tracedEdges()) {
      clickPoints(e);
      QTest::keyClick(canvas_.get(), Qt::Key_Return);
    }
  }

 private slots:
  void initTestCase() {
    QStandardPaths::setTestModeEnabled(true);
    QVERIFY(dir_.isValid());
  }

  void init() {
    doc_ = std::make_unique<Document>();
    canvas_ = std::make_unique<Canvas>(doc_.get());
    canvas_->setTool(std::make_unique<LineTool>(canvas_.get(), doc_.get()));
    canvas_->resize(800, 600);
    canvas_->show();
    QVERIFY(QTest::qWaitForWindowExposed(canvas_.get()));
    doc_->reset(distortedGridPhoto());
  }

  void cleanup() {
    canvas_.reset();
    doc_.reset();
  }

  void clickedLinesStraightenHeldOutEdges() {
    traceAll();
    QCOMPARE(doc_->lines().size(), tracedEdges().size());
    QVERIFY(doc_->openLine().empty());
    // Clicks land on whole widget pixels: each point within one widget pixel of its aim.
    const double tolerance = 1.0 / canvas_->view().scale();
    for (size_t i = 0; i < tracedEdges().size(); ++i) {
      QCOMPARE(doc_->lines()[i].points.size(), tracedEdges()[i].size());
      for (size_t k = 0; k < tracedEdges()[i].size(); ++k)
        QVERIFY((doc_->lines()[i].points[k] - tracedEdges()[i][k]).norm() <= tolerance);
    }
    QVERIFY2(doc_->fit().status.ok, doc_->fit().status.message.c_str());
    QCOMPARE(doc_->pairsNeeded(), 0);  // lines need no pairs
    // The document's geometry is core's line fit of the same points.
    const LinesFitSummary direct = fitLinesCamera(doc_->lines(), {}, kFrame, kFrame);
    QVERIFY2(direct.status.ok, direct.status.message.c_str());
    const Camera geometry = positionPart(doc_->camera());
    const std::vector<LineTrace> held = heldOutEdges();
    const std::vector<LineBow> bows = lineBows(geometry, held);
    const std::vector<LineBow> direct_bows = lineBows(direct.camera, held);
    QCOMPARE(bows.size(), held.size());
    for (size_t i = 0; i < bows.size(); ++i)
      QVERIFY(std::abs(bows[i].max_px - direct_bows[i].max_px) < 1e-9);
    // Straightened: the held-out edges bow by pixels in the photo and by little after the fit.
    const double before = maxBow(lineBows(identityImageCamera(kFrame), held));
    QVERIFY2(before > 3.0, qPrintable(QString::number(before)));
    QVERIFY2(maxBow(bows) < 0.05, qPrintable(QString::number(maxBow(bows))));
    // And the lens itself: held-out photo points land on their scene points.
    for (const LineTrace& l : held)
      for (const Eigen::Vector2d& p : l.points) {
        const auto mapped = targetPixelFromSourcePixel(geometry, p);
        QVERIFY(mapped);
        QVERIFY2((*mapped - sceneFromPhoto(p)).norm() < 0.5,
                 qPrintable(QString::number((*mapped - sceneFromPhoto(p)).norm())));
      }
    // Each traced line's bow, as labelled on the canvas, is the fit's.
    for (int i = 0; i < static_cast<int>(doc_->lines().size()); ++i) {
      const std::optional<LineBow> bow = doc_->lineBow(i);
      QVERIFY(bow);
      QVERIFY(std::abs(bow->max_px - direct.bows[static_cast<size_t>(i)].max_px) < 1e-9);
    }
    QVERIFY(!canvas_->grab().isNull());  // the lines and labels paint
  }

  void enterNeedsThreePointsAndEscDropsTheLine() {
    QSignalSpy messages(canvas_.get(), &Canvas::toolMessage);
    const auto e = tracedEdges()[0];
    clickPoints({e[0], e[3]});
    QTest::keyClick(canvas_.get(), Qt::Key_Return);
    QCOMPARE(messages.size(), 1);
    QVERIFY(messages.front().front().toString().contains("3 points"));
    QVERIFY(doc_->lines().empty());
    QCOMPARE(doc_->openLine().size(), size_t{2});
    QTest::keyClick(canvas_.get(), Qt::Key_Escape);
    QVERIFY(doc_->openLine().empty());
    doc_->undoStack()->undo();  // the cancel is an edit like any other
    QCOMPARE(doc_->openLine().size(), size_t{2});
    // A third point, then a double click ends the line (its first press adds the point).
    const QPoint at = test::widgetPoint(*canvas_, e[6]);
    test::click(canvas_.get(), at);
    test::sendMouse(canvas_.get(), QEvent::MouseButtonDblClick, at, Qt::LeftButton, Qt::LeftButton);
    test::sendMouse(canvas_.get(), QEvent::MouseButtonRelease, at, Qt::LeftButton, Qt::NoButton);
    QCOMPARE(doc_->lines().size(), size_t{1});
    QCOMPARE(doc_->lines()[0].points.size(), size_t{3});
    QVERIFY(doc_->openLine().empty());
  }

  void undoRedoRestoreLinesAndFitExactly() {
    traceAll();
    const LineSet lines = doc_->lineSet();
    const std::vector<Eigen::MatrixXd> q = doc_->camera().stages().at(0).q;
    doc_->undoStack()->undo();  // reopens the last line
    QCOMPARE(doc_->lines().size(), lines.lines.size() - 1);
    QVERIFY(doc_->openLine() == lines.lines.back().points);
    QVERIFY(doc_->camera().stages().at(0).q != q);
    doc_->undoStack()->undo();  // its last point
    QCOMPARE(doc_->openLine().size(), lines.lines.back().points.size() - 1);
    doc_->undoStack()->redo();
    doc_->undoStack()->redo();
    QVERIFY(doc_->lineSet() == lines);
    QVERIFY(doc_->camera().stages().at(0).q == q);  // bit for bit

    // Delete the selected line (a click on one of its points selects it), then undo.
    auto* tool = static_cast<LineTool*>(canvas_->tool());
    test::click(canvas_.get(), test::widgetPoint(*canvas_, lines.lines[1].points[2]));
    QCOMPARE(tool->selectedLine(), 1);
    QTest::keyClick(canvas_.get(), Qt::Key_Delete);
    QCOMPARE(doc_->lines().size(), lines.lines.size() - 1);
    QVERIFY(doc_->lines()[1].label == lines.lines[2].label);
    doc_->undoStack()->undo();
    QVERIFY(doc_->lineSet() == lines);
    QVERIFY(doc_->camera().stages().at(0).q == q);

    // Clear, undone.
    QVERIFY(pushClearLines(doc_.get()));
    QVERIFY(doc_->lines().empty());
    doc_->undoStack()->undo();
    QVERIFY(doc_->lineSet() == lines);
  }

  void dragMovesAPointAsOneStepFittedInTheWorker() {
    traceAll();
    const LineSet before = doc_->lineSet();
    const int steps = doc_->undoStack()->count();
    const long worker_fits = fitThreadCounts().other_threads;
    const QPoint from = test::widgetPoint(*canvas_, before.lines[0].points[3]);
    test::drag(canvas_.get(), from, from + QPoint(0, 12));
    QCOMPARE(doc_->undoStack()->count(), steps + 1);  // merged drag
    const double s = canvas_->view().scale();
    const Eigen::Vector2d moved = doc_->lines()[0].points[3];
    QVERIFY((moved - before.lines[0].points[3] - Eigen::Vector2d(0, 12 / s)).norm() < 1e-9);
    QTRY_VERIFY_WITH_TIMEOUT(!doc_->fitPending(), 20000);
    QVERIFY(fitThreadCounts().other_threads > worker_fits);
    // The worker's camera is the fit of the moved points.
    const LinesFitSummary direct = fitLinesCamera(doc_->lines(), {}, kFrame, kFrame);
    QVERIFY(direct.status.ok);
    const auto a = targetPixelFromSourcePixel(positionPart(doc_->camera()), {100, 100});
    const auto b = targetPixelFromSourcePixel(direct.camera, {100, 100});
    QVERIFY(a && b && (*a - *b).norm() < 1e-9);
    doc_->undoStack()->undo();
    QVERIFY(doc_->lineSet() == before);
  }

  // The photo view draws the lines as traced, the result view where the camera sends them.
  void resultViewDrawsTheMappedLines() {
    traceAll();
    PreviewController preview(doc_.get());
    canvas_->setPreview(&preview);
    canvas_->setTool(std::make_unique<PairTool>(canvas_.get(), doc_.get()));  // shows the result
    // A point away from the label (at the first point) and from every other line.
    const Eigen::Vector2d traced = doc_->lines()[0].points[1];
    const auto mapped = targetPixelFromSourcePixel(positionPart(doc_->camera()), traced);
    QVERIFY(mapped);
    QVERIFY((*mapped - traced).norm() * canvas_->view().scale() > 12.0);
    // A straightened line is drawn green (its bow is far below a pixel); the photo is grey.
    auto greenAt = [this](const QImage& shot, const Eigen::Vector2d& p) {
      const QColor c = shot.pixelColor(test::widgetPoint(*canvas_, p));
      return c.green() > c.red() + 80 && c.green() > c.blue() + 80;
    };
    canvas_->setViewMode(CanvasViewMode::Result);
    QImage shot = canvas_->grab().toImage();
    QVERIFY(greenAt(shot, *mapped));
    QVERIFY(!greenAt(shot, traced));
    canvas_->setViewMode(CanvasViewMode::Photo);
    shot = canvas_->grab().toImage();
    QVERIFY(greenAt(shot, traced));
    QVERIFY(!greenAt(shot, *mapped));
    canvas_->setPreview(nullptr);
  }

  // A project with lines opened in the studio and saved again keeps its lines; the lines the
  // tool traced are saved and read back bit for bit with the same camera.
  void projectKeepsTheLines() {
    const QString photo = dir_.filePath("grid.png");
    QVERIFY(writeImage(photo.toStdString(), doc_->photo()->full.image).ok);
    StudioProject written;
    written.photo_path = photo.toStdString();
    for (size_t i = 0; i < tracedEdges().size(); ++i)
      written.lines.push_back({std::to_string(i + 1), tracedEdges()[i], i != 2});
    const QString first = dir_.filePath("first.artcamproj");
    QVERIFY(writeStudioProject(first.toStdString(), written).ok);

    Document doc;
    Session session(&doc, nullptr);
    session.setInteractive(false);
    QSignalSpy errors(&session, &Session::errorOccurred);
    session.openPath(first);
    QTRY_VERIFY_WITH_TIMEOUT(doc.photo() != nullptr || !errors.isEmpty(), 20000);
    QVERIFY(errors.isEmpty());
    QVERIFY(sameLines(doc.lines(), written.lines));
    QVERIFY2(doc.fit().status.ok, doc.fit().status.message.c_str());
    const QString second = dir_.filePath("second.artcamproj");
    QVERIFY(ui::test::saveAndWait(session, second));
    const Result<StudioProject> back = readStudioProject(second.toStdString());
    QVERIFY2(back.ok(), back.status.message.c_str());
    QVERIFY(sameLines(back->lines, written.lines));

    // Lines traced in the studio: saved, reopened, the same lines and camera.
    Canvas canvas(&doc);
    canvas.setTool(std::make_unique<LineTool>(&canvas, &doc));
    canvas.resize(800, 600);
    canvas.show();
    QVERIFY(QTest::qWaitForWindowExposed(&canvas));
    for (const Eigen::Vector2d& p : edge({60, 120}, {420, 140}, 3))
      test::click(&canvas, canvas.view().widgetFromImage(QPointF(p.x(), p.y())).toPoint());
    QTest::keyClick(&canvas, Qt::Key_Enter);
    QCOMPARE(doc.lines().size(), written.lines.size() + 1);
    QVERIFY(ui::test::saveAndWait(session, second));
    Document doc2;
    Session session2(&doc2, nullptr);
    session2.setInteractive(false);
    session2.openPath(second);
    QTRY_VERIFY_WITH_TIMEOUT(doc2.photo() != nullptr, 20000);
    QVERIFY(sameLines(doc2.lines(), doc.lines()));
    QVERIFY(doc2.camera().stages().at(0).q == doc.camera().stages().at(0).q);
    QVERIFY(!doc2.isModified());
  }
};

QTEST_MAIN(TestLineTool)
#include "test_line_tool.moc"
