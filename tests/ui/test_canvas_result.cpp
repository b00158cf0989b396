// SPDX-License-Identifier: Apache-2.0
// The main canvas shows the preview worker's result: Photo/Result/Split/Onion and `\`; in
// Result mode the canvas's pixels are the controller's image and the photo shifted by a
// translation camera (an independent truth); while a render is in flight the last result stays,
// and a new photo never shows the old one's result nor itself in its place; over the result the
// pair tool moves targets as they are and sources through the camera's inverse (a translation
// here, so the truth is the click less the shift); the mode survives a project round trip.
#include "tests/ui/session_wait.h"
#include "tests/ui/ui_fixtures.h"
#include "ui/canvas.h"
#include "ui/commands.h"
#include "ui/document.h"
#include "ui/main_window.h"
#include "ui/preview_controller.h"
#include "ui/project_file.h"
#include "ui/session.h"
#include "ui/tools/pair_tool.h"

#include "core/io/image_io.h"

#include <QAction>
#include <QDockWidget>
#include <QSlider>
#include <QStandardPaths>
#include <QTemporaryDir>
#include <QtTest/QtTest>

#include <array>
#include <cmath>

using namespace artcam;
using namespace artcam::ui;

namespace {

constexpr int kW = 320, kH = 240, kBlock = 40;

// Flat 40-px blocks of fully saturated colours, so sRGB display values are exactly 0 or 255
// and a translation by whole pixels moves them without any filtering.
QRgb blockColour(int x, int y) {
  static const std::array<QRgb, 8> palette = {
      qRgb(255, 0, 0),   qRgb(0, 255, 0),   qRgb(0, 0, 255),     qRgb(255, 255, 0),
      qRgb(0, 255, 255), qRgb(255, 0, 255), qRgb(255, 255, 255), qRgb(0, 0, 0)};
  return palette[static_cast<size_t>((x / kBlock + 3 * (y / kBlock)) % 8)];
}

PhotoPtr blockPhoto() {
  ImageF img(kW, kH, 3);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const QRgb c = blockColour(x, y);
      float* p = img.pixel(x, y);
      p[0] = qRed(c) / 255.0f;
      p[1] = qGreen(c) / 255.0f;
      p[2] = qBlue(c) / 255.0f;
    }
  LoadedImage loaded;
  loaded.image = std::move(img);
  loaded.info.path = "blocks.png";
  return makePhoto(QStringLiteral("blocks.png"), std::move(loaded));
}

PhotoPtr uniformPhoto(int w, int h) {
  ImageF img(w, h, 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c) img.pixel(x, y)[c] = 1.0f;
  LoadedImage loaded;
  loaded.image = std::move(img);
  loaded.info.path = "white.png";
  return makePhoto(QStringLiteral("white.png"), std::move(loaded));
}

// Four pairs moved by `d` (corners, away from the sample points below): a translation camera.
std::vector<Pair> shiftedPairs(const Eigen::Vector2d& d) {
  std::vector<Pair> out;
  for (const Eigen::Vector2d& s : {Eigen::Vector2d(10, 10), Eigen::Vector2d(kW - 10, 10),
                                   Eigen::Vector2d(10, kH - 10), Eigen::Vector2d(kW - 10, kH - 10)})
    out.push_back({s, s + d, true});
  return out;
}

// Image points in block interiors (block centres moved by d), clear of the corner pairs and of
// the mode badge at the top.
std::vector<QPointF> samplePoints(const Eigen::Vector2d& d) {
  std::vector<QPointF> out;
  for (const auto& [bx, by] : {std::pair{1, 1}, {2, 2}, {3, 1}, {4, 3}, {5, 2}, {2, 3}})
    out.emplace_back(bx * kBlock + kBlock / 2 + d.x(), by * kBlock + kBlock / 2 + d.y());
  return out;
}

bool near(QRgb a, QRgb b, int tolerance = 2) {
  return std::abs(qRed(a) - qRed(b)) <= tolerance && std::abs(qGreen(a) - qGreen(b)) <= tolerance &&
         std::abs(qBlue(a) - qBlue(b)) <= tolerance;
}

QString rgb(QRgb c) { return QString("(%1, %2, %3)").arg(qRed(c)).arg(qGreen(c)).arg(qBlue(c)); }

QRgb canvasPixel(const QImage& grabbed, const Canvas& canvas, const QPointF& image_point) {
  const QPointF w = canvas.view().widgetFromImage(image_point);
  return grabbed.pixel(static_cast<int>(std::floor(w.x())), static_cast<int>(std::floor(w.y())));
}

// The controller's image at a photo pixel position (the result may be smaller than the photo).
QRgb resultPixel(const QImage& result, const QPointF& image_point, int frame_w, int frame_h) {
  const QImage rgba = result.convertToFormat(QImage::Format_RGB32);
  return rgba.pixel(static_cast<int>(image_point.x() * result.width() / frame_w),
                    static_cast<int>(image_point.y() * result.height() / frame_h));
}

bool isChecker(QRgb c) { return near(c, qRgb(90, 90, 90)) || near(c, qRgb(120, 120, 120)); }

struct Rig {
  Document doc;
  PreviewController preview{&doc};
  Canvas canvas{&doc};

  Rig() {
    canvas.setPreview(&preview);
    canvas.setTool(std::make_unique<PairTool>(&canvas, &doc));
    canvas.resize(800, 600);
    canvas.show();
  }
};

}  // namespace

class TestCanvasResult : public QObject {
  Q_OBJECT

 private slots:
  void initTestCase() { QStandardPaths::setTestModeEnabled(true); }

  void modesSwitchAndBackslashToggles() {
    MainWindow window;
    window.session()->setInteractive(false);
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    Canvas* canvas = window.canvas();
    QCOMPARE(canvas->viewMode(), CanvasViewMode::Result);  // the default
    // The Preview dock is optional now: hidden, but still offered in the View menu.
    auto* dock = window.findChild<QDockWidget*>("previewDock");
    QVERIFY(dock && !dock->isVisible());
    dock->toggleViewAction()->trigger();
    QVERIFY(dock->isVisible());

    canvas->setFocus();
    QTest::keyClick(&window, Qt::Key_Backslash);
    QCOMPARE(canvas->viewMode(), CanvasViewMode::Photo);
    QTest::keyClick(&window, Qt::Key_Backslash);
    QCOMPARE(canvas->viewMode(), CanvasViewMode::Result);
    QTest::keyClick(&window, Qt::Key_3, Qt::AltModifier);
    QCOMPARE(canvas->viewMode(), CanvasViewMode::Split);
    QTest::keyClick(&window, Qt::Key_Backslash);
    QCOMPARE(canvas->viewMode(), CanvasViewMode::Photo);
    QTest::keyClick(&window, Qt::Key_Backslash);  // back to the last result view, not Result
    QCOMPARE(canvas->viewMode(), CanvasViewMode::Split);
    QTest::keyClick(&window, Qt::Key_4, Qt::AltModifier);
    QCOMPARE(canvas->viewMode(), CanvasViewMode::Onion);
    QTest::keyClick(&window, Qt::Key_1, Qt::AltModifier);
    QCOMPARE(canvas->viewMode(), CanvasViewMode::Photo);
    QTest::keyClick(&window, Qt::Key_Backslash);
    QCOMPARE(canvas->viewMode(), CanvasViewMode::Onion);
    QTest::keyClick(&window, Qt::Key_2, Qt::AltModifier);
    QCOMPARE(canvas->viewMode(), CanvasViewMode::Result);

    // The menu follows the canvas's state, whoever sets it; the slider sets the onion opacity.
    canvas->setViewMode(CanvasViewMode::Split);
    QVERIFY(window.findChild<QAction*>("canvasMode_split")->isChecked());
    QVERIFY(!window.findChild<QAction*>("canvasMode_result")->isChecked());
    auto* slider = window.findChild<QSlider*>("onionOpacitySlider");
    QVERIFY(slider);
    slider->setValue(30);
    QCOMPARE(canvas->viewState().onion_opacity, 0.3);
    canvas->setOnionOpacity(0.8);
    QCOMPARE(slider->value(), 80);
  }

  void resultPixelsAreTheControllersImageAndTheShiftedPhoto() {
    Rig rig;
    QVERIFY(QTest::qWaitForWindowExposed(&rig.canvas));
    const Eigen::Vector2d d(24, 16);
    rig.doc.reset(blockPhoto(), shiftedPairs(d), ModelClass::Translation);
    QVERIFY(rig.doc.fit().status.ok);
    QVERIFY(test::waitForNewestPreview(rig.preview));
    QCOMPARE(rig.canvas.shownMode(), CanvasViewMode::Result);

    QImage shown = rig.canvas.grab().toImage();
    shown.save(QDir::temp().filePath("artcam_canvas_result.png"));  // for a look by hand
    for (const QPointF& p : samplePoints(d)) {
      // The result at p is the photo at p − d (a translation camera moves content by d).
      const QRgb expected =
          blockColour(static_cast<int>(p.x() - d.x()), static_cast<int>(p.y() - d.y()));
      const QRgb got = canvasPixel(shown, rig.canvas, p);
      QVERIFY2(near(got, expected), qPrintable(QString("result at (%1, %2): %3, expected %4")
                                                   .arg(p.x())
                                                   .arg(p.y())
                                                   .arg(rgb(got), rgb(expected))));
      const QRgb controller = resultPixel(rig.preview.image(), p, kW, kH);
      QVERIFY2(near(got, controller),
               qPrintable(QString("canvas %1, controller %2").arg(rgb(got), rgb(controller))));
      // The photo at p has another colour, so the comparison tells the two pictures apart.
      QVERIFY(!near(blockColour(static_cast<int>(p.x()), static_cast<int>(p.y())), expected));
    }
    // Where p − d is off the photo there is no preimage: the checkerboard, not the photo.
    QVERIFY(isChecker(canvasPixel(shown, rig.canvas, QPointF(8, 120))));

    // Photo mode shows the photo itself at the same image points, through the same transform.
    rig.canvas.setViewMode(CanvasViewMode::Photo);
    shown = rig.canvas.grab().toImage();
    for (const QPointF& p : samplePoints(d))
      QVERIFY(near(canvasPixel(shown, rig.canvas, p),
                   blockColour(static_cast<int>(p.x()), static_cast<int>(p.y()))));

    // Split: photo left of the divider, result right; Onion: the two mixed by the opacity.
    rig.canvas.setViewMode(CanvasViewMode::Split);
    rig.canvas.setSplit(0.5);
    shown = rig.canvas.grab().toImage();
    shown.save(QDir::temp().filePath("artcam_canvas_split.png"));
    for (const QPointF& p : samplePoints(d)) {
      const bool left = rig.canvas.view().widgetFromImage(p).x() < rig.canvas.dividerX() - 2;
      const bool right = rig.canvas.view().widgetFromImage(p).x() > rig.canvas.dividerX() + 2;
      const QPointF from = left ? p : p - QPointF(d.x(), d.y());
      if (left || right)
        QVERIFY(near(canvasPixel(shown, rig.canvas, p),
                     blockColour(static_cast<int>(from.x()), static_cast<int>(from.y()))));
    }
    rig.canvas.setViewMode(CanvasViewMode::Onion);
    rig.canvas.setOnionOpacity(0.5);
    shown = rig.canvas.grab().toImage();
    for (const QPointF& p : samplePoints(d)) {
      const QRgb a = blockColour(static_cast<int>(p.x()), static_cast<int>(p.y()));
      const QRgb b = blockColour(static_cast<int>(p.x() - d.x()), static_cast<int>(p.y() - d.y()));
      const QRgb mix =
          qRgb((qRed(a) + qRed(b)) / 2, (qGreen(a) + qGreen(b)) / 2, (qBlue(a) + qBlue(b)) / 2);
      QVERIFY2(near(canvasPixel(shown, rig.canvas, p), mix, 3),
               qPrintable(rgb(canvasPixel(shown, rig.canvas, p)) + " vs " + rgb(mix)));
    }
  }

  void renderInFlightShowsTheLastResultAndANewPhotoNeverTheOld() {
    Rig rig;
    QVERIFY(QTest::qWaitForWindowExposed(&rig.canvas));
    const Eigen::Vector2d d(24, 16);
    rig.doc.reset(blockPhoto(), shiftedPairs(d), ModelClass::Translation);
    QVERIFY(test::waitForNewestPreview(rig.preview));

    // A new camera: until its render arrives, the canvas keeps the last result (not blank, not
    // the photo). grab() paints without running the event loop, so no result arrives meanwhile.
    const Eigen::Vector2d d2(-16, 8);
    std::vector<int> all = {0, 1, 2, 3};
    rig.doc.undoStack()->push(
        new MovePairsCommand(&rig.doc, all, rig.doc.pairs(), shiftedPairs(d2), 0, "shift"));
    QVERIFY(rig.preview.requestedGeneration() > rig.preview.imageGeneration());
    QImage shown = rig.canvas.grab().toImage();
    for (const QPointF& p : samplePoints(d))
      QVERIFY(near(canvasPixel(shown, rig.canvas, p),
                   blockColour(static_cast<int>(p.x() - d.x()), static_cast<int>(p.y() - d.y()))));
    QVERIFY(test::waitForNewestPreview(rig.preview));
    shown = rig.canvas.grab().toImage();
    for (const QPointF& p : samplePoints(d2))
      QVERIFY(
          near(canvasPixel(shown, rig.canvas, p),
               blockColour(static_cast<int>(p.x() - d2.x()), static_cast<int>(p.y() - d2.y()))));

    // A new photo (white): before its first result the canvas shows neither the
    // old photo's result nor the new photo, only the checkerboard under "Rendering…".
    rig.doc.reset(uniformPhoto(kW, kH), shiftedPairs(d), ModelClass::Translation);
    QVERIFY(!rig.preview.image().isNull());  // the controller still holds the old result
    shown = rig.canvas.grab().toImage();
    for (const QPointF& p : samplePoints(d)) QVERIFY(isChecker(canvasPixel(shown, rig.canvas, p)));
    QVERIFY(test::waitForNewestPreview(rig.preview));
    shown = rig.canvas.grab().toImage();
    for (const QPointF& p : samplePoints(d))
      QVERIFY(near(canvasPixel(shown, rig.canvas, p), qRgb(255, 255, 255)));
  }

  void overTheResultThePairToolEditsThroughTheInverse() {
    Rig rig;
    QVERIFY(QTest::qWaitForWindowExposed(&rig.canvas));
    // Sources and targets far apart, so a press picks one of them unambiguously.
    std::vector<Pair> pairs;
    for (const auto& [x, y] : {std::pair{60.0, 60.0}, {250.0, 70.0}, {70.0, 180.0}, {240.0, 170.0}})
      pairs.push_back({{x, y}, {x + 30.0, y + 20.0}, true});
    rig.doc.reset(blockPhoto(), pairs, ModelClass::Affine);
    QCOMPARE(rig.canvas.shownMode(), CanvasViewMode::Result);
    const double scale = rig.canvas.view().scale();
    const QPoint delta(24, -18);

    // Dragging a target moves that target by the drag in image pixels; its source stays.
    const Pair before = rig.doc.pairs()[1];
    const QPoint t = test::widgetPoint(rig.canvas, before.target);
    test::drag(&rig.canvas, t, t + delta);
    QTRY_VERIFY(!rig.doc.fitPending());
    const Pair after = rig.doc.pairs()[1];
    QVERIFY(after.source == before.source);
    QVERIFY((after.target - before.target - Eigen::Vector2d(delta.x(), delta.y()) / scale).norm() <
            1e-9);
    rig.doc.undoStack()->undo();
    QVERIFY(rig.doc.pairs()[1] == before);

    // A source dragged over the result moves by the cursor's motion mapped back through the
    // camera: a translation by (30, 20), whose inverse moves points as the cursor moves.
    const QPoint s = test::widgetPoint(rig.canvas, before.source);
    test::drag(&rig.canvas, s, s + delta);
    QTRY_VERIFY(!rig.doc.fitPending());
    QVERIFY(
        (rig.doc.pairs()[1].source - before.source - Eigen::Vector2d(delta.x(), delta.y()) / scale)
            .norm() < 1e-6);
    QVERIFY(rig.doc.pairs()[1].target == before.target);
    rig.doc.undoStack()->undo();
    QVERIFY(rig.doc.pairs()[1] == before);

    // The same drag where the photo shows moves the source by the drag in photo pixels.
    rig.canvas.setViewMode(CanvasViewMode::Photo);
    test::drag(&rig.canvas, s, s + delta);
    QTRY_VERIFY(!rig.doc.fitPending());
    QVERIFY(
        (rig.doc.pairs()[1].source - before.source - Eigen::Vector2d(delta.x(), delta.y()) / scale)
            .norm() < 1e-9);
    QVERIFY(rig.doc.pairs()[1].target == before.target);
    rig.doc.undoStack()->undo();

    // A new pair placed wholly on the result: the source click is the photo pixel the result
    // shows there (the click less the translation), the target click is in result pixels; one
    // undo step. On the photo (`\`) the source click is the photo pixel itself.
    rig.canvas.setViewMode(CanvasViewMode::Result);
    auto* tool = dynamic_cast<PairTool*>(rig.canvas.tool());
    const QPoint empty = test::widgetPoint(rig.canvas, {160, 120});
    const Eigen::Vector2d empty_px(rig.canvas.view().imageFromWidget(empty).x(),
                                   rig.canvas.view().imageFromWidget(empty).y());
    test::click(&rig.canvas, empty);
    QVERIFY(tool->hasPendingSource());
    const QPoint target_at = test::widgetPoint(rig.canvas, {180, 100});
    test::click(&rig.canvas, target_at);
    QCOMPARE(rig.doc.pairs().size(), size_t{5});
    Pair added = rig.doc.pairs().back();
    QVERIFY((added.source - (empty_px - Eigen::Vector2d(30.0, 20.0))).norm() < 1e-6);
    QVERIFY((added.target - Eigen::Vector2d(rig.canvas.view().imageFromWidget(target_at).x(),
                                            rig.canvas.view().imageFromWidget(target_at).y()))
                .norm() < 1e-9);
    rig.doc.undoStack()->undo();
    QCOMPARE(rig.doc.pairs().size(), size_t{4});
    rig.canvas.toggleBeforeAfter();
    QCOMPARE(rig.canvas.shownMode(), CanvasViewMode::Photo);
    test::click(&rig.canvas, empty);
    rig.canvas.toggleBeforeAfter();
    test::click(&rig.canvas, target_at);
    QCOMPARE(rig.doc.pairs().size(), size_t{5});
    added = rig.doc.pairs().back();
    QVERIFY((added.source - empty_px).norm() < 1e-9);
    rig.doc.undoStack()->undo();
    QCOMPARE(rig.doc.pairs().size(), size_t{4});
  }

  void splitDividerDragsOnTheCanvas() {
    Rig rig;
    QVERIFY(QTest::qWaitForWindowExposed(&rig.canvas));
    rig.doc.reset(blockPhoto(), shiftedPairs({24, 16}), ModelClass::Translation);
    rig.canvas.setViewMode(CanvasViewMode::Split);
    rig.canvas.setSplit(0.5);
    const std::vector<Pair> pairs = rig.doc.pairs();
    const QPoint handle(rig.canvas.width() / 2, rig.canvas.height() / 2);
    test::drag(&rig.canvas, handle, handle - QPoint(200, 0));
    QCOMPARE(rig.canvas.viewState().split, (rig.canvas.width() / 2 - 200.0) / rig.canvas.width());
    test::sendMouse(&rig.canvas, QEvent::MouseButtonPress, QPoint(600, 100), Qt::LeftButton,
                    Qt::LeftButton, Qt::AltModifier);
    test::sendMouse(&rig.canvas, QEvent::MouseButtonRelease, QPoint(600, 100), Qt::LeftButton,
                    Qt::NoButton, Qt::AltModifier);
    QCOMPARE(rig.canvas.viewState().split, 600.0 / rig.canvas.width());
    QVERIFY(rig.doc.pairs() == pairs);  // the tool saw none of it
  }

  void viewStateRoundTrip() {
    // The project file keeps the canvas state; a project without it reads as the defaults.
    Project p;
    p.photo_path = "/tmp/x.png";
    p.view.canvas = {CanvasViewMode::Photo, CanvasViewMode::Onion, 0.25, 0.75};
    const Result<Project> back =
        parseProject(projectToJson(p, "/tmp/a.artcamproj"), "/tmp/a.artcamproj");
    QVERIFY2(back.ok(), back.status.message.c_str());
    QVERIFY(back->view.canvas == p.view.canvas);
    const Result<Project> old =
        parseProject(R"({"format":"artcam-studio-project","version":1,"photo":"x.png",)"
                     R"("view":{"scale":1,"centre":[1,2],"preview_mode":2,"opacity":0.5}})",
                     "/tmp/old.artcamproj");
    QVERIFY2(old.ok(), old.status.message.c_str());
    QVERIFY(old->view.canvas == CanvasViewState{});
    QCOMPARE(old->view.canvas.mode, CanvasViewMode::Result);
    const Result<Project> bad =
        parseProject(R"({"format":"artcam-studio-project","version":1,"photo":"x.png",)"
                     R"("view":{"canvas":{"mode":"wipe"}}})",
                     "/tmp/bad.artcamproj");
    QVERIFY(!bad.ok());
    QVERIFY(QString::fromStdString(bad.status.message).contains("/view/canvas/mode"));

    // Through the window: saved from one canvas, restored on another.
    QTemporaryDir dir;
    QVERIFY(dir.isValid());
    const QString photo = dir.filePath("blocks.png");
    QVERIFY(writeImage(photo.toStdString(), blockPhoto()->full.image).ok);
    const QString project = dir.filePath("canvas.artcamproj");
    CanvasViewState state;
    {
      MainWindow window;
      window.session()->setInteractive(false);
      window.session()->openPath(photo);
      QTRY_VERIFY_WITH_TIMEOUT(window.document()->photo() != nullptr, 30000);
      window.canvas()->setViewMode(CanvasViewMode::Onion);
      window.canvas()->setOnionOpacity(0.3);
      window.canvas()->setViewMode(CanvasViewMode::Split);
      window.canvas()->setSplit(0.625);
      window.canvas()->toggleBeforeAfter();  // Photo, with Split to come back to
      state = window.canvas()->viewState();
      QVERIFY(ui::test::saveAndWait(*window.session(), project));
    }
    QCOMPARE(state.mode, CanvasViewMode::Photo);
    QCOMPARE(state.compare_mode, CanvasViewMode::Split);
    MainWindow window;
    window.session()->setInteractive(false);
    QCOMPARE(window.canvas()->viewMode(), CanvasViewMode::Result);
    window.session()->openPath(project);
    QTRY_VERIFY_WITH_TIMEOUT(window.document()->photo() != nullptr, 30000);
    QTRY_VERIFY(window.canvas()->viewState() == state);
  }
};

QTEST_MAIN(TestCanvasResult)
#include "test_canvas_result.moc"
