// SPDX-License-Identifier: Apache-2.0
// The tensor panel: typed entries become symmetric edits as undo commands; presets, which are
// the effects table's builders (the CLI's cameras: tests/ui/test_effects_table.cpp) with their
// refusals shown and no undo step pushed.
#include "core/effects/effect_table.h"
#include "core/model/structure.h"
#include "tests/ui/ui_fixtures.h"
#include "ui/document.h"
#include "ui/panels/tensor_panel.h"
#include "ui/preview_controller.h"

#include <QLabel>
#include <QTableWidget>
#include <QtTest/QtTest>

using namespace artcam;
using namespace artcam::ui;

class TestTensorPanel : public QObject {
  Q_OBJECT

 private slots:
  void typedEntryIsASymmetricUndoableEdit() {
    Document doc;
    doc.reset(test::syntheticPhoto(), test::ninePairs(), ModelClass::Quadratic);
    QVERIFY(doc.fit().status.ok);
    const Camera fitted = doc.camera();
    TensorPanel panel(&doc);
    QCOMPARE(panel.tables().size(), size_t{3});
    QTableWidget* q3 = panel.tables()[2];
    // Shown with 6 significant digits (|x| ≥ 1e-12 here); the tooltip holds all 17.
    QVERIFY(std::abs(fitted.stages()[0].q[2](0, 1)) >= 1e-12);
    QCOMPARE(q3->item(0, 1)->text(), QString::number(fitted.stages()[0].q[2](0, 1), 'g', 6));
    QVERIFY(q3->item(0, 1)->toolTip().endsWith(
        "= " + QString::number(fitted.stages()[0].q[2](0, 1), 'g', 17)));
    q3->item(0, 1)->setText("0.125");  // as if typed
    QVERIFY(doc.manualCamera().has_value());
    QCOMPARE(doc.camera().stages()[0].q[2](0, 1), 0.125);
    QCOMPARE(doc.camera().stages()[0].q[2](1, 0), 0.125);
    QCOMPARE(q3->item(1, 0)->text(), QString("0.125"));  // mirrored in the table
    QCOMPARE(doc.undoStack()->count(), 1);
    q3->item(2, 2)->setText("not a number");  // refused, old value back
    QCOMPARE(doc.undoStack()->count(), 1);
    QCOMPARE(q3->item(2, 2)->text(), QString::number(doc.camera().stages()[0].q[2](2, 2), 'g', 6));
    doc.undoStack()->undo();
    QVERIFY(!doc.manualCamera());
    QCOMPARE(doc.camera().stages()[0].q, fitted.stages()[0].q);
  }

  void editingAnEntryUpdatesThePreview() {
    Document doc;
    PreviewController preview(&doc);
    doc.reset(test::syntheticPhoto(), test::ninePairs(), ModelClass::Quadratic);
    TensorPanel panel(&doc);
    QVERIFY(test::waitForNewestPreview(preview));
    const QImage before = preview.image();
    const quint64 generation = preview.imageGeneration();
    // Q_1(0, 0) scales u: typing 1.2 times the fitted value visibly stretches the picture.
    QTableWidget* q1 = panel.tables()[0];
    const double value = doc.camera().stages()[0].q[0](0, 0);
    q1->item(0, 0)->setText(QString::number(value * 1.2, 'g', 17));
    QCOMPARE(doc.camera().stages()[0].q[0](0, 0), value * 1.2);
    QVERIFY(test::waitForNewestPreview(preview));
    QVERIFY(preview.imageGeneration() > generation);
    QVERIFY(preview.image() != before);
    QCOMPARE(preview.image(), test::directPreviewRender(doc));
  }

  void presets() {
    Document doc;
    doc.reset(test::syntheticPhoto());
    TensorPanel panel(&doc);
    panel.applyPreset("pincushion");
    QCOMPARE(analyseStructure(doc.camera()).geometry, GeometryClass::Rational);
    // Pincushion pushes a corner outwards, barrel pulls it in; the centre stays.
    const Eigen::Vector2d corner(10.0, 10.0), centre(160.0, 120.0);
    const auto out = targetPixelFromSourcePixel(doc.camera(), corner);
    QVERIFY(out && out->x() < corner.x() && out->y() < corner.y());
    QVERIFY((*targetPixelFromSourcePixel(doc.camera(), centre) - centre).norm() < 1e-9);
    panel.applyPreset("barrel");
    const auto in = targetPixelFromSourcePixel(doc.camera(), corner);
    QVERIFY(in && in->x() > corner.x() && in->y() > corner.y());
    panel.applyPreset("identity");
    QCOMPARE(analyseStructure(doc.camera()).geometry, GeometryClass::Identity);
    QCOMPARE(doc.undoStack()->count(), 3);
  }

  void presetsAreTheTablesBuilders() {
    Document doc;
    TensorPanel panel(&doc);
    QVERIFY(!panel.applyPreset("barrel").isEmpty());  // no photo, no frame: refused, said why
    QCOMPARE(doc.undoStack()->count(), 0);
    doc.reset(test::syntheticPhoto());
    QCOMPARE(panel.presets().front().first, QString("identity"));
    int steps = 0;
    for (const auto& [name, label] : panel.presets()) {
      if (name == "identity") continue;
      const EffectSpec* spec = findEffect(name.toStdString());
      QVERIFY2(spec && !spec->needs_depth && !spec->needs_second, qPrintable(name));
      QCOMPARE(label, QString::fromStdString(spec->label));
      QCOMPARE(panel.applyPreset(name), QString());
      QCOMPARE(doc.undoStack()->count(), ++steps);
      QCOMPARE(doc.undoStack()->text(steps - 1), QString("Preset: %1").arg(label));
      const Artcam want = buildEffect(spec->name, {}, doc.frame());
      QCOMPARE(doc.manualCamera()->layers.size(), want.layers.size());
      for (size_t l = 0; l < want.layers.size(); ++l)
        QVERIFY2(doc.manualCamera()->layers[l].stages()[0].q == want.layers[l].stages()[0].q,
                 qPrintable(name));
    }
    QVERIFY(steps >= 4);
    // The table's refusal: nothing pushed, the reason shown beneath the presets.
    const QString refused = panel.applyPreset("pincushion", {{"k", {0.6}}});
    QVERIFY2(refused.contains("k = 0.6 is outside its range 0 … 0.45"), qPrintable(refused));
    QCOMPARE(doc.undoStack()->count(), steps);
    bool shown = false;
    for (const QLabel* l : panel.findChildren<QLabel*>()) shown = shown || l->text() == refused;
    QVERIFY(shown);
    QVERIFY(!panel.applyPreset("depth-of-field").isEmpty());  // not offered: needs depth
    QCOMPARE(doc.undoStack()->count(), steps);
  }
};

QTEST_MAIN(TestTensorPanel)
#include "test_tensor_panel.moc"
