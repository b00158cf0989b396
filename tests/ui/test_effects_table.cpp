// SPDX-License-Identifier: Apache-2.0
// The effects table (core/effects/effect_table.h) walked through both front ends. For every
// effect, every parameter (each component of a vector) is set to a value other than its default
// through the CLI (`artcam preset NAME --PARAM V … --size W,H`) and through the studio's Effects
// panel (offscreen, typing into the spin boxes it made from the table), and both cameras are
// compared with the table's builder called directly: the same layers, tensors, frames and depth
// output. The panel edits the document's effect stack, so its entry is checked too.
#include "core/effects/effect_table.h"
#include "core/io/artcam_file.h"
#include "tests/app/cli_run.h"
#include "tests/ui/ui_fixtures.h"
#include "ui/document.h"
#include "ui/panels/effects_panel.h"

#include <QDoubleSpinBox>
#include <QTemporaryDir>
#include <QtTest/QtTest>

#include <cmath>
#include <memory>

using namespace artcam;
using namespace artcam::ui;

namespace {

// Halfway from the default to the nearer end of its range (the farther one if it is at an end),
// to the panel's four decimals: inside the range, and not crossing a neighbour (near < far).
double otherValue(const EffectParam& p, double d) {
  double end = (p.max - d <= d - p.min) ? p.max : p.min;
  if (end == d) end = (end == p.max) ? p.min : p.max;
  // A named choice's value is an index: the nearest whole one.
  if (p.isChoice()) return std::round((d + end) / 2);
  return std::round((d + end) / 2 * 1e4) / 1e4;
}

EffectValues otherValues(const EffectSpec& effect) {
  EffectValues values;
  for (const EffectParam& p : effect.params)
    for (const double d : p.value) values[p.name].push_back(otherValue(p, d));
  return values;
}

QString differences(const std::vector<Camera>& got, const std::vector<Camera>& want,
                    std::string_view got_output, DepthOutput want_output) {
  if (got_output != depthOutputName(want_output))
    return QString("depth output %1").arg(QString::fromUtf8(got_output.data(), static_cast<int>(got_output.size())));
  if (got.size() != want.size()) return QString("%1 layers, not %2").arg(got.size()).arg(want.size());
  for (size_t l = 0; l < got.size(); ++l) {
    const Camera& a = got[l];
    const Camera& b = want[l];
    if (a.blocks() != b.blocks()) return QString("layer %1: blocks").arg(l);
    if (a.sourceSize() != b.sourceSize() || a.targetSize() != b.targetSize())
      return QString("layer %1: frames").arg(l);
    if (a.stages().size() != b.stages().size()) return QString("layer %1: stage count").arg(l);
    for (size_t s = 0; s < a.stages().size(); ++s)
      for (size_t i = 0; i < b.stages()[s].q.size(); ++i)
        if (a.stages()[s].q.size() != b.stages()[s].q.size() || a.stages()[s].q[i] != b.stages()[s].q[i])
          return QString("layer %1 stage %2 tensor %3").arg(l).arg(s).arg(i);
  }
  return {};
}

QString differences(const Artcam& got, const Artcam& want) {
  if (got.isPiecewise()) return "patches";
  return differences(got.layers, want.layers, depthOutputName(got.depth_output), want.depth_output);
}

}  // namespace

class TestEffectsTable : public QObject {
  Q_OBJECT

 private slots:
  void cliMakesTheBuildersCamera() {
    QTemporaryDir dir;
    const FrameSize frame{320, 200};
    QVERIFY(effectSpecs().size() >= 8);
    for (const EffectSpec& effect : effectSpecs()) {
      const EffectValues values = otherValues(effect);
      QStringList args = {"preset", QString::fromStdString(effect.name), "--size", "320,200"};
      for (const auto& [name, value] : values) {
        QStringList numbers;
        for (const double v : value) numbers << QString::number(v, 'g', 17);
        args << QString::fromStdString("--" + name) << numbers.join(',');
      }
      const QString out = dir.filePath(QString::fromStdString(effect.name) + ".artcam");
      const artcam::test::CliRun r = artcam::test::artcamCli(args << "-o" << out);
      QVERIFY2(r.exit_code == 0, qPrintable(args.join(' ') + ": " + r.err));
      const auto file = readArtcam(out.toStdString());
      QVERIFY2(file.ok(), file.status.message.c_str());
      const Artcam want = effect.build(values, frame);
      const QString diff = differences(*file, want);
      QVERIFY2(diff.isEmpty(), qPrintable(QString::fromStdString(effect.name) + ": " + diff));
    }
  }

  void panelMakesTheBuildersCamera() {
    Document doc;
    doc.reset(artcam::ui::test::syntheticPhoto());
    EffectsPanel panel(&doc);
    const FrameSize frame = doc.frame();
    for (const EffectSpec& effect : effectSpecs()) {
      const QString name = QString::fromStdString(effect.name);
      QVERIFY2(panel.addEffect(name), qPrintable(name));
      const int entry = static_cast<int>(doc.effects().size()) - 1;
      QCOMPARE(panel.selectedIndex(), entry);
      const EffectValues values = otherValues(effect);
      for (const EffectParam& p : effect.params)
        for (int i = 0; i < p.size(); ++i) {
          const std::string object = p.size() == 1 ? p.name : p.name + "[" + std::to_string(i) + "]";
          auto* spin = panel.findChild<QDoubleSpinBox*>(QString::fromStdString(object));
          const QString what = name + " " + QString::fromStdString(object);
          QVERIFY2(spin, qPrintable(what + ": no spin box"));
          // The widget is the table's row: range, default, unit.
          QVERIFY2(spin->minimum() == p.min && spin->maximum() == p.max, qPrintable(what));
          QVERIFY2(spin->value() == p.value[static_cast<size_t>(i)], qPrintable(what));
          QCOMPARE(spin->suffix(), p.unit.empty() ? QString() : QString::fromStdString(" " + p.unit));
          spin->setValue(values.at(p.name)[static_cast<size_t>(i)]);
        }
      QVERIFY2(panel.parameters() == values, qPrintable(name));
      // The document's stack holds what was typed, and its camera is the builder's.
      const EffectStep& step = doc.effects()[static_cast<size_t>(entry)];
      QCOMPARE(QString::fromStdString(step.effect), name);
      QVERIFY2(step.values == values, qPrintable(name));
      const Artcam want = effect.build(values, frame);
      const QString diff = differences(buildEffect(step.effect, step.values, frame), want);
      QVERIFY2(diff.isEmpty(), qPrintable(name + ": " + diff));
    }
    QCOMPARE(doc.effects().size(), effectSpecs().size());
  }
};

QTEST_MAIN(TestEffectsTable)
#include "test_effects_table.moc"
