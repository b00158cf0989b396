// SPDX-License-Identifier: Apache-2.0
// What the user sees is what they get: the bundled project resources/depth-effects.artcamproj
// (coffee.png, two painted depth planes, aerial perspective then depth of field) opened in the
// studio shows a preview that matches its full-resolution export scaled down; saved and reopened
// it exports the same pixels; and `artcam export` on the saved file writes those pixels too.
#include "core/io/image_io.h"
#include "tests/app/cli_run.h"
#include "tests/ui/session_wait.h"
#include "tests/ui/ui_fixtures.h"
#include "ui/depth_model.h"
#include "ui/document.h"
#include "ui/export_job.h"
#include "ui/image_convert.h"
#include "ui/main_window.h"
#include "ui/preview_controller.h"
#include "ui/session.h"

#include <QFile>
#include <QSignalSpy>
#include <QTemporaryDir>
#include <QtTest/QtTest>

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
    for (const char* f : {"coffee.png", "depth-effects.artcamproj"})
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
    QVERIFY(QFile::copy(QString(ARTCAM_RESOURCES_DIR) + "/sample.artcamproj",
                        dir_.filePath("sample.artcamproj")));
    MainWindow window;
    window.session()->setInteractive(false);
    window.session()->openProject(dir_.filePath("sample.artcamproj"));
    Document* doc = window.document();
    QVERIFY(QTest::qWaitFor([doc] { return doc->photo() && doc->photo()->hasFullImage(); }, 30000));
    QVERIFY(artcam::ui::test::waitForNewestPreview(*window.preview()));
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
