// SPDX-License-Identifier: Apache-2.0
// Colour calibration in the studio: patches picked on two synthetic
// photos whose colours differ by a known 3×3 matrix M (made in code), the fit run off the GUI
// thread recovering M, undo/redo of every sample edit, the preview and the export showing the
// colour block (checked against M applied by hand and an independent sRGB encoding), the
// project round trip and the CSV that core's reader takes.
#include "core/colour/colour_difference.h"
#include "core/colour/colour_map.h"
#include "core/io/image_io.h"
#include "core/io/matches_csv.h"
#include "tests/ui/ui_fixtures.h"
#include "tests/ui/session_wait.h"
#include "ui/background_job.h"
#include "ui/colour/colour_commands.h"
#include "ui/colour/colour_dock.h"
#include "ui/colour/colour_project.h"
#include "core/colour/colour_stage.h"
#include "ui/colour/patch_view.h"
#include "ui/commands.h"
#include "ui/document.h"
#include "ui/export_job.h"
#include "ui/preview_controller.h"
#include "ui/session.h"

#include <QJsonDocument>
#include <QSignalSpy>
#include <QStandardPaths>
#include <QTableWidget>
#include <QTemporaryDir>
#include <QtTest/QtTest>

#include <cmath>

using namespace artcam;
using namespace artcam::ui;

namespace {

// The reference's colours are M times the source's (rows sum below 1: stays in [0, 1]).
Eigen::Matrix3d transformM() {
  Eigen::Matrix3d m;
  m << 0.70, 0.20, 0.05,  //
      0.10, 0.60, 0.25,   //
      0.05, 0.15, 0.75;
  return m;
}

constexpr int kCols = 4, kRows = 4, kBlock = 40;

// Block (i, j)'s linear colour: spread over the cube, no three on a line.
Eigen::Vector3d blockColour(int i, int j) {
  return {0.05 + 0.28 * i + 0.02 * j, 0.08 + 0.27 * j + 0.01 * i * i,
          0.9 - 0.2 * ((i + 2 * j) % 4) - 0.03 * i};
}

// A kCols × kRows grid of uniform blocks of `block` px, colours through `m`.
PhotoPtr blocksPhoto(int block, const Eigen::Matrix3d& m, const QString& name) {
  ImageF img(kCols * block, kRows * block, 3);
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const Eigen::Vector3d c = m * blockColour(x / block, y / block);
      for (int k = 0; k < 3; ++k) img.pixel(x, y)[k] = static_cast<float>(c[k]);
    }
  LoadedImage loaded;
  loaded.image = std::move(img);
  loaded.info.path = name.toStdString();
  return makePhoto(name, std::move(loaded));
}

Eigen::Vector2d blockCentre(int i, int j, int block) {
  return {(i + 0.5) * block, (j + 0.5) * block};
}

// IEC 61966-2-1 encoding, written out here so the check does not use the code under test.
int srgbCode(double linear) {
  linear = std::clamp(linear, 0.0, 1.0);
  const double e = linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1 / 2.4) - 0.055;
  return static_cast<int>(std::lround(255.0 * e));
}

ColourMap linearMap(const Eigen::Matrix3d& m) {
  ColourMap map;
  map.model = ColourModel::Linear;
  map.m = m;
  return map;
}

void clickPatch(PatchView* view, const Eigen::Vector2d& photo_px) {
  test::click(view, view->widgetFromPhoto(photo_px).toPoint());
}

struct Studio {
  Document doc;
  ColourDock dock{&doc};

  Studio() {
    dock.resize(900, 700);
    dock.show();
  }
  // The synthetic pair: source at 40 px blocks, reference twice as large (other pixels).
  void load() {
    doc.reset(blocksPhoto(kBlock, Eigen::Matrix3d::Identity(), "source.png"));
    ColourSampleState s = dock.model()->state();
    s.reference = blocksPhoto(2 * kBlock, transformM(), "reference.png");
    s.reference_path = "reference.png";
    pushColourSamples(dock.model(), s, "reference");
  }
  void pick(int i, int j) {
    clickPatch(dock.sourceView(), blockCentre(i, j, kBlock));
    clickPatch(dock.referenceView(), blockCentre(i, j, 2 * kBlock));
  }
};

}  // namespace

class TestColourSamples : public QObject {
  Q_OBJECT

  QTemporaryDir dir_;

 private slots:
  void initTestCase() {
    QStandardPaths::setTestModeEnabled(true);
    QVERIFY(dir_.isValid());
  }

  void pickedPatchesRecoverTheTransform() {
    Studio st;
    QVERIFY(QTest::qWaitForWindowExposed(&st.dock));
    st.doc.reset(test::syntheticPhoto());  // a photo first, so the new one resets the samples
    st.load();
    // Geometry too, so the colour block has to join a rational camera.
    for (const Pair& p : test::ninePairs(kCols * kBlock, kRows * kBlock))
      st.doc.undoStack()->push(new AddPairCommand(&st.doc, p));
    QVERIFY(st.doc.fit().status.ok);
    const Camera geometry = st.doc.camera();
    for (int j = 0; j < kRows; ++j)
      for (int i = 0; i < kCols; ++i) st.pick(i, j);
    QCOMPARE(st.dock.model()->state().samples.size(), size_t{kCols * kRows});
    // Every picked pair holds the block's colour and M times it (uniform blocks: exact means).
    for (int k = 0; k < kCols * kRows; ++k) {
      const auto pair = st.dock.model()->colourPair(k);
      QVERIFY(pair.has_value());
      const Eigen::Vector3d c = blockColour(k % kCols, k / kCols);
      QVERIFY((pair->source - c).norm() < 1e-6);
      QVERIFY((pair->target - transformM() * c).norm() < 1e-6);
      // The table's ΔE before the fit is that of the two colours as made.
      const double shown = st.dock.table()->item(k, 3)->text().toDouble();
      QVERIFY(std::abs(shown - deltaE2000(c, transformM() * c)) < 0.006);
    }

    QSignalSpy done(&st.dock, &ColourDock::fitFinished);
    st.dock.setFitModel(ColourModel::Auto);
    st.dock.fit();
    QVERIFY(done.wait(60000));
    QVERIFY(done.front().front().toBool());
    const ColourFitSummary& fit = *st.dock.lastFit();
    QCOMPARE(fit.selected, ColourModel::Linear);  // exact linear data: the simplest model
    QVERIFY(fit.max_de < 1e-3);
    QVERIFY(st.doc.colourBlock().has_value());
    QVERIFY(st.dock.report().contains("linear"));
    QVERIFY(st.dock.report().contains("Held-out"));  // the selection's evidence is shown

    // Colours never sampled go through the block as through M.
    const Eigen::Vector3d probes[] = {{0.3, 0.5, 0.2}, {0.9, 0.1, 0.4}, {0.05, 0.05, 0.05}};
    for (const Eigen::Vector3d& c : probes) {
      double out[3];
      const double in[3] = {c[0], c[1], c[2]};
      QVERIFY(applyColourCamera(*st.doc.colourBlock(), in, out));
      const Eigen::Vector3d want = transformM() * c;
      QVERIFY((Eigen::Vector3d(out[0], out[1], out[2]) - want).norm() < 1e-6);
      QVERIFY(deltaE2000(Eigen::Vector3d(out[0], out[1], out[2]), want) < 1e-3);
    }
    // The document's camera keeps the fitted geometry and maps colour by M at any position.
    const Camera& cam = st.doc.camera();
    QCOMPARE(cam.blocks().size(), size_t{2});
    for (const Eigen::Vector2d& uv : {Eigen::Vector2d(-0.4, 0.2), Eigen::Vector2d(0.3, -0.5)}) {
      Eigen::VectorXd x(7);
      x << uv.x(), uv.y(), 1.0, 0.3, 0.5, 0.2, 1.0;
      const Eigen::VectorXd y = cam.evaluate(x);
      const auto g = targetFromSourceNormalized(geometry, uv);
      QVERIFY(g.has_value());
      QVERIFY(std::abs(y[0] - g->x()) < 1e-12 && std::abs(y[1] - g->y()) < 1e-12);
      QVERIFY((y.segment<3>(3) - transformM() * Eigen::Vector3d(0.3, 0.5, 0.2)).norm() < 1e-6);
      QVERIFY(std::abs(y[6] - 1.0) < 1e-12);  // opaque stays opaque
    }
    // The fitted column now shows ~0 for every sample.
    for (int k = 0; k < kCols * kRows; ++k)
      QVERIFY(st.dock.table()->item(k, 4)->text().toDouble() < 0.01);
    // The fit is one undo step.
    st.doc.undoStack()->undo();
    QVERIFY(!st.doc.colourBlock().has_value());
    QCOMPARE(st.doc.camera().blocks().size(), size_t{1});
  }

  void robustFitIgnoresAMismatchedPatch() {
    Studio st;
    QVERIFY(QTest::qWaitForWindowExposed(&st.dock));
    st.load();
    for (int j = 0; j < kRows; ++j)
      for (int i = 0; i < kCols; ++i) st.pick(i, j);
    // A wrong pair: block (0, 0) against block (3, 3) of the reference (off the squares
    // already there: a click on a square selects it).
    clickPatch(st.dock.sourceView(), blockCentre(0, 0, kBlock) + Eigen::Vector2d(12, 12));
    clickPatch(st.dock.referenceView(), blockCentre(3, 3, 2 * kBlock) + Eigen::Vector2d(25, 25));
    QCOMPARE(st.dock.model()->state().samples.size(), size_t{kCols * kRows + 1});
    QSignalSpy done(&st.dock, &ColourDock::fitFinished);
    st.dock.setFitModel(ColourModel::Linear);
    st.dock.setRobust(true);
    st.dock.fit();
    QVERIFY(done.wait(60000));
    QVERIFY(done.front().front().toBool());
    QCOMPARE(st.dock.lastFit()->inliers.size(), size_t{kCols * kRows});
    double out[3];
    const double in[3] = {0.4, 0.4, 0.4};
    QVERIFY(applyColourCamera(*st.doc.colourBlock(), in, out));
    QVERIFY(
        (Eigen::Vector3d(out[0], out[1], out[2]) - transformM() * Eigen::Vector3d(0.4, 0.4, 0.4))
            .norm() < 1e-6);
  }

  void sampleEditsUndoAndRedo() {
    Studio st;
    QVERIFY(QTest::qWaitForWindowExposed(&st.dock));
    st.load();
    QUndoStack* stack = st.doc.undoStack();
    const int base = stack->count();
    st.pick(0, 0);
    st.pick(2, 1);
    QCOMPARE(stack->count(), base + 2);
    const ColourSampleState two = st.dock.model()->state();
    QCOMPARE(two.samples.size(), size_t{2});

    // A drag of the second source square is one step, ending where it was dropped.
    PatchView* v = st.dock.sourceView();
    const QPoint from = v->widgetFromPhoto(two.samples[1].source).toPoint();
    const QPoint to = v->widgetFromPhoto(blockCentre(3, 3, kBlock)).toPoint();
    test::drag(v, from, to);
    QCOMPARE(stack->count(), base + 3);
    const ColourSampleState moved = st.dock.model()->state();
    QVERIFY((moved.samples[1].source - v->photoFromWidget(to)).norm() < 1e-9);
    QVERIFY(moved.samples[0] == two.samples[0]);
    const auto pair = st.dock.model()->colourPair(1);
    QVERIFY(pair && (pair->source - blockColour(3, 3)).norm() < 1e-6);

    // Radius, enable toggle and delete are steps too.
    st.dock.setRadius(7);
    st.dock.table()->item(0, 0)->setCheckState(Qt::Unchecked);
    QVERIFY(!st.dock.model()->state().samples[0].enabled);
    st.dock.model()->setSelection({0});
    QTest::keyClick(&st.dock, Qt::Key_Delete);
    const ColourSampleState last = st.dock.model()->state();
    QCOMPARE(last.samples.size(), size_t{1});
    QCOMPARE(last.radius, 7);
    QCOMPARE(stack->count(), base + 6);

    stack->undo();  // delete
    QCOMPARE(st.dock.model()->state().samples.size(), size_t{2});
    QVERIFY(!st.dock.model()->state().samples[0].enabled);
    stack->undo();  // enable
    stack->undo();  // radius
    QVERIFY(st.dock.model()->state() == moved);
    stack->undo();  // drag
    QVERIFY(st.dock.model()->state() == two);
    stack->undo();
    stack->undo();
    QVERIFY(st.dock.model()->state().samples.empty());
    for (int k = 0; k < 6; ++k) stack->redo();
    QVERIFY(st.dock.model()->state() == last);

    // Esc drops a half pair: the next two clicks make exactly one sample.
    clickPatch(st.dock.sourceView(), blockCentre(1, 1, kBlock));
    QTest::keyClick(&st.dock, Qt::Key_Escape);
    st.pick(1, 2);
    QCOMPARE(st.dock.model()->state().samples.size(), size_t{2});
    QVERIFY((st.dock.model()->state().samples[1].source - blockCentre(1, 2, kBlock)).norm() < 2.0);
  }

  void previewAndExportShowTheColourBlock() {
    Document doc;
    PreviewController preview(&doc);
    doc.reset(test::syntheticPhoto());
    QVERIFY(test::waitForNewestPreview(preview));
    const QImage before = preview.image();
    doc.undoStack()->push(new SetColourBlockCommand(
        &doc, colourCamera(linearMap(transformM()), doc.frame()), "colour"));
    QVERIFY(test::waitForNewestPreview(preview));
    const QImage after = preview.image();
    const ImageF& src = doc.photo()->preview;
    QCOMPARE(after.width(), src.width);  // the colour-only path: the preview copy's pixels
    int worst = 0;
    for (const QPoint p : {QPoint(5, 7), QPoint(100, 50), QPoint(250, 200), QPoint(40, 130)}) {
      const float* s = src.pixel(p.x(), p.y());
      const Eigen::Vector3d want = transformM() * Eigen::Vector3d(s[0], s[1], s[2]);
      const QRgb got = after.pixel(p);
      worst = std::max({worst, std::abs(qRed(got) - srgbCode(want[0])),
                        std::abs(qGreen(got) - srgbCode(want[1])),
                        std::abs(qBlue(got) - srgbCode(want[2]))});
      QCOMPARE(qAlpha(got), 255);
    }
    QVERIFY2(worst <= 1, qPrintable(QString("worst %1 codes").arg(worst)));
    QVERIFY(after != before);

    // The export renders the full-resolution photo through the same block.
    const QString path = dir_.filePath("colour.png");
    ExportJob job(doc.photo(), doc.artcam(), path);
    QSignalSpy done(&job, &ExportJob::done);
    job.start();
    QVERIFY(done.wait(60000));
    QVERIFY2(done.front().front().toBool(), qPrintable(done.front().at(1).toString()));
    const Result<LoadedImage> back = readImage(path.toStdString());
    QVERIFY(back.ok());
    const ImageF& full = doc.photo()->full.image;
    for (const QPoint p : {QPoint(5, 7), QPoint(100, 50), QPoint(250, 200)}) {
      const float* s = full.pixel(p.x(), p.y());
      const Eigen::Vector3d want = transformM() * Eigen::Vector3d(s[0], s[1], s[2]);
      const float* g = back->image.pixel(p.x(), p.y());
      for (int k = 0; k < 3; ++k)
        QVERIFY2(std::abs(srgbCode(g[k]) - srgbCode(want[k])) <= 1,
                 qPrintable(QString("channel %1: %2 vs %3").arg(k).arg(g[k]).arg(want[k])));
    }

    // Undo: the pyramid path's image again.
    doc.undoStack()->undo();
    QVERIFY(test::waitForNewestPreview(preview));
    QCOMPARE(preview.image(), test::directPreviewRender(doc));
  }

  void previewOfAWarpWithAColourBlock() {
    // Geometry and colour at once: the preview must be the geometry-only warp of the preview
    // copy, interpolated in the photo's stored domain (the one resampling rule,
    // core/colour/stored_encoding.h) and decoded, with M applied per pixel — which core's plain
    // warpImage and the encoding give independently of the attributed renderer.
    Document doc;
    PreviewController preview(&doc);
    doc.reset(test::syntheticPhoto(), test::ninePairs());
    QVERIFY(doc.fit().status.ok);
    const Camera geometry = doc.camera();
    doc.undoStack()->push(new SetColourBlockCommand(
        &doc, colourCamera(linearMap(transformM()), doc.frame()), "colour"));
    QVERIFY(test::waitForNewestPreview(preview));
    const QImage got = preview.image();
    WarpOptions options;
    options.width = got.width();
    options.height = got.height();
    const StoredEncoding encoding = storedEncodingOf(doc.photo()->full.info);
    QVERIFY(!encoding.isLinear());
    ImageF stored = doc.photo()->preview;
    encoding.encode(stored.data.data(), stored.data.size() / static_cast<size_t>(stored.channels),
                    stored.channels, stored.alpha_channel);
    ImageF warped = warpImage(stored, geometry, options);
    encoding.decode(warped.data.data(), warped.data.size() / static_cast<size_t>(warped.channels),
                    warped.channels, warped.alpha_channel);
    int worst = 0, compared = 0;
    for (int y = 3; y < got.height(); y += 17)
      for (int x = 3; x < got.width(); x += 13) {
        const float* w = warped.pixel(x, y);
        const QRgb g = got.pixel(x, y);
        if (warped.alpha_channel < 0 || w[warped.alpha_channel] < 0.999f || qAlpha(g) < 255)
          continue;  // edges: coverage differs in rounding only
        const Eigen::Vector3d want = transformM() * Eigen::Vector3d(w[0], w[1], w[2]);
        worst = std::max({worst, std::abs(qRed(g) - srgbCode(want[0])),
                          std::abs(qGreen(g) - srgbCode(want[1])),
                          std::abs(qBlue(g) - srgbCode(want[2]))});
        ++compared;
      }
    QVERIFY(compared > 200);
    QVERIFY2(worst <= 2, qPrintable(QString("worst %1 codes").arg(worst)));
  }

  void projectKeepsSamplesAndColourBlock() {
    const QString source_path = dir_.filePath("source.tif");
    const QString reference_path = dir_.filePath("reference.tif");
    QVERIFY(writeImage(source_path.toStdString(),
                       blocksPhoto(kBlock, Eigen::Matrix3d::Identity(), "s")->full.image)
                .ok);
    QVERIFY(writeImage(reference_path.toStdString(),
                       blocksPhoto(2 * kBlock, transformM(), "r")->full.image)
                .ok);
    Document doc;
    Session session(&doc, nullptr);
    session.setInteractive(false);
    ColourDock dock(&doc);
    dock.attachToSession(&session);
    session.openPhoto(source_path);
    QTRY_VERIFY_WITH_TIMEOUT(doc.photo() != nullptr, 20000);
    QSignalSpy loaded(&dock, &ColourDock::referenceLoaded);
    dock.openReference(reference_path);
    QVERIFY(loaded.wait(20000));
    QVERIFY(loaded.front().front().toBool());
    ColourSampleState s = dock.model()->state();
    s.radius = 6;
    s.samples = {{{1.0 / 3.0, 50.25}, {20.5, 2.0 / 7.0}, true}, {{100.5, 60.5}, {201, 121}, false}};
    pushColourSamples(dock.model(), s, "samples");
    doc.undoStack()->push(new SetColourBlockCommand(
        &doc, colourCamera(linearMap(transformM()), doc.frame()), "colour"));
    const QString project = dir_.filePath("colour.artcamproj");
    QVERIFY(ui::test::saveAndWait(session, project));

    Document doc2;
    Session session2(&doc2, nullptr);
    session2.setInteractive(false);
    ColourDock dock2(&doc2);
    dock2.attachToSession(&session2);
    QSignalSpy loaded2(&dock2, &ColourDock::referenceLoaded);
    session2.openPath(project);
    QTRY_VERIFY_WITH_TIMEOUT(loaded2.size() == 1, 20000);
    QVERIFY(loaded2.front().front().toBool());
    const ColourSampleState& back = dock2.model()->state();
    QVERIFY(back.samples == s.samples);
    QCOMPARE(back.radius, 6);
    QCOMPARE(back.reference_path, dock.model()->state().reference_path);
    QVERIFY(back.reference != nullptr);
    QVERIFY(doc2.colourBlock().has_value());
    const auto& q1 = doc.colourBlock()->stages()[0].q;
    const auto& q2 = doc2.colourBlock()->stages()[0].q;
    for (size_t i = 0; i < q1.size(); ++i) QVERIFY(q1[i] == q2[i]);
    QVERIFY(!doc2.isModified());  // opening is not an edit
    // The reopened samples read the same colours (the reference was read again).
    const auto a = dock.model()->colourPair(1), b = dock2.model()->colourPair(1);
    QVERIFY(a && b && a->source == b->source && a->target == b->target);
  }

  void malformedPartsAreNamedByPath() {
    const auto parse = [](const char* json) {
      return colourPartFromJson(QJsonDocument::fromJson(json).object(),
                                "p.artcamproj: /parts/colour");
    };
    const auto radius = parse(R"({"radius": 2.5, "samples": []})");
    QVERIFY(!radius.ok());
    QVERIFY(QString::fromStdString(radius.status.message)
                .startsWith("p.artcamproj: /parts/colour/radius"));
    const auto sample =
        parse(R"({"radius": 3, "samples": [{"source": [1, 2], "reference": [3]}]})");
    QVERIFY(!sample.ok());
    QVERIFY(QString::fromStdString(sample.status.message).contains("/parts/colour/samples/0"));
    const auto block = parse(R"({"radius": 3, "samples": [], "colour_block": {"format": "x"}})");
    QVERIFY(!block.ok());
    QVERIFY(QString::fromStdString(block.status.message).contains("/parts/colour/colour_block"));
    const auto good = parse(
        R"({"radius": 3, "samples": [{"source": [1, 2], "reference": [3, 4], "enabled": false}]})");
    QVERIFY2(good.ok(), good.status.message.c_str());
    QCOMPARE(good->state.radius, 3);
    QVERIFY(good->state.samples.size() == 1 && !good->state.samples[0].enabled);
    QVERIFY(good->state.samples[0].reference == Eigen::Vector2d(3, 4));
  }

  void csvExportReadsBackInCore() {
    Studio st;
    QVERIFY(QTest::qWaitForWindowExposed(&st.dock));
    st.load();
    st.pick(0, 0);
    st.pick(3, 1);
    st.pick(2, 3);
    st.dock.table()->item(1, 0)->setCheckState(Qt::Unchecked);
    const QString path = dir_.filePath("samples.csv");
    // Written by a one-shot job: a job runs when the call returns, the file is there at its end.
    QTRY_COMPARE_WITH_TIMEOUT(BackgroundJob::runningCount(), 0, 20000);
    QSignalSpy exported(&st.dock, &ColourDock::csvExported);
    QVERIFY(st.dock.exportCsv(path));
    QVERIFY(BackgroundJob::runningCount() > 0);
    QVERIFY(exported.wait(20000));
    QVERIFY2(exported.front().at(0).toBool(), qPrintable(exported.front().at(1).toString()));
    const Result<std::vector<PointMatch>> read = readColourSamplesCsv(path.toStdString());
    QVERIFY2(read.ok(), read.status.message.c_str());
    QCOMPARE(read->size(), size_t{3});
    const int blocks[3][2] = {{0, 0}, {3, 1}, {2, 3}};
    for (int k = 0; k < 3; ++k) {
      const PointMatch& m = (*read)[static_cast<size_t>(k)];
      const Eigen::Vector3d c = blockColour(blocks[k][0], blocks[k][1]);
      QVERIFY((m.source - c).norm() < 1e-6);
      QVERIFY((m.target - transformM() * c).norm() < 1e-6);
      QCOMPARE(m.enabled, k != 1);
      const auto shown = st.dock.model()->colourPair(k);
      QVERIFY(shown && m.source == shown->source && m.target == shown->target);  // exact digits
    }
  }
};

QTEST_MAIN(TestColourSamples)
#include "test_colour_samples.moc"
