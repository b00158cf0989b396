// SPDX-License-Identifier: Apache-2.0
// Lens ▸ From Database…: the dialog suggests from the photo's EXIF, searches as you type, and
// the session sets the camera `artcam lens camera` makes (the same core function, compared
// with a direct call), undoably, as the document's camera set by hand.
#include "tests/ui/ui_fixtures.h"
#include "ui/commands.h"
#include "ui/lens_dialog.h"
#include "ui/main_window.h"
#include "ui/session.h"

#include <QCheckBox>
#include <QDialogButtonBox>
#include <QDoubleSpinBox>
#include <QLineEdit>
#include <QListWidget>
#include <QMenuBar>
#include <QPushButton>
#include <QtTest/QtTest>

using namespace artcam;
using namespace artcam::ui;

namespace {
const char* const kG11 = "Canon PowerShot G11 & compatibles (Standard)";
const char* const kWide = "Canon EF-S 10-22mm f/3.5-4.5 USM";
}  // namespace

class TestLensDialog : public QObject {
  Q_OBJECT
  std::shared_ptr<const LensDatabase> db_;

 private slots:
  void initTestCase() {
    auto db = LensDatabase::load();
    QVERIFY2(db.ok(), db.status.message.c_str());
    db_ = *db.value;
  }

  void suggestsAndSearchesAsYouType() {
    LensHint hint;
    hint.camera_maker = "Canon";
    hint.camera_model = "Canon PowerShot G11";
    hint.focal_mm = 6.1;
    LensDialog dialog(db_, {600, 400}, hint);
    // From the EXIF: the G11's own lens, at the EXIF focal length.
    QVERIFY(dialog.lensList()->count() >= 1);
    QVERIFY(dialog.lensList()->item(0)->text().startsWith(kG11));
    QCOMPARE(dialog.focalField()->value(), 6.1);
    QCOMPARE(dialog.options().lens, std::string(kG11));

    // Typing narrows the list to the lenses holding every word, at each keystroke.
    QTest::keyClicks(dialog.searchField(), "canon 10-2");
    const int partial = dialog.lensList()->count();
    QTest::keyClicks(dialog.searchField(), "2");
    QVERIFY(dialog.lensList()->count() >= 1);
    QVERIFY(dialog.lensList()->count() <= partial);
    int wide_row = -1;
    for (int i = 0; i < dialog.lensList()->count(); ++i) {
      const QString t = dialog.lensList()->item(i)->text();
      QVERIFY2(t.contains("10-22"), qPrintable(t));
      if (t.startsWith(kWide)) wide_row = i;
    }
    QVERIFY(wide_row >= 0);
    dialog.lensList()->setCurrentRow(wide_row);
    // 6.1 mm is outside 10-22 mm: the focal length moves into the lens's range.
    QCOMPARE(dialog.focalField()->value(), 10.0);
    const LensCameraOptions o = dialog.options();
    QCOMPARE(o.lens, std::string(kWide));
    QCOMPARE(o.size.width, 600);

    // Nothing matches: nothing to accept.
    dialog.searchField()->setText("nosuchlensmakerxyz");
    QCOMPARE(dialog.lensList()->count(), 0);
    QVERIFY(dialog.options().lens.empty());
    auto* ok = dialog.findChild<QDialogButtonBox*>()->button(QDialogButtonBox::Ok);
    QVERIFY(!ok->isEnabled());
    // Cleared: the suggestions again.
    dialog.searchField()->clear();
    QVERIFY(dialog.lensList()->item(0)->text().startsWith(kG11));
  }

  void sessionSetsTheLensCameraUndoably() {
    Document doc;
    doc.reset(test::syntheticPhoto(600, 400));
    Session session(&doc, nullptr);
    session.setInteractive(false);
    QSignalSpy applied(&session, &Session::lensCameraApplied);
    LensCameraOptions o;
    o.lens = kG11;
    o.focal_mm = 6.1;
    session.applyLensCamera(o, db_);
    QTRY_COMPARE_WITH_TIMEOUT(applied.size(), 1, 60000);
    QVERIFY2(applied.front().at(0).toBool(), qPrintable(applied.front().at(1).toString()));
    QVERIFY(doc.manualCamera());
    // The same camera as the core function makes for this photo (what artcam lens camera
    // writes), without the lensfun samples as pairs.
    o.size = {600, 400};
    const LensCameraSummary direct = lensCamera(*db_, o);
    QVERIFY(direct.status.ok);
    QCOMPARE(doc.manualCamera()->isPiecewise(), direct.camera.isPiecewise());
    QCOMPARE(doc.manualCamera()->main().stages()[0].q, direct.camera.main().stages()[0].q);
    QVERIFY(doc.pairs().empty());
    doc.undoStack()->undo();
    QVERIFY(!doc.manualCamera());

    // A lens that cannot be made is reported, and the document keeps its camera.
    o.focal_mm = 99;
    session.applyLensCamera(o, db_);
    QTRY_COMPARE_WITH_TIMEOUT(applied.size(), 2, 60000);
    QVERIFY(!applied.back().at(0).toBool());
    QVERIFY(applied.back().at(1).toString().contains("6.1-30.5"));
    QVERIFY(!doc.manualCamera());
  }

  // Vignetting: the dialog takes the EXIF's f-number, and the session's camera carries the gain
  // in every layer, as the core function makes it; without an aperture the summary says why
  // there is none.
  void vignettingFromTheDialog() {
    const char* const prime = "Canon EF 50mm f/1.8 MkII";
    LensHint hint;
    hint.focal_mm = 50;
    hint.aperture = 2.8;
    LensDialog dialog(db_, {600, 400}, hint);
    dialog.searchField()->setText("canon ef 50mm f/1.8 mkii");
    QVERIFY(dialog.lensList()->count() >= 1);
    QCOMPARE(dialog.apertureField()->value(), 2.8);
    QVERIFY(dialog.vignettingBox()->isChecked());
    LensCameraOptions o = dialog.options();
    QCOMPARE(o.lens, std::string(prime));
    QCOMPARE(o.aperture, 2.8);
    QVERIFY(o.vignetting);

    Document doc;
    doc.reset(test::syntheticPhoto(600, 400));
    Session session(&doc, nullptr);
    session.setInteractive(false);
    QSignalSpy applied(&session, &Session::lensCameraApplied);
    o.crop = 1.6;  // one camera at this crop (patches would leave vignetting out)
    session.applyLensCamera(o, db_);
    QTRY_COMPARE_WITH_TIMEOUT(applied.size(), 1, 60000);
    QVERIFY2(applied.front().at(0).toBool(), qPrintable(applied.front().at(1).toString()));
    QVERIFY2(applied.front().at(1).toString().contains("vignetting at f/2.8"),
             qPrintable(applied.front().at(1).toString()));
    QVERIFY(doc.manualCamera());
    o.size = {600, 400};
    const LensCameraSummary direct = lensCamera(*db_, o);
    QVERIFY(direct.vignetting);
    QCOMPARE(doc.manualCamera()->layers.size(), direct.camera.layers.size());
    for (size_t l = 0; l < direct.camera.layers.size(); ++l) {
      QVERIFY(hasShading(doc.manualCamera()->layers[l]));
      QCOMPARE(doc.manualCamera()->layers[l].stages().size(), size_t{3});
      for (size_t st = 0; st < 3; ++st)
        QCOMPARE(doc.manualCamera()->layers[l].stages()[st].q,
                 direct.camera.layers[l].stages()[st].q);
    }
    o.aperture = 0;
    session.applyLensCamera(o, db_);
    QTRY_COMPARE_WITH_TIMEOUT(applied.size(), 2, 60000);
    QVERIFY2(applied.back().at(1).toString().contains("give the aperture"),
             qPrintable(applied.back().at(1).toString()));
    QVERIFY(!hasShading(doc.manualCamera()->main()));
  }

  void mainWindowHasTheMenu() {
    MainWindow window;
    QAction* found = nullptr;
    for (QAction* menu : window.menuBar()->actions())
      if (menu->text().remove('&') == "Lens" && menu->menu())
        for (QAction* a : menu->menu()->actions())
          if (a->text().remove('&').startsWith("From Database")) found = a;
    QVERIFY(found);
  }
};

QTEST_MAIN(TestLensDialog)
#include "test_lens_dialog.moc"
