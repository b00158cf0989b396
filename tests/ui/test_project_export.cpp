// SPDX-License-Identifier: Apache-2.0
// What the user sees is what they get: the bundled project resources/depth-effects.artcamproj
// (coffee.png, two painted depth planes, aerial perspective then depth of field) opened in the
// studio shows a preview that matches its full-resolution export scaled down; saved and reopened
// it exports the same pixels; and `artcam export` on the saved file writes those pixels too.
#include "core/colour/composite.h"
#include "core/io/image_io.h"
#include "tests/app/cli_run.h"
#include "tests/ui/session_wait.h"
#include "tests/ui/ui_fixtures.h"
#include "ui/depth_model.h"
#include "ui/document.h"
#include "ui/export_job.h"
#include "ui/image_convert.h"
#include "ui/main_window.h"
#include "ui/panels/effects_panel.h"
#include "ui/preview_controller.h"
#include "ui/session.h"

#include <QComboBox>
#include <QFile>
#include <QSignalSpy>
#include <QTemporaryDir>
#include <QtTest/QtTest>

#include <algorithm>
#include <cmath>
#include <memory>

using namespace artcam;
using namespace artcam::ui;

namespace {

// Opens `path` in the window and waits for the photo, the depth planes and a final preview of
// the whole camera (the depth reaches the preview through the overlay's throttled raster).
bool openAndSettle(MainWindow& window, const QString& path) {
  window.session()->setInteractive(false);
  window.session()->openProject(path);
  Document* doc = window.document();
  if (!QTest::qWaitFor([doc] { return doc->photo() && doc->depth()->layerCount() == 2; }, 30000))
    return false;
  if (!QTest::qWaitFor([doc] { return readsDepth(doc->artcam()); }, 10000)) return false;
  QTest::qWait(200);  // past the overlay's 40 ms throttle: the preview has its depth
  return artcam::ui::test::waitForNewestPreview(*window.preview());
}

// Opens `path` (no prompts) and waits for the whole photo and the newest preview.
bool openWhole(MainWindow& window, const QString& path) {
  window.session()->setInteractive(false);
  window.session()->openProject(path);
  Document* doc = window.document();
  return QTest::qWaitFor([doc] { return doc->photo() && doc->photo()->hasFullImage(); }, 30000) &&
         artcam::ui::test::waitForNewestPreview(*window.preview());
}

ImageF exportNow(const Document& doc) {
  const ImageF depth = doc.depth()->rasterise();
  RenderSummary summary;
  return ExportJob::render(doc.photo()->full, &depth, doc.artcam(), {}, {}, &summary);
}

}  // namespace

class TestProjectExport : public QObject {
  Q_OBJECT

 private slots:
  void initTestCase() {
    QVERIFY(dir_.isValid());
    for (const char* f : {"coffee.png", "depth-effects.artcamproj", "sample.artcamproj"})
      QVERIFY(QFile::copy(QString(ARTCAM_RESOURCES_DIR) + "/" + f, dir_.filePath(f)));
  }

  void previewMatchesTheExport() {
    MainWindow window;
    // The camera reads depth and the depth raster arrives a moment later: the preview waits for
    // it instead of failing once ("Preview failed: this camera reads depth" on every reopen).
    QSignalSpy failures(window.preview(), &PreviewController::renderFailed);
    QVERIFY(openAndSettle(window, dir_.filePath("depth-effects.artcamproj")));
    QTest::qWait(100);  // a failure would arrive queued from the worker
    QVERIFY2(failures.isEmpty(),
             qPrintable(failures.isEmpty() ? QString() : failures.first().first().toString()));
    Document* doc = window.document();
    QVERIFY2(doc->artcamNote().empty(), doc->artcamNote().c_str());
    QCOMPARE(doc->effects().size(), size_t{2});
    const QImage preview = window.preview()->image();
    const ImageF full = exportNow(*doc);
    QCOMPARE(full.width, 600);
    const QImage scaled = qimageFromLinear(boxDownscale(full, std::max(preview.width(), preview.height())));
    QCOMPARE(scaled.size(), preview.size());
    const double off = artcam::ui::test::meanDifference(scaled, preview);
    // Without the effects the picture is far from it: the comparison can tell.
    const QImage photo = qimageFromLinear(boxDownscale(doc->photo()->full.image, scaled.width()));
    const double plain = artcam::ui::test::meanDifference(photo, preview);
    qInfo("preview vs downscaled export: %.2f codes; vs the plain photo: %.2f", off, plain);
    QVERIFY2(off < 3.0, qPrintable(QString("preview vs export: %1 codes").arg(off)));
    QVERIFY2(plain > 4 * off + 2.0, qPrintable(QString("photo vs preview: %1 codes").arg(plain)));
  }

  // A geometry-only project on a photo the canvas shows at full size (600×400): the canvas at
  // 100 % and the export are the same pixels, to a code (the export once used bicubic where
  // the canvas and `artcam warp` use bilinear: visibly sharper than what the user saw).
  void canvasAtFullSizeIsTheExport() {
    MainWindow window;
    QVERIFY(openWhole(window, dir_.filePath("sample.artcamproj")));
    Document* doc = window.document();
    const QImage canvas = window.preview()->image().convertToFormat(QImage::Format_RGBA8888);
    RenderSummary summary;
    const ImageF full = ExportJob::render(doc->photo()->full, nullptr, doc->artcam(), {}, {}, &summary);
    const QImage exported = qimageFromLinear(full).convertToFormat(QImage::Format_RGBA8888);
    QCOMPARE(canvas.size(), exported.size());
    QCOMPARE(canvas.width(), 600);
    int worst = 0;
    long long compared = 0, over = 0;
    for (int y = 0; y < canvas.height(); ++y) {
      const uchar* p = canvas.constScanLine(y);
      const uchar* q = exported.constScanLine(y);
      for (int x = 0; x < canvas.width(); ++x, p += 4, q += 4) {
        if (p[3] != 255 || q[3] != 255) continue;
        ++compared;
        for (int c = 0; c < 3; ++c) {
          const int d = std::abs(int(p[c]) - int(q[c]));
          worst = std::max(worst, d);
          over += d > 1;
        }
      }
    }
    QVERIFY2(compared > 100000, qPrintable(QString::number(compared)));
    // One code, but for a few values on the sharpest edges: the canvas trusts the rational
    // kernel's certified cells to kPreviewCertifyTolerancePx (core/render/preview.h), the
    // export to the full tolerance, and a few hundredths of a pixel on an edge of 40 codes per
    // pixel is a second code (23 of 720 000 values on this photo).
    QVERIFY2(worst <= 2 && over * 10000 < compared * 3,
             qPrintable(QString("canvas vs export: worst %1 codes, %2 values over 1").arg(worst).arg(over)));
  }

  // The colour block's compositing in the studio: a project with a second image and a screen
  // effect shows, exports and saves the screen of the photo and the second image, A + B − A·B
  // in linear light per pixel (computed here from the two files, not by the renderer), and
  // `artcam export` of the saved project writes the same pixels; removing the second image
  // (undoably) leaves the effect out, saying why.
  void compositingWithASecondImage() {
    ImageF second(600, 400, 3);
    for (int y = 0; y < 400; ++y)
      for (int x = 0; x < 600; ++x) {
        float* p = second.pixel(x, y);
        p[0] = 0.6f * x / 600.0f;
        p[1] = 0.4f * y / 400.0f;
        p[2] = 0.25f;
      }
    QVERIFY(writeImage(dir_.filePath("second.png").toStdString(), second).ok);
    const auto& ops = compositeOpNames();
    const int screen = static_cast<int>(std::find(ops.begin(), ops.end(), "screen") - ops.begin());
    QVERIFY(screen < static_cast<int>(ops.size()));
    QFile project(dir_.filePath("screen.artcamproj"));
    QVERIFY(project.open(QIODevice::WriteOnly));
    project.write(QStringLiteral(R"({"format": "artcam-studio-project", "version": 5,
      "photo": "coffee.png", "model": "auto", "pairs": [],
      "effects": [{"effect": "composite", "params": {"op": [%1], "amount": [1]}}],
      "second": {"path": "second.png"}})")
                      .arg(screen)
                      .toUtf8());
    project.close();

    MainWindow window;
    QVERIFY(openWhole(window, dir_.filePath("screen.artcamproj")));
    Document* doc = window.document();
    // The second image is read after the photo: the preview that shows it comes after it.
    QVERIFY(QTest::qWaitFor([doc] { return doc->secondImage().has_value(); }, 30000));
    QVERIFY(artcam::ui::test::waitForNewestPreview(*window.preview()));
    QVERIFY2(doc->artcamNote().empty(), doc->artcamNote().c_str());
    RenderSummary summary;
    const ImageF shown = ExportJob::render(doc->photo()->full, nullptr, doc->artcam(), {}, {},
                                           &summary, doc->secondImage()->image.get());
    const Result<LoadedImage> a = readImage(dir_.filePath("coffee.png").toStdString());
    const Result<LoadedImage> b = readImage(dir_.filePath("second.png").toStdString());
    QVERIFY(a.ok() && b.ok());
    double worst = 0.0, moved = 0.0;
    for (int y = 0; y < 400; y += 7)
      for (int x = 0; x < 600; x += 7)
        for (int c = 0; c < 3; ++c) {
          const double pa = a->image.pixel(x, y)[c], pb = b->image.pixel(x, y)[c];
          const double truth = pa + pb - pa * pb;
          worst = std::max(worst, std::abs(shown.pixel(x, y)[c] - truth));
          moved = std::max(moved, std::abs(truth - pa));
        }
    qInfo("screen in the studio's export vs A + B - A*B: max %.2e (the effect moves %.3f)", worst,
          moved);
    QVERIFY2(worst < 1e-4, qPrintable(QString::number(worst)));
    QVERIFY(moved > 0.2);
    // The preview shows it: close to the export scaled down, far from the plain photo.
    const QImage preview = window.preview()->image();
    const QImage scaled =
        qimageFromLinear(boxDownscale(shown, std::max(preview.width(), preview.height())));
    const double off = artcam::ui::test::meanDifference(scaled, preview);
    const double plain = artcam::ui::test::meanDifference(
        qimageFromLinear(boxDownscale(doc->photo()->full.image, scaled.width())), preview);
    QVERIFY2(off < 3.0 && plain > 4 * off + 2.0,
             qPrintable(QString("preview vs export %1, vs photo %2").arg(off).arg(plain)));

    // Saved, the project keeps the second image; the CLI exports the same pixels.
    const QString saved = dir_.filePath("screen-saved.artcamproj");
    QVERIFY(ui::test::saveAndWait(*window.session(), saved));
    QFile back(saved);
    QVERIFY(back.open(QIODevice::ReadOnly));
    QVERIFY(back.readAll().contains("\"second\""));
    const QString out = dir_.filePath("screen.exr");
    const artcam::test::CliRun r =
        artcam::test::artcamCli({"export", saved, "-o", out, "--bit-depth", "float"});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    const Result<LoadedImage> cli = readImage(out.toStdString());
    QVERIFY(cli.ok());
    double cli_worst = 0.0;
    for (size_t i = 0; i < shown.data.size(); ++i)
      cli_worst =
          std::max(cli_worst, static_cast<double>(std::abs(cli->image.data[i] - shown.data[i])));
    QVERIFY2(cli_worst < 1e-6, qPrintable(QString("CLI differs by %1").arg(cli_worst)));

    // Removed: the effect is left out and the note says why; undo brings it back.
    window.session()->removeSecondImage();
    QVERIFY(!doc->secondImage());
    QVERIFY2(QString::fromStdString(doc->artcamNote()).contains("second image"),
             doc->artcamNote().c_str());
    doc->undoStack()->undo();
    QVERIFY(doc->secondImage() && doc->artcamNote().empty());
  }

  // Marks in the studio: the Effects panel's finish is drawn by the preview, the export and the
  // saved project alike (the canvas shows the 600×400 photo whole, so the same pixels);
  // `artcam export` of the saved project writes the studio's export byte for byte, `--finish
  // none` the unmarked picture.
  void finishIsDrawnByPreviewExportAndProject() {
    MainWindow window;
    QVERIFY(openWhole(window, dir_.filePath("sample.artcamproj")));
    Document* doc = window.document();
    const QImage plain_preview = window.preview()->image();
    QVERIFY(doc->finish().empty());
    auto* box = window.findChild<EffectsPanel*>()->finishBox();
    box->setCurrentIndex(box->findData(QStringLiteral("pencil")));
    QCOMPARE(doc->finish(), std::string("pencil"));
    QVERIFY(artcam::ui::test::waitForNewestPreview(*window.preview()));
    const QImage marked_preview = window.preview()->image();
    ExportOptions options;
    options.finish = doc->finish();
    RenderSummary summary;
    const ImageF exported =
        ExportJob::render(doc->photo()->full, nullptr, doc->artcam(), options, {}, &summary);
    const QImage shown = qimageFromLinear(exported);
    QCOMPARE(shown.size(), marked_preview.size());
    const double off = artcam::ui::test::meanDifference(shown, marked_preview);
    const double marks = artcam::ui::test::meanDifference(plain_preview, marked_preview);
    qInfo("pencil: preview vs export %.2f codes; marked vs plain preview %.2f", off, marks);
    QVERIFY2(off < 1.0 && marks > 10.0,
             qPrintable(QString("preview vs export %1, marks %2").arg(off).arg(marks)));

    const QString saved = dir_.filePath("pencil.artcamproj");
    QVERIFY(ui::test::saveAndWait(*window.session(), saved));
    const QString out = dir_.filePath("pencil.exr");
    const artcam::test::CliRun r =
        artcam::test::artcamCli({"export", saved, "-o", out, "--bit-depth", "float"});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    const Result<LoadedImage> cli = readImage(out.toStdString());
    QVERIFY(cli.ok());
    QVERIFY(cli->image.data == exported.data);
    const artcam::test::CliRun none =
        artcam::test::artcamCli({"export", saved, "-o", dir_.filePath("none.exr"), "--bit-depth",
                                 "float", "--finish", "none"});
    QVERIFY2(none.exit_code == 0, qPrintable(none.err));
    const Result<LoadedImage> unmarked = readImage(dir_.filePath("none.exr").toStdString());
    const ImageF plain =
        ExportJob::render(doc->photo()->full, nullptr, doc->artcam(), {}, {}, &summary);
    QVERIFY(unmarked.ok() && unmarked->image.data == plain.data);
    const artcam::test::CliRun bad = artcam::test::artcamCli(
        {"export", saved, "-o", dir_.filePath("bad.png"), "--finish", "crayon"});
    QCOMPARE(bad.exit_code, 2);
    QVERIFY2(bad.err.contains("unknown --finish \"crayon\""), qPrintable(bad.err));

    // Undo takes the marks away again.
    doc->undoStack()->undo();
    QVERIFY(doc->finish().empty());
    QCOMPARE(box->currentIndex(), 0);
  }

  void saveReopenExportGivesTheSamePixels() {
    ImageF first;
    const QString saved = dir_.filePath("saved.artcamproj");
    {
      MainWindow window;
      QVERIFY(openAndSettle(window, dir_.filePath("depth-effects.artcamproj")));
      first = exportNow(*window.document());
      QVERIFY(ui::test::saveAndWait(*window.session(), saved));
    }
    MainWindow again;
    QVERIFY(openAndSettle(again, saved));
    const ImageF second = exportNow(*again.document());
    QVERIFY(second.data == first.data);

    // The command line renders the saved project to the same pixels (float EXR: no rounding).
    const QString out = dir_.filePath("cli.exr");
    const artcam::test::CliRun r = artcam::test::artcamCli(
        {"export", saved, "-o", out, "--bit-depth", "float", "--depth-out", dir_.filePath("d.exr"),
         "--camera-out", dir_.filePath("c.artcam")});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    const Result<LoadedImage> cli = readImage(out.toStdString());
    QVERIFY2(cli.ok(), cli.status.message.c_str());
    QCOMPARE(cli->image.width, first.width);
    QCOMPARE(cli->image.channels, first.channels);
    double worst = 0.0;
    for (size_t i = 0; i < first.data.size(); ++i)
      worst = std::max(worst, static_cast<double>(std::abs(cli->image.data[i] - first.data[i])));
    QVERIFY2(worst < 1e-6, qPrintable(QString("CLI differs by %1").arg(worst)));
    // The depth it wrote is the painted depth: the cup plane's 0.8 at the cup's centre.
    const Result<LoadedImage> depth = readImage(dir_.filePath("d.exr").toStdString());
    QVERIFY(depth.ok());
    QVERIFY(std::abs(depth->image.pixel(290, 140)[0] - 0.8f) < 1e-5f);
  }

 private:
  QTemporaryDir dir_;
};

QTEST_MAIN(TestProjectExport)
#include "test_project_export.moc"
