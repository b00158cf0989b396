// SPDX-License-Identifier: Apache-2.0
// A JPEG has no alpha: the pixels a barrel camera leaves without a preimage (the corners) are
// written white, not black, with the default "Keep transparent"; a chosen fill or crop is
// kept; and the status line says what the file holds, never transparent pixels it has not.
#include "core/effects/effect_table.h"
#include "core/io/image_io.h"
#include "tests/ui/ui_fixtures.h"
#include "ui/commands.h"
#include "ui/document.h"
#include "ui/export_options_dialog.h"
#include "ui/session.h"

#include <QRadioButton>
#include <QSignalSpy>
#include <QStandardPaths>
#include <QTemporaryDir>
#include <QtTest/QtTest>

using namespace artcam;
using namespace artcam::ui;

class TestExportFlatten : public QObject {
  Q_OBJECT

 private slots:
  void initTestCase() {
    QStandardPaths::setTestModeEnabled(true);
    QVERIFY(dir_.isValid());
    QSettings::setPath(QSettings::NativeFormat, QSettings::UserScope, dir_.filePath("settings"));
    QCoreApplication::setOrganizationName("ARTcamTest");
    QCoreApplication::setApplicationName("ExportFlatten");
  }

  void jpegCornersAreFilledNotBlack() {
    Document doc;
    Session session(&doc, nullptr);
    session.setInteractive(false);
    session.setExportOptions(ExportOptions{});  // keep transparent, as a first export
    doc.reset(ui::test::syntheticPhoto(320, 240));
    // Barrel: u' = u/(1 + 0.3 r²) pulls the corners in, so the target's corners have no
    // preimage (the corner's r² = 1.5625 in the normalised frame maps inside by 1/1.47).
    doc.undoStack()->push(new SetCameraCommand(
        &doc, buildEffect("barrel", {{"k", {-0.3}}}, doc.frame()), "Set camera"));

    auto exportTo = [&](const QString& name) -> std::pair<Result<LoadedImage>, QString> {
      QSignalSpy finished(&session, &Session::exportFinished);
      session.exportImage(dir_.filePath(name));
      if (!QTest::qWaitFor([&] { return finished.size() == 1; }, 60000))
        return {Result<LoadedImage>::failure("no export"), QString()};
      const QString message = finished.front().at(1).toString();
      if (!finished.front().at(0).toBool())
        return {Result<LoadedImage>::failure(message.toStdString()), message};
      return {readImage(dir_.filePath(name).toStdString()), message};
    };

    // The PNG keeps the corner transparent, which tells the corner is outside the picture.
    {
      const auto [png, message] = exportTo("keep.png");
      QVERIFY2(png.ok(), png.status.message.c_str());
      QCOMPARE(png->image.channels, 4);
      QCOMPARE(png->image.pixel(0, 0)[3], 0.0f);
      QVERIFY2(message.contains("transparent"), qPrintable(message));
    }
    // The JPEG: white (linear 1) at the corner, and the status says it was filled.
    {
      const auto [jpeg, message] = exportTo("keep.jpg");
      QVERIFY2(jpeg.ok(), jpeg.status.message.c_str());
      const float* corner = jpeg->image.pixel(0, 0);
      for (int c = 0; c < 3; ++c)
        QVERIFY2(corner[c] > 0.9f, qPrintable(QString::number(corner[c])));
      QVERIFY2(message.contains("filled"), qPrintable(message));
      QVERIFY2(!message.contains("transparent pixels"), qPrintable(message));
    }
    // A chosen fill colour is the one written; the status claims no transparent pixels.
    {
      ExportOptions red;
      red.fill = std::array<float, 4>{1.0f, 0.0f, 0.0f, 1.0f};
      session.setExportOptions(red);
      const auto [png, message] = exportTo("red.png");
      QVERIFY2(png.ok(), png.status.message.c_str());
      const float* corner = png->image.pixel(0, 0);
      QVERIFY(corner[0] > 0.99f && corner[1] < 0.01f && corner[2] < 0.01f);
      QVERIFY2(!message.contains("transparent"), qPrintable(message));
    }
    // Crop to the valid area: every pixel has a preimage, and the status says none is empty.
    {
      ExportOptions crop;
      crop.crop_to_valid = true;
      session.setExportOptions(crop);
      const auto [png, message] = exportTo("crop.png");
      QVERIFY2(png.ok(), png.status.message.c_str());
      QVERIFY(png->image.width < 320);
      QVERIFY2(!message.contains("transparent"), qPrintable(message));
    }
  }

  // The dialog for a JPEG does not offer what JPEG cannot hold.
  void jpegDialogOffersNoTransparency() {
    ExportOptionsDialog dialog(ExportOptions{}, "out.jpg");
    QRadioButton* keep = nullptr;
    for (QRadioButton* b : dialog.findChildren<QRadioButton*>())
      if (b->text().startsWith("Keep")) keep = b;
    QVERIFY(keep);
    QVERIFY(!keep->isEnabled());
    QVERIFY(dialog.options().fill.has_value());
    ExportOptionsDialog png_dialog(ExportOptions{}, "out.png");
    QVERIFY(!png_dialog.options().fill.has_value());
  }

 private:
  QTemporaryDir dir_;
};

QTEST_MAIN(TestExportFlatten)
#include "test_export_flatten.moc"
