// SPDX-License-Identifier: Apache-2.0
// Panels in the user's words: tensor cells rounded (round-off shown as 0) with a tooltip that
// names the term and block an entry weighs, effects listed by the table's human names, and a
// render's missing depth answered with the studio's actions, not a command line.
#include "core/effects/effect_table.h"
#include "tests/ui/ui_fixtures.h"
#include "ui/commands.h"
#include "ui/document.h"
#include "ui/main_window.h"
#include "ui/panels/effects_panel.h"
#include "ui/panels/tensor_panel.h"
#include "ui/session.h"

#include <QComboBox>
#include <QListWidget>
#include <QSlider>
#include <QStandardPaths>
#include <QStatusBar>
#include <QTableWidget>
#include <QtTest/QtTest>

using namespace artcam;
using namespace artcam::ui;

class TestPanelWording : public QObject {
  Q_OBJECT

 private slots:
  void initTestCase() { QStandardPaths::setTestModeEnabled(true); }

  void tensorCellsAreRounded() {
    Document doc;
    doc.reset(ui::test::syntheticPhoto());
    TensorPanel panel(&doc);
    // Q1 (the u output) over (u, v, w): entry (u, v) is round-off, (u, u) a real weight.
    panel.setEntry(0, 0, 0, 1, 6.338627883e-16);
    panel.setEntry(0, 0, 0, 0, 0.123456789);
    QTableWidget* q1 = panel.tables().at(0);
    QCOMPARE(q1->item(0, 1)->text(), QString("0"));
    QCOMPARE(q1->item(1, 0)->text(), QString("0"));  // symmetric storage
    QCOMPARE(q1->item(0, 0)->text(), QString("0.123457"));
    // The identity's w weight of the u output is exactly 1/2 per entry (u·w = ½(u w + w u)).
    QCOMPARE(q1->item(0, 2)->text(), QString("0.5"));
    // The tooltip says what the entry weighs: the term, its block, the output, the exact value.
    const QString off = q1->item(0, 1)->toolTip();
    QVERIFY2(off.contains("2·u·v") && off.contains("position") && off.contains("output u"),
             qPrintable(off));
    QVERIFY2(off.contains("6.33862788"), qPrintable(off));
    const QString diag = q1->item(0, 0)->toolTip();
    QVERIFY2(diag.contains("u²") && diag.contains("0.123456789"), qPrintable(diag));
  }

  void effectsAreListedByTheirHumanNames() {
    Document doc;
    doc.reset(ui::test::syntheticPhoto());
    EffectsPanel panel(&doc);
    auto* box = panel.findChild<QComboBox*>();
    QVERIFY(box);
    QCOMPARE(box->count(), static_cast<int>(effectSpecs().size()));
    for (int i = 0; i < box->count(); ++i) {
      const EffectSpec& spec = effectSpecs()[static_cast<size_t>(i)];
      QCOMPARE(box->itemText(i), QString::fromStdString(spec.label));
    }
    QVERIFY(box->findText("photo-glc") < 0);
    QVERIFY(box->findText("General linear view") >= 0);
    QVERIFY(panel.addEffect("photo-glc"));
    auto* list = panel.findChild<QListWidget*>();
    QVERIFY(list);
    QCOMPARE(list->item(0)->text(), QString("1. General linear view"));
    QVERIFY2(!doc.undoStack()->text(doc.undoStack()->index() - 1).contains("photo-glc"),
             qPrintable(doc.undoStack()->text(doc.undoStack()->index() - 1)));
    // Without depth it is left out, and the panel's status names it as the list does.
    QVERIFY2(panel.status().contains("General linear view"), qPrintable(panel.status()));
  }

  // The lens's strengths on sliders: a slider types into its box, the stack's entry and so the
  // document's camera follow, and one drag is one undo step.
  void lensStrengthSlidersBuildTheCamera() {
    Document doc;
    doc.reset(ui::test::syntheticPhoto(600, 400));
    EffectsPanel panel(&doc);
    QVERIFY(panel.addEffect("lens-distortion"));
    const int steps_before = doc.undoStack()->count();
    for (const char* name :
         {"k1/slider", "k2/slider", "centre[0]/slider", "centre[1]/slider", "scale/slider"})
      QVERIFY2(panel.findChild<QSlider*>(name), name);
    auto* k1 = panel.findChild<QSlider*>("k1/slider");
    for (int v : {500, 400, 300}) k1->setValue(v);  // one drag
    QCOMPARE(doc.undoStack()->count(), steps_before + 1);
    // 300 of 1000 over k1's range −0.6 … 0.45: −0.6 + 0.3·1.05 = −0.285.
    QCOMPARE(panel.parameters().at("k1").at(0), -0.285);
    panel.findChild<QSlider*>("scale/slider")->setValue(400);  // 0.5 + 0.4·1.5 = 1.1
    QCOMPARE(panel.parameters().at("scale").at(0), 1.1);
    // The document's camera is the closed form q' = q/(1 − k1|q|²), p' = s·q' (centre 0, k2 0).
    for (const Eigen::Vector2d& p : {Eigen::Vector2d(0.5, 0.3), Eigen::Vector2d(-0.9, 0.6)}) {
      const auto got = targetFromSourceNormalized(doc.artcam().main(), p);
      QVERIFY(got.has_value());
      const Eigen::Vector2d want = 1.1 * p / (1.0 + 0.285 * p.squaredNorm());
      QVERIFY2((*got - want).norm() < 1e-9, qPrintable(QString::number((*got - want).norm())));
    }
  }

  // An imported camera that reads depth, before any depth is painted: the preview's refusal
  // names what to do in the studio.
  void missingDepthNamesTheStudiosActions() {
    MainWindow window;
    window.session()->setInteractive(false);
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    Document* doc = window.document();
    doc->reset(ui::test::syntheticPhoto());
    Artcam camera = buildEffect("aerial-perspective", {}, doc->frame());
    doc->undoStack()->push(new SetCameraCommand(doc, std::move(camera), "Set camera"));
    QTRY_VERIFY_WITH_TIMEOUT(window.statusBar()->currentMessage().contains("Preview failed"),
                             30000);
    const QString message = window.statusBar()->currentMessage();
    QVERIFY2(message.contains("depth"), qPrintable(message));
    QVERIFY2(!message.contains("artcam warp"), qPrintable(message));
    QVERIFY2(message.contains("Load Depth Map"), qPrintable(message));
  }
};

QTEST_MAIN(TestPanelWording)
#include "test_panel_wording.moc"
