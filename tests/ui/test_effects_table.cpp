// SPDX-License-Identifier: Apache-2.0
// The effects table (core/effects/effect_table.h) walked through both front ends. For every
// effect, every parameter (each component of a vector) is set to a value other than its default
// through the CLI (`artcam preset NAME --PARAM V … --size W,H`) and through the studio's Effects
// panel (offscreen, typing into the spin boxes it made from the table), and both cameras are
// compared with the table's builder called directly: the same layers, tensors, frames and depth
// output. The panel edits the document's effect stack, so its entry is checked too. The tensor
// panel's presets are the CLI's presets of the same names. The 3D effects table
// (core/effects/effects_3d_table.h) walked likewise: `artcam preset list` and the 3D view offer
// the same effects with the same defaults, and the view's camera for each, in its cloud's
// object frame, is the one `artcam preset NAME --object-centre C --object-radius R` writes.
#include "core/cloud/sample_clouds.h"
#include "core/effects/effect_table.h"
#include "core/effects/effects_3d_table.h"
#include "core/io/artcam_file.h"
#include "tests/app/cli_run.h"
#include "tests/ui/ui_fixtures.h"
#include "ui/cloud_view.h"
#include "ui/document.h"
#include "ui/panels/effects_panel.h"
#include "ui/panels/tensor_panel.h"

#include <QComboBox>
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

QString numbers(const std::vector<double>& value) {
  QStringList text;
  for (const double v : value) text << QString::number(v, 'g', 17);  // reads back bit-exactly
  return text.join(',');
}

// The words of NAME's entry in `artcam preset list`: its line and the indented lines under it.
QStringList listedWords(const QString& listing, const QString& name) {
  const qsizetype at = listing.indexOf(QStringLiteral("\n  ") + name + ' ');
  if (at < 0) return {};
  const qsizetype next = listing.indexOf(QRegularExpression(QStringLiteral("\n  [^ ]")), at + 1);
  return listing.mid(at, next < 0 ? -1 : next - at)
      .split(QRegularExpression("\\s+"), Qt::SkipEmptyParts);
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

  // The tensor panel offers the table's rows the photo alone can show, under their human names,
  // and applies each as the camera `artcam preset NAME --size W×H` writes; a value the table
  // refuses is refused by both with the same words, and the panel pushes no undo step.
  void tensorPanelPresetsAreTheCliPresets() {
    QTemporaryDir dir;
    Document doc;
    doc.reset(artcam::ui::test::syntheticPhoto());
    TensorPanel panel(&doc);
    const FrameSize frame = doc.frame();
    const QString size = QString("%1x%2").arg(frame.width).arg(frame.height);
    std::vector<std::pair<QString, QString>> want = {{"identity", "Identity"}};
    for (const EffectSpec& e : effectSpecs())
      if (!e.needs_depth && !e.needs_second)
        want.emplace_back(QString::fromStdString(e.name), QString::fromStdString(e.label));
    QVERIFY(panel.presets() == want);
    QVERIFY(want.size() >= 5);  // identity, barrel, pincushion, twist, inverse perspective, …
    int steps = 0;
    for (const auto& [name, label] : want) {
      if (name == "identity") continue;
      QCOMPARE(panel.applyPreset(name), QString());
      QCOMPARE(doc.undoStack()->count(), ++steps);
      QVERIFY2(doc.manualCamera(), qPrintable(name));
      const QString out = dir.filePath(name + ".artcam");
      const artcam::test::CliRun r =
          artcam::test::artcamCli({"preset", name, "--size", size, "-o", out});
      QVERIFY2(r.exit_code == 0, qPrintable(name + ": " + r.err));
      const auto file = readArtcam(out.toStdString());
      QVERIFY2(file.ok(), file.status.message.c_str());
      const QString diff = differences(*doc.manualCamera(), *file);
      QVERIFY2(diff.isEmpty(), qPrintable(name + ": " + diff));
    }
    const QString refused = panel.applyPreset("barrel", {{"k", {0.3}}});
    QVERIFY2(refused.contains("k = 0.3 is outside its range -1 … 0"), qPrintable(refused));
    QCOMPARE(doc.undoStack()->count(), steps);
    const artcam::test::CliRun r = artcam::test::artcamCli(
        {"preset", "barrel", "--k", "0.3", "--size", size, "-o", dir.filePath("no.artcam")});
    QCOMPARE(r.exit_code, 2);
    QVERIFY2(r.err.contains("k = 0.3 is outside its range -1 … 0"), qPrintable(r.err));
  }

  // The 3D table through `artcam preset list`, the 3D view and `artcam preset NAME`: one list,
  // one set of defaults (the view changes only a viewer row's eye and at, to its orbit), one
  // camera per effect, in the object frame of the view's cloud (off the origin, radius ≠ 1,
  // so a frame rule the two applied differently would show).
  void threeDEffectsAreTheCliPresets() {
    QVERIFY(effect3dSpecs().size() >= 5);
    const artcam::test::CliRun list = artcam::test::artcamCli({"preset", "list"});
    QCOMPARE(list.exit_code, 0);
    for (const Effect3dSpec& e : effect3dSpecs()) {
      const QString name = QString::fromStdString(e.name);
      const QStringList words = listedWords(list.out, name);
      QVERIFY2(!words.isEmpty(), qPrintable(name + " not in preset list"));
      for (const EffectParam& p : e.params) {
        const QString word = QString::fromStdString(p.name + "=" + defaultText(p));
        QVERIFY2(words.contains(word), qPrintable(name + ": " + word + " not listed"));
      }
      QVERIFY2(words.contains("object-centre=0,0,0") && words.contains("object-radius=1"),
               qPrintable(name));
    }

    CubeOfCubesOptions small;
    small.samples_per_edge = 4;
    small.half_size = 2.5;
    PointCloud cloud = cubeOfCubes(small);
    for (Eigen::Vector3d& p : cloud.positions) p += Eigen::Vector3d(4.0, -1.5, 7.0);
    LoadedCloud loaded;
    loaded.path = "moved-cube.ply";
    loaded.bounds = cloudBounds(cloud);
    loaded.point_spacing = estimatePointSpacing(cloud);
    loaded.cloud = std::make_shared<const PointCloud>(std::move(cloud));
    Document doc;
    CloudView view(&doc);
    view.resize(160, 120);
    view.setCloud(loaded);
    view.setOrbit(view.yaw() + 0.3, view.pitch() - 0.2, view.distance() * 1.3);
    const ObjectFrame frame = view.effectFrame();
    QCOMPARE(frame.centre, loaded.bounds.centre());
    QCOMPARE(frame.radius, loaded.bounds.radius());

    // The view's list: none, then the table's rows in order, under their human names.
    auto* box = view.findChild<QComboBox*>();
    QVERIFY(box);
    QCOMPARE(box->count(), static_cast<int>(effect3dSpecs().size()) + 1);
    QCOMPARE(box->itemData(0).toString(), QString());
    QTemporaryDir dir;
    for (size_t i = 0; i < effect3dSpecs().size(); ++i) {
      const Effect3dSpec& e = effect3dSpecs()[i];
      const QString name = QString::fromStdString(e.name);
      QCOMPARE(box->itemData(static_cast<int>(i) + 1).toString(), name);
      QCOMPARE(box->itemText(static_cast<int>(i) + 1), QString::fromStdString(e.label));
      box->setCurrentIndex(static_cast<int>(i) + 1);  // as the user picks it
      QCOMPARE(view.effect(), e.name);
      // Its values: the table's defaults, but a viewer's eye and at (the orbit's, in the frame).
      const EffectValues values = view.effectValues();
      const Eigen::Vector3d c = loaded.bounds.centre();
      const Eigen::Vector3d eye =
          c + view.distance() * Eigen::Vector3d(std::cos(view.pitch()) * std::sin(view.yaw()),
                                                std::sin(view.pitch()),
                                                -std::cos(view.pitch()) * std::cos(view.yaw()));
      for (const EffectParam& p : e.params) {
        const std::vector<double>& got = values.at(p.name);
        const QString what = name + " " + QString::fromStdString(p.name);
        if (e.viewer && p.name == "eye") {
          const Eigen::Vector3d want = (eye - c) / frame.radius;
          QVERIFY2((Eigen::Vector3d(got[0], got[1], got[2]) - want).norm() < 1e-12, qPrintable(what));
        } else if (e.viewer && p.name == "at") {
          QVERIFY2(got == std::vector<double>({0.0, 0.0, 0.0}), qPrintable(what));
        } else {
          QVERIFY2(got == p.value, qPrintable(what + " is not the table's default"));
        }
      }
      const CloudRenderRequest request = view.currentRequest();
      QCOMPARE(request.effects.size(), size_t{1});
      QCOMPARE(request.layers == RenderLayers::Rgb, e.colour_layers);
      // The same effect from the CLI, given the view's frame and values.
      QStringList args = {"preset", name, "--object-centre", numbers({c.x(), c.y(), c.z()}),
                          "--object-radius", numbers({frame.radius})};
      for (const auto& [param, value] : values)
        args << QString::fromStdString("--" + param) << numbers(value);
      const QString out = dir.filePath(name + ".artcam");
      const artcam::test::CliRun r = artcam::test::artcamCli(args << "-o" << out);
      QVERIFY2(r.exit_code == 0, qPrintable(args.join(' ') + ": " + r.err));
      QCOMPARE(r.out.contains("--layers rgb"), e.colour_layers);
      const auto file = readArtcam(out.toStdString());
      QVERIFY2(file.ok(), file.status.message.c_str());
      const QString diff = differences(*file, Artcam(request.effects.front()));
      QVERIFY2(diff.isEmpty(), qPrintable(name + ": " + diff));
    }
    box->setCurrentIndex(0);
    QCOMPARE(view.effect(), std::string());
    QVERIFY(view.currentRequest().effects.empty());
  }
};

QTEST_MAIN(TestEffectsTable)
#include "test_effects_table.moc"
