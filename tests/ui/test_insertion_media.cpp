// SPDX-License-Identifier: Apache-2.0
// Fig 8(d) in the Insertion panel: `artcam sample glass-of-water` (a glass filled to half its
// height) opened, the graphic loaded, the grid through the water imported, then New Medium and
// the grid through the air above the waterline. The panel lists both media and each is its own
// piecewise camera; the exported composite puts the graphic where the ray tracer sees it
// through each medium (the truth of tests/app/glass_of_water_truth.h, as for the command line's
// two chained inserts, whose picture it equals); editing a medium keeps the other; undo takes
// the new medium back; the project keeps both.
#include "core/io/artcam_file.h"
#include "core/io/image_io.h"
#include "tests/app/cli_run.h"
#include "tests/app/glass_of_water_truth.h"
#include "ui/document.h"
#include "ui/image_loader.h"
#include "ui/matting/insertion_model.h"
#include "ui/matting/insertion_panel.h"
#include "ui/matting/insertion_preview.h"
#include "ui/matting/insertion_project.h"

#include <QComboBox>
#include <QSignalSpy>
#include <QTemporaryDir>
#include <QUndoStack>
#include <QtTest/QtTest>

using namespace artcam;
using namespace artcam::ui;

namespace {

bool openPhoto(Document& doc, const QString& path) {
  ImageLoader loader(path);
  bool done = false, ok = false;
  QObject::connect(&loader, &ImageLoader::loaded, &doc, [&](const PhotoPtr& photo) {
    doc.reset(photo);
    done = ok = true;
  });
  QObject::connect(&loader, &ImageLoader::failed, &doc, [&](const QString&) { done = true; });
  loader.start();
  for (int i = 0; i < 1200 && !done; ++i) QTest::qWait(50);
  return ok && doc.photo() != nullptr;
}

bool waitForCurrent(const InsertionPreview& preview) {
  for (int i = 0; i < 1200 && !preview.isCurrent(); ++i) QTest::qWait(50);
  return preview.isCurrent();
}

ImageF load(const QString& path) {
  const auto r = readImage(path.toStdString());
  return r ? r->image : ImageF();
}

}  // namespace

class TestInsertionMedia : public QObject {
  Q_OBJECT

  QTemporaryDir dir_;
  QString path(const QString& name) const { return dir_.filePath(name); }

 private slots:
  void initTestCase() {
    QVERIFY(dir_.isValid());
    const auto made = artcam::test::artcamCli(
        {"sample", "glass-of-water", "-o", dir_.path(), "--size", "320x240"});
    QVERIFY2(made.exit_code == 0, qPrintable(made.err));
  }

  void graphicGoesThroughWaterAndAir() {
    Document doc;
    InsertionModel model(&doc);
    InsertionPreview preview(&model);
    InsertionPanel panel(&model, &preview);
    panel.setInteractive(false);
    QVERIFY(openPhoto(doc, path("glass-of-water.png")));
    QSignalSpy graphic(&panel, &InsertionPanel::graphicLoaded);
    panel.loadGraphic(path("emblem.png"));
    QVERIFY(graphic.wait(60000) && graphic.front().at(0).toBool());
    QSignalSpy grid(&panel, &InsertionPanel::gridImported);
    panel.importGridCsv(path("glass-of-water-grid.csv"));
    QVERIFY(grid.wait(60000) && grid.last().at(0).toBool());
    QVERIFY(waitForCurrent(preview));
    QVERIFY2(preview.fit().ok, qPrintable(preview.fit().message));
    const size_t water_matches = model.state().matches.size();

    // A second medium: the first stays, the grid now fills the new one.
    model.addMedium();
    QCOMPARE(model.mediumCount(), 2);
    QCOMPARE(model.state().current_medium, 1);
    QVERIFY(model.state().matches.empty());
    QCOMPARE(model.state().other_media.front().matches.size(), water_matches);
    panel.importGridCsv(path("glass-of-water-air-grid.csv"));
    QVERIFY(grid.wait(60000) && grid.last().at(0).toBool());
    QVERIFY(waitForCurrent(preview));
    QVERIFY2(preview.fit().ok, qPrintable(preview.fit().message));
    QCOMPARE(preview.fit().other_media.size(), size_t{1});
    QVERIFY(preview.fit().other_media.front().ok);
    QCOMPARE(panel.mediumBox()->count(), 2);
    QCOMPARE(panel.mediumBox()->currentIndex(), 1);
    QVERIFY2(panel.statusText().contains("Medium 1:"), qPrintable(panel.statusText()));

    // Export Piecewise Camera writes the edited medium's camera and says it is one of two: a
    // file that passed for the whole chain would insert through the air only.
    QSignalSpy camera_done(&panel, &InsertionPanel::cameraExported);
    panel.exportCamera(path("air.artcam"));
    QVERIFY(camera_done.wait(60000));
    const QString said = camera_done.last().at(1).toString();
    QVERIFY2(camera_done.last().at(0).toBool(), qPrintable(said));
    QVERIFY2(said.contains("medium 2 of 2 only"), qPrintable(said));
    QCOMPARE(panel.statusText(), said);
    const auto air = readArtcam(path("air.artcam").toStdString());
    QVERIFY2(air.ok(), air ? "" : air.status.message.c_str());
    QVERIFY(air->pieces.has_value());
    QCOMPARE(air->pieces->patches.size(), preview.fit().camera->patches.size());
    for (const CameraPatch& patch : preview.fit().camera->patches) {
      // The middle of the patch's own matches: inside its support, so both must answer.
      Eigen::Vector2d probe = Eigen::Vector2d::Zero();
      for (const Eigen::Vector2d& corner : patch.support) probe += corner;
      probe /= double(std::max<size_t>(1, patch.support.size()));
      const auto written = air->pieces->targetPixelFromSourcePixel(probe);
      const auto fitted = preview.fit().camera->targetPixelFromSourcePixel(probe);
      QVERIFY(written.has_value() && fitted.has_value());
      QVERIFY((*written - *fitted).norm() < 1e-9);
    }

    QSignalSpy exported(&panel, &InsertionPanel::compositeExported);
    panel.exportComposite(path("studio-both.png"));
    QVERIFY(exported.wait(60000));
    QVERIFY2(exported.last().at(0).toBool(), qPrintable(exported.last().at(1).toString()));
    const ImageF photo = load(path("glass-of-water.png"));
    const ImageF emblem = load(path("emblem.png"));
    const ImageF both = load(path("studio-both.png"));
    QCOMPARE(both.width, 320);
    for (const auto medium : {GlassOfWaterScene::Medium::Water, GlassOfWaterScene::Medium::Air}) {
      const artcam::test::TracerComparison c = artcam::test::compareWithTracer(
          photo, emblem, both, artcam::test::sampleGlassOfWater320(), medium);
      qInfo(
          "studio, through %s: mean %.4f against the tracer over %lld px (the graphic changes "
          "them by %.3f)",
          medium == GlassOfWaterScene::Medium::Water ? "water" : "air", c.mean, c.pixels, c.change);
      QVERIFY(c.pixels > 300);
      QVERIFY2(c.mean < 0.02 && c.change > 8 * c.mean,
               qPrintable(QString("mean %1, change %2").arg(c.mean).arg(c.change)));
    }
    // The command line's two chained inserts give the same picture.
    auto r = artcam::test::artcamCli({"insert", path("glass-of-water.png"), path("emblem.png"),
                                      "--matches", path("glass-of-water-grid.csv"), "-o",
                                      path("water.png")});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    r = artcam::test::artcamCli({"insert", path("water.png"), path("emblem.png"), "--matches",
                                 path("glass-of-water-air-grid.csv"), "-o", path("cli-both.png")});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    const ImageF cli = load(path("cli-both.png"));
    double worst = 0.0;
    for (int y = 0; y < 240; ++y)
      for (int x = 0; x < 320; ++x)
        for (int c = 0; c < 3; ++c)
          worst = std::max(worst, double(std::abs(cli.pixel(x, y)[c] - both.pixel(x, y)[c])));
    qInfo("studio vs two artcam inserts: largest difference %.4f", worst);
    QVERIFY2(worst < 0.02, qPrintable(QString::number(worst)));

    // Editing the first medium brings its grid back and keeps the second.
    model.editMedium(0);
    QCOMPARE(model.state().current_medium, 0);
    QCOMPARE(model.state().matches.size(), water_matches);
    QCOMPARE(model.state().other_media.size(), size_t{1});
    QVERIFY(waitForCurrent(preview));
    QCOMPARE(preview.fit().other_media.size(), size_t{1});
    QCOMPARE(panel.mediumBox()->currentIndex(), 0);

    // Kept in the project's part, and read back the same.
    const auto back = insertionFromJson(insertionToJson(model.state()), "p");
    QVERIFY(back.ok());
    QCOMPARE(back->other_media, model.state().other_media);
    QCOMPARE(back->current_medium, 0);

    // Undo: back to editing the air, then the second medium is gone (the air's grid with it).
    doc.undoStack()->undo();
    QCOMPARE(model.state().current_medium, 1);
    doc.undoStack()->undo();  // the air's grid import
    doc.undoStack()->undo();  // New Medium
    QCOMPARE(model.mediumCount(), 1);
    QCOMPARE(model.state().matches.size(), water_matches);
  }

  void projectRefusesTooManyMedia() {
    QJsonObject o = insertionToJson([] {
      InsertionState s;
      s.matches.push_back({{1, 1}, {2, 2}, false});
      return s;
    }());
    QJsonArray media;
    for (int i = 0; i < kMaxInsertionMedia; ++i)
      media.append(QJsonObject{{"matches", QJsonArray{}}, {"region", QJsonArray{}}});
    o["other_media"] = media;
    const auto r = insertionFromJson(o, "project: /parts/insertion");
    QVERIFY(!r.ok());
    QVERIFY2(QString::fromStdString(r.status.message).contains("/other_media"),
             r.status.message.c_str());
    o["other_media"] = QJsonArray{QJsonObject{{"matches", QJsonArray{}}, {"region", QJsonArray{}}}};
    o["current_medium"] = 5;
    QVERIFY(!insertionFromJson(o, "p").ok());
  }
};

QTEST_MAIN(TestInsertionMedia)
#include "test_insertion_media.moc"
