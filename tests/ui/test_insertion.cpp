// SPDX-License-Identifier: Apache-2.0
// Insertion mode: the bundled ray-traced mirror-sphere sample opened through
// the panel's API; the piecewise fit arrives from the worker within the threshold with more
// than one patch (residuals recomputed here against the sample's exact corner positions); the
// preview equals a direct core renderPiecewise + compositeOver of the same camera; the region
// limits it; a grid-tool click near a traced corner snaps to it within 0.1 px, Shift-click
// does not snap, Del and undo remove the match; closing mid-fit shuts down cleanly.
#include "core/io/image_io.h"
#include "core/io/matches_csv.h"
#include "core/io/artcam_file.h"
#include "core/piecewise/piecewise_render.h"
#include "core/piecewise/sample_scenes.h"
#include "core/pipeline/insert_graphic.h"
#include "tests/support/test_support.h"
#include "tests/ui/ui_fixtures.h"
#include "ui/canvas.h"
#include "ui/document.h"
#include "ui/image_convert.h"
#include "ui/image_loader.h"
#include "ui/main_window.h"
#include "ui/matting/insertion_model.h"
#include "ui/matting/insertion_overlay.h"
#include "ui/matting/insertion_panel.h"
#include "ui/matting/insertion_preview.h"
#include "ui/matting/insertion_studio.h"
#include "ui/matting/insertion_worker.h"
#include "ui/tools/grid_tool.h"
#include "ui/tools/region_tool.h"

#include <QAction>
#include <QDockWidget>
#include <QKeyEvent>
#include <QSignalSpy>
#include <QTemporaryDir>
#include <QtTest/QtTest>

#include <algorithm>
#include <memory>

using namespace artcam;
using namespace artcam::ui;

namespace {

const QString kPhoto =
    QString::fromStdString(artcam::test::resourcePath("insertion/mirror-sphere.png"));
const QString kGrid =
    QString::fromStdString(artcam::test::resourcePath("insertion/mirror-sphere-grid.csv"));
const QString kEmblem = QString::fromStdString(artcam::test::resourcePath("insertion/emblem.png"));

// Opens the photo as the studio does (ImageLoader off the GUI thread, then Document::reset).
bool openPhoto(Document& doc, const QString& path) {
  ImageLoader loader(path);
  bool done = false, ok = false;
  QObject::connect(&loader, &ImageLoader::loaded, &doc, [&](const PhotoPtr& photo) {
    doc.reset(photo);
    done = ok = true;
  });
  QObject::connect(&loader, &ImageLoader::failed, &doc, [&](const QString& m) {
    qWarning("%s", qPrintable(m));
    done = true;
  });
  loader.start();
  for (int i = 0; i < 1200 && !done; ++i) QTest::qWait(50);
  return ok && doc.photo() != nullptr;
}

bool waitForCurrent(const InsertionPreview& preview) {
  for (int i = 0; i < 1200 && !preview.isCurrent(); ++i) QTest::qWait(50);
  return preview.isCurrent();
}

struct Rig {
  Document doc;
  InsertionModel model{&doc};
  InsertionPreview preview{&model};
  InsertionPanel panel{&model, &preview};

  Rig() { panel.setInteractive(false); }

  // Photo, grid CSV and graphic, as a user would through the panel.
  bool openSample(const QString& photo = kPhoto, const QString& csv = kGrid) {
    if (!openPhoto(doc, photo)) return false;
    QSignalSpy grid(&panel, &InsertionPanel::gridImported);
    panel.importGridCsv(csv);
    if (!grid.wait(60000) || !grid.front().at(0).toBool()) return false;
    QSignalSpy graphic(&panel, &InsertionPanel::graphicLoaded);
    panel.loadGraphic(kEmblem);
    if (!graphic.wait(60000) || !graphic.front().at(0).toBool()) return false;
    return waitForCurrent(preview);
  }
};

// The preview the worker should show, made here from the files and core calls only.
QImage directComposite(const PiecewiseCamera& camera, const std::vector<Eigen::Vector2d>& region) {
  auto photo = readImage(kPhoto.toStdString());
  auto graphic = readImage(kEmblem.toStdString());
  if (!photo || !graphic) return {};
  ImageF top = renderPiecewise(graphic->image, camera);
  // The region mask, by the definition (pixel centre inside the polygon, even-odd), written
  // out independently of the worker's scanline fill.
  if (region.size() >= 3)
    for (int y = 0; y < top.height; ++y)
      for (int x = 0; x < top.width; ++x) {
        const double px = x + 0.5, py = y + 0.5;
        bool inside = false;
        for (size_t i = 0, j = region.size() - 1; i < region.size(); j = i++) {
          const Eigen::Vector2d& a = region[i];
          const Eigen::Vector2d& b = region[j];
          if ((a.y() > py) != (b.y() > py) &&
              px < (b.x() - a.x()) * (py - a.y()) / (b.y() - a.y()) + a.x())
            inside = !inside;
        }
        if (!inside)
          for (int c = 0; c < top.channels; ++c) top.pixel(x, y)[c] = 0.0f;
      }
  compositeOver(top, photo->image);
  return qimageFromLinear(photo->image);
}

}  // namespace

class TestInsertion : public QObject {
  Q_OBJECT

 private slots:
  void fitArrivesWithinTheThreshold() {
    Rig rig;
    QVERIFY(rig.openSample());
    const auto csv = readMatchesCsv(kGrid.toStdString());
    QVERIFY(csv.ok());
    QCOMPARE(rig.model.state().matches.size(), csv->size());
    QCOMPARE(rig.model.state().max_error_px, 0.5);
    const InsertionFit& fit = rig.preview.fit();
    QVERIFY2(fit.ok, qPrintable(fit.message));
    qInfo("%d patches, max %.3f px, fit %.0f ms in the worker", fit.patches, fit.max_px,
          fit.fit_ms);
    QVERIFY2(fit.patches > 1, qPrintable(fit.report));
    QVERIFY2(fit.max_px < 0.5, qPrintable(fit.report));
    QCOMPARE(fit.patch_outlines.size(), fit.patches);
    // Residuals recomputed from the camera against the traced corners in the CSV.
    double worst = 0.0;
    int mapped = 0;
    for (const PointMatch& m : *csv) {
      const auto p = fit.camera->targetPixelFromSourcePixel(m.source.head<2>());
      if (!p) continue;
      ++mapped;
      worst = std::max(worst, (*p - m.target.head<2>()).norm());
    }
    QVERIFY(mapped > static_cast<int>(csv->size()) * 9 / 10);
    QVERIFY2(worst < 0.5, qPrintable(QString::number(worst)));
    QVERIFY(rig.panel.reportText().contains(QString::number(fit.patches)));
    QVERIFY2(!rig.panel.statusText().startsWith("Fitting"), qPrintable(rig.panel.statusText()));

    // Undo of the import leaves no matches and no fit.
    rig.doc.undoStack()->undo();  // graphic
    rig.doc.undoStack()->undo();  // grid
    QVERIFY(rig.model.state().matches.empty());
    QVERIFY(waitForCurrent(rig.preview));
    QVERIFY(!rig.preview.fit().ok);
    QVERIFY(rig.preview.composite().isNull());
  }

  void waterGlassSampleFits() {
    // The refraction sample (the paper's Fig 8): the same workflow, the same guarantees.
    Rig rig;
    const QString photo =
        QString::fromStdString(artcam::test::resourcePath("insertion/water-glass.png"));
    const QString csv =
        QString::fromStdString(artcam::test::resourcePath("insertion/water-glass-grid.csv"));
    QVERIFY(rig.openSample(photo, csv));
    const InsertionFit& fit = rig.preview.fit();
    QVERIFY2(fit.ok, qPrintable(fit.message));
    QVERIFY2(fit.patches > 1 && fit.max_px < 0.5, qPrintable(fit.report));
    const auto matches = readMatchesCsv(csv.toStdString());
    QVERIFY(matches.ok());
    for (const PointMatch& m : *matches)
      if (const auto p = fit.camera->targetPixelFromSourcePixel(m.source.head<2>()))
        QVERIFY((*p - m.target.head<2>()).norm() < 0.5);
    QVERIFY(!rig.preview.composite().isNull());
  }

  void errorMapOutlinesThePatches() {
    Rig rig;
    QVERIFY(rig.openSample());
    const InsertionFit& fit = rig.preview.fit();
    QVERIFY(fit.ok);
    // Every traced corner lies in the mapped support of the patch that holds it (hulls are of
    // the patch's own matches; the outline is densified, so allow half a pixel).
    const auto csv = readMatchesCsv(kGrid.toStdString());
    QVERIFY(csv.ok());
    int inside = 0;
    for (const PointMatch& m : *csv) {
      const int patch = fit.camera->patchAt(m.source.head<2>());
      if (patch < 0) continue;
      const QPolygonF& outline = fit.patch_outlines[patch];
      QVERIFY(outline.size() >= 3);
      const QPointF t(m.target.x(), m.target.y());
      bool near = outline.containsPoint(t, Qt::OddEvenFill);
      for (int i = 0; !near && i < outline.size(); ++i) {
        const QPointF a = outline[i], b = outline[(i + 1) % outline.size()];
        const QPointF ab = b - a;
        const double len2 = QPointF::dotProduct(ab, ab);
        const double u =
            len2 > 0 ? std::clamp(QPointF::dotProduct(t - a, ab) / len2, 0.0, 1.0) : 0.0;
        const QPointF q = a + u * ab - t;
        near = std::hypot(q.x(), q.y()) < 0.5;
      }
      QVERIFY2(near,
               qPrintable(QString("(%1, %2) outside patch %3").arg(t.x()).arg(t.y()).arg(patch)));
      ++inside;
    }
    QVERIFY(inside > static_cast<int>(csv->size()) / 2);
    // Colours: green at 0, red at and beyond the threshold.
    QCOMPARE(InsertionOverlay::errorColour(0.0, 0.5), QColor(0, 200, 0));
    QCOMPARE(InsertionOverlay::errorColour(0.5, 0.5), QColor(255, 0, 0));
    QCOMPARE(InsertionOverlay::errorColour(3.0, 0.5), QColor(255, 0, 0));
    // The toggle is view state: no undo step.
    const int steps = rig.doc.undoStack()->count();
    rig.model.setErrorMapVisible(false);
    QVERIFY(!rig.model.errorMapVisible());
    QCOMPARE(rig.doc.undoStack()->count(), steps);
  }

  void previewEqualsCoreRender() {
    Rig rig;
    QVERIFY(rig.openSample());
    const InsertionFit fit = rig.preview.fit();
    QVERIFY(fit.ok && fit.camera);
    const QImage expected = directComposite(*fit.camera, {});
    QVERIFY(!expected.isNull());
    QCOMPARE(rig.preview.composite().size(), expected.size());
    QVERIFY(rig.preview.composite() == expected);
    // The graphic really is in it: the composite differs from the plain photo.
    auto photo = readImage(kPhoto.toStdString());
    QVERIFY(photo.ok());
    QVERIFY(rig.preview.composite() != qimageFromLinear(photo->image));

    // A region limits the composite: a triangle over part of the sphere.
    InsertionState next = rig.model.state();
    next.region = {{250.0, 200.0}, {420.0, 230.0}, {300.0, 400.0}};
    rig.model.edit(next, "region");
    QVERIFY(waitForCurrent(rig.preview));
    QCOMPARE(rig.preview.fit().camera, fit.camera);  // only the region changed: no refit
    const QImage limited = directComposite(*fit.camera, next.region);
    QVERIFY(rig.preview.composite() == limited);
    QVERIFY(limited != expected);
    rig.doc.undoStack()->undo();
    QVERIFY(waitForCurrent(rig.preview));
    QVERIFY(rig.preview.composite() == expected);

    // Placed at (128, 128), 256 board px wide: the 512 px emblem is pasted, pixel for pixel,
    // at (256, 256) of a transparent 1024×1024 board (2 pixels per board pixel).
    GraphicPlacement placement;
    placement.origin = {128.0, 128.0};
    placement.width = 256.0;
    rig.panel.setPlacement(placement);
    QVERIFY(waitForCurrent(rig.preview));
    auto emblem = readImage(kEmblem.toStdString());
    auto photo2 = readImage(kPhoto.toStdString());
    QVERIFY(emblem.ok() && photo2.ok());
    QCOMPARE(emblem->image.channels, 4);
    ImageF placed(1024, 1024, 4, 3);
    for (int y = 0; y < 512; ++y)
      for (int x = 0; x < 512; ++x)
        for (int c = 0; c < 4; ++c)
          placed.pixel(x + 256, y + 256)[c] = emblem->image.pixel(x, y)[c];
    compositeOver(renderPiecewise(placed, *fit.camera), photo2->image);
    QVERIFY(rig.preview.composite() == qimageFromLinear(photo2->image));
    QVERIFY(rig.preview.composite() != expected);
    rig.doc.undoStack()->undo();
    QVERIFY(rig.model.state().placement.fillsBoard());
  }

  void tableClicksPutTheGraphicOnTheTable() {
    // Fig 7(b, c) in the studio: with "Clicks on the table", four grid-tool clicks on board
    // corners seen directly fix the board's homography; the preview then shows the graphic on
    // the table (outside the region) and in the reflection, exactly as core's insertGraphic
    // makes it from the same clicks, and the piecewise fit does not see the table clicks.
    Rig rig;
    QVERIFY(rig.openSample());
    const int grid_matches = rig.preview.fit().matches;
    MirrorSphereScene scene;  // the bundled photo's scene (`artcam sample mirror-sphere`)
    scene.photo_width = 640;
    scene.photo_height = 480;
    scene.focal_px = 0.9 * 640;
    scene.floor_centre_z = 1.6;
    InsertionState with_region = rig.model.state();
    with_region.region = makeMirrorSphereSample(scene, 4).region;
    rig.model.edit(with_region, "region");

    Canvas canvas(&rig.doc);
    GridTool tool(&canvas, &rig.doc, &rig.model, &rig.preview, defaultCornerSnapper());
    rig.model.setClickingTable(true);
    const int n = rig.model.cornersPerRow();
    std::vector<PointMatch> clicks;
    for (const auto& [i, j] : {std::pair{2, 2}, {n - 1, 2}, {n - 1, 13}, {2, 13}}) {
      const int corner = (j - 1) * n + (i - 1);
      rig.model.setSelectedCorner(corner);
      const Eigen::Vector2d board = rig.model.cornerPosition(corner);
      const Eigen::Vector2d photo = scene.photoFromWorld(scene.floorFromGraphicPx(board));
      const TracedRay seen_there = scene.trace(photo);
      QVERIFY(seen_there.on_plane && !seen_there.through_object);  // a corner on the table
      tool.placeAt(photo, 0.0);
      PointMatch m;
      m.source = board;
      m.target = photo;
      clicks.push_back(m);
    }
    QCOMPARE(rig.model.tableMatches().size(), size_t(4));
    QCOMPARE(int(rig.model.pointMatches().size()), grid_matches);
    QVERIFY(waitForCurrent(rig.preview));
    const InsertionFit fit = rig.preview.fit();
    QVERIFY2(fit.ok && fit.table, qPrintable(fit.table_report));
    QCOMPARE(fit.matches, grid_matches);
    QVERIFY(rig.panel.reportText().contains("table"));

    auto photo = readImage(kPhoto.toStdString());
    auto graphic = readImage(kEmblem.toStdString());
    QVERIFY(photo.ok() && graphic.ok());
    InsertionCameras cameras;
    cameras.object = *fit.camera;
    const FitSummary table = fitBoardHomography(clicks, rig.model.state().board_size, {640, 480});
    QVERIFY(table.status.ok);
    cameras.plane = table.camera;
    cameras.region = with_region.region;
    const QImage expected = qimageFromLinear(insertGraphic(photo->image, graphic->image, cameras));
    QVERIFY(rig.preview.composite() == expected);
    cameras.plane.reset();
    const QImage reflection_only = qimageFromLinear(insertGraphic(photo->image, graphic->image, cameras));
    QVERIFY(expected != reflection_only);  // the table's copy is there

    // Undo takes the last click away: three clicks fix no homography.
    rig.doc.undoStack()->undo();
    QVERIFY(waitForCurrent(rig.preview));
    QVERIFY(!rig.preview.fit().table);
    QVERIFY(rig.preview.composite() == reflection_only);
  }

  void largePhotosPreviewOnTheirPreviewCopy() {
    // A 2048×1536 traced photo: its preview copy is 1024×768 (box 2×2), and the live composite
    // is made there with the camera retargeted to that frame.
    MirrorSphereScene scene;
    scene.photo_width = 2048;
    scene.photo_height = 1536;
    scene.focal_px = 0.9 * 2048;
    scene.floor_centre_z = 1.6;
    SampleScene sample = makeMirrorSphereSample(scene, 24);
    LoadedImage loaded;
    loaded.image = std::move(sample.photo);
    Rig rig;
    rig.doc.reset(makePhoto(QStringLiteral("sphere-2048.png"), std::move(loaded)));
    QCOMPARE(rig.doc.photo()->preview.width, 1024);
    InsertionState next = rig.model.state();
    for (const PointMatch& m : sample.grid_matches)
      next.matches.push_back({m.source.head<2>(), m.target.head<2>()});
    next.graphic = std::make_shared<const ImageF>(makeEmblemGraphic(512));
    rig.model.edit(next, "sample");
    QVERIFY(waitForCurrent(rig.preview));
    const InsertionFit fit = rig.preview.fit();
    QVERIFY2(fit.ok && fit.max_px < 0.5, qPrintable(fit.report));
    QCOMPARE(rig.preview.composite().size(), QSize(1024, 768));
    // The retargeted camera sends every match to half its full-resolution target.
    const PiecewiseCamera half = InsertionWorker::retarget(*fit.camera, {1024, 768});
    for (const PointMatch& m : sample.grid_matches) {
      const auto a = fit.camera->targetPixelFromSourcePixel(m.source.head<2>());
      const auto b = half.targetPixelFromSourcePixel(m.source.head<2>());
      QCOMPARE(a.has_value(), b.has_value());
      if (a) QVERIFY((*a * 0.5 - *b).norm() < 1e-9);
    }
    ImageF bottom = rig.doc.photo()->preview;
    compositeOver(renderPiecewise(*next.graphic, half), bottom);
    QVERIFY(rig.preview.composite() == qimageFromLinear(bottom));
  }

  void exportsTheImageAndTheCamera() {
    Rig rig;
    QVERIFY(rig.openSample());
    const InsertionFit fit = rig.preview.fit();
    QVERIFY(fit.ok);
    QTemporaryDir dir;
    const QString image_path = dir.filePath("inserted.png");
    const QString camera_path = dir.filePath("sphere.artcam");
    QSignalSpy image_done(&rig.panel, &InsertionPanel::compositeExported);
    rig.panel.exportComposite(image_path);
    QVERIFY(image_done.wait(60000));
    QVERIFY2(image_done.front().at(0).toBool(), qPrintable(image_done.front().at(1).toString()));
    QSignalSpy camera_done(&rig.panel, &InsertionPanel::cameraExported);
    rig.panel.exportCamera(camera_path);
    QVERIFY(camera_done.wait(60000));
    QVERIFY2(camera_done.front().at(0).toBool(), qPrintable(camera_done.front().at(1).toString()));

    // The written image is the direct composite, to 8-bit rounding.
    const auto written = readImage(image_path.toStdString());
    QVERIFY(written.ok());
    const QImage expected = directComposite(*fit.camera, {}).convertToFormat(QImage::Format_RGB32);
    const QImage got = qimageFromLinear(written->image).convertToFormat(QImage::Format_RGB32);
    QCOMPARE(got.size(), expected.size());
    int worst = 0;
    for (int y = 0; y < got.height(); ++y)
      for (int x = 0; x < got.width(); ++x) {
        const QRgb a = got.pixel(x, y), b = expected.pixel(x, y);
        worst = std::max({worst, std::abs(qRed(a) - qRed(b)), std::abs(qGreen(a) - qGreen(b)),
                          std::abs(qBlue(a) - qBlue(b))});
      }
    QVERIFY2(worst <= 1, qPrintable(QString::number(worst)));

    // The camera file reads back with the same patches, mapping the matches the same.
    const auto doc = readArtcam(camera_path.toStdString());
    QVERIFY2(doc.ok(), doc.status.message.c_str());
    QVERIFY(doc->pieces);
    QCOMPARE(doc->pieces->patches.size(), fit.camera->patches.size());
    for (const GridMatch& m : rig.model.state().matches) {
      const auto a = fit.camera->targetPixelFromSourcePixel(m.board);
      const auto b = doc->pieces->targetPixelFromSourcePixel(m.board);
      QCOMPARE(a.has_value(), b.has_value());
      if (a) QVERIFY((*a - *b).norm() < 1e-9);
    }
  }

  void gridClickSnapsToTheCorner() {
    // The mirror sphere traced in code at twice the bundled sample's resolution (as a user
    // would shoot a calibration photo; at 640×480 the reflected squares are 7 px wide and the
    // photo holds a corner to about 0.13 px only), with its exact corners (Newton on the tracer).
    MirrorSphereScene scene;
    scene.photo_width = 1280;
    scene.photo_height = 960;
    scene.focal_px = 0.9 * 1280;
    scene.floor_centre_z = 1.6;
    SampleScene sample = makeMirrorSphereSample(scene, 24);
    LoadedImage loaded;
    loaded.image = std::move(sample.photo);
    loaded.info.path = "mirror-sphere-1280.png";
    Rig rig;
    rig.doc.reset(makePhoto(QStringLiteral("mirror-sphere-1280.png"), std::move(loaded)));
    Canvas canvas(&rig.doc);
    canvas.resize(800, 600);
    canvas.show();
    canvas.setTool(std::make_unique<GridTool>(&canvas, &rig.doc, &rig.model, &rig.preview,
                                              defaultCornerSnapper()));
    // Click (0.9, -0.7) px off every interior corner whose neighbours are 8 px away or more,
    // zoomed to 2× about it as a user placing points would be.
    std::vector<double> errors;
    int first_corner = -1;
    Eigen::Vector2d first_truth;
    for (const PointMatch& m : sample.grid_matches) {
      if (m.source.minCoeff() < 1.0 || m.source.maxCoeff() > 511.0) continue;  // not X-corners
      double nearest = 1e9;
      for (const PointMatch& n : sample.grid_matches)
        if (&n != &m) nearest = std::min(nearest, (n.target - m.target).norm());
      if (nearest < 8.0) continue;
      const Eigen::Vector2d truth = m.target.head<2>();
      const int board_corner = rig.model.cornerAt(m.source.head<2>(), 1e-6);
      QVERIFY(board_corner >= 0);
      rig.model.setSelectedCorner(board_corner);
      canvas.setView(2.0, QPointF(truth.x(), truth.y()));
      const size_t before = rig.model.state().matches.size();
      artcam::ui::test::click(
          &canvas, artcam::ui::test::widgetPoint(canvas, truth + Eigen::Vector2d(0.9, -0.7)));
      QCOMPARE(rig.model.state().matches.size(), before + 1);
      const GridMatch placed = rig.model.state().matches.back();
      QVERIFY((placed.board - m.source.head<2>()).norm() < 1e-9);
      QCOMPARE(rig.model.selectedMatch(), static_cast<int>(before));
      if (board_corner + 1 < rig.model.cornerCount())
        QCOMPARE(rig.model.selectedCorner(), board_corner + 1);  // advanced along the row
      errors.push_back((placed.photo - truth).norm());
      if (first_corner < 0) {
        first_corner = board_corner;
        first_truth = truth;
      }
    }
    QVERIFY(errors.size() >= 20);
    std::vector<double> sorted = errors;
    std::sort(sorted.begin(), sorted.end());
    const double median = sorted[sorted.size() / 2];
    qInfo("%zu clicks snapped: median %.4f px, worst %.4f px", sorted.size(), median,
          sorted.back());
    QVERIFY2(median < 0.1, qPrintable(QString::number(median)));
    QVERIFY2(sorted.back() < 0.3, qPrintable(QString::number(sorted.back())));

    // Undo removes the last click; redo brings it back; Del removes the selected match.
    const size_t n = rig.model.state().matches.size();
    rig.doc.undoStack()->undo();
    QCOMPARE(rig.model.state().matches.size(), n - 1);
    rig.doc.undoStack()->redo();
    QCOMPARE(rig.model.state().matches.size(), n);
    rig.model.setSelectedMatch(0);
    const GridMatch removed = rig.model.state().matches.front();
    QKeyEvent del(QEvent::KeyPress, Qt::Key_Delete, Qt::NoModifier);
    QCoreApplication::sendEvent(&canvas, &del);
    QCOMPARE(rig.model.state().matches.size(), n - 1);
    rig.doc.undoStack()->undo();
    QCOMPARE(rig.model.state().matches.size(), n);
    QVERIFY(rig.model.state().matches.front() == removed);
    while (rig.doc.undoStack()->canUndo()) rig.doc.undoStack()->undo();
    QVERIFY(rig.model.state().matches.empty());

    // Shift-click: no snap, the clicked image point itself.
    rig.model.setSelectedCorner(first_corner);
    canvas.setView(2.0, QPointF(first_truth.x(), first_truth.y()));
    const QPoint w =
        artcam::ui::test::widgetPoint(canvas, first_truth + Eigen::Vector2d(0.9, -0.7));
    artcam::ui::test::click(&canvas, w, Qt::ShiftModifier);
    const QPointF raw = canvas.view().imageFromWidget(QPointF(w));
    QCOMPARE(rig.model.state().matches.size(), size_t(1));
    QVERIFY((rig.model.state().matches.front().photo - Eigen::Vector2d(raw.x(), raw.y())).norm() <
            1e-9);
    QVERIFY((rig.model.state().matches.front().photo - first_truth).norm() > 0.5);

    // Dragging the match drops it on the corner near the release point, snapped; undo.
    const Eigen::Vector2d unsnapped = rig.model.state().matches.front().photo;
    artcam::ui::test::drag(
        &canvas, artcam::ui::test::widgetPoint(canvas, unsnapped),
        artcam::ui::test::widgetPoint(canvas, first_truth + Eigen::Vector2d(-0.8, 0.6)));
    QCOMPARE(rig.model.state().matches.size(), size_t(1));
    const double dropped = (rig.model.state().matches.front().photo - first_truth).norm();
    QVERIFY2(dropped < 0.3, qPrintable(QString::number(dropped)));
    rig.doc.undoStack()->undo();
    QVERIFY(rig.model.state().matches.front().photo == unsnapped);
  }

  void mainWindowHasTheInsertionMode() {
    MainWindow window;
    auto* dock = window.findChild<QDockWidget*>(QStringLiteral("insertionDock"));
    QVERIFY(dock);
    QVERIFY(qobject_cast<InsertionPanel*>(dock->widget()));
    auto* studio = window.findChild<InsertionStudio*>();
    QVERIFY(studio);
    QCOMPARE(studio->gridToolAction()->shortcut(), QKeySequence(QStringLiteral("C")));
    QVERIFY(!studio->gridToolAction()->toolTip().isEmpty());
    studio->gridToolAction()->trigger();
    QVERIFY(dynamic_cast<GridTool*>(window.canvas()->tool()));
    studio->regionToolAction()->trigger();
    QVERIFY(dynamic_cast<RegionTool*>(window.canvas()->tool()));
    // Insertion edits are steps of the document's undo stack.
    studio->panel()->setSquares(12);
    QCOMPARE(studio->model()->state().squares, 12);
    window.document()->undoStack()->undo();
    QCOMPARE(studio->model()->state().squares, 24);
  }

  void regionToolMarksThePolygon() {
    Rig rig;
    QVERIFY(openPhoto(rig.doc, kPhoto));
    Canvas canvas(&rig.doc);
    canvas.resize(640, 480);
    canvas.show();
    canvas.zoomToFit();
    auto tool = std::make_unique<RegionTool>(&canvas, &rig.doc, &rig.model, &rig.preview);
    RegionTool* region = tool.get();
    canvas.setTool(std::move(tool));
    const std::vector<Eigen::Vector2d> corners = {{100, 100}, {400, 120}, {300, 380}};
    for (const Eigen::Vector2d& c : corners)
      artcam::ui::test::click(&canvas, artcam::ui::test::widgetPoint(canvas, c));
    QCOMPARE(region->pending().size(), size_t(3));
    QVERIFY(rig.model.state().region.empty());
    QKeyEvent enter(QEvent::KeyPress, Qt::Key_Return, Qt::NoModifier);
    QCoreApplication::sendEvent(&canvas, &enter);
    QCOMPARE(rig.model.state().region.size(), size_t(3));
    for (size_t i = 0; i < corners.size(); ++i)
      QVERIFY((rig.model.state().region[i] - corners[i]).norm() < 1.0 / canvas.view().scale());
    rig.doc.undoStack()->undo();
    QVERIFY(rig.model.state().region.empty());
  }

  void closingMidFitShutsDownCleanly() {
    auto rig = std::make_unique<Rig>();
    QVERIFY(openPhoto(rig->doc, kPhoto));
    QSignalSpy grid(&rig->panel, &InsertionPanel::gridImported);
    rig->panel.importGridCsv(kGrid);
    QVERIFY(grid.wait(60000));
    // Several edits in a row: fits queued and in flight when everything is destroyed.
    for (double e : {0.4, 0.3, 0.25}) rig->panel.setMaxError(e);
    QVERIFY(!rig->preview.isCurrent());
    rig.reset();
    QTest::qWait(200);  // queued results of the dead worker must not be delivered anywhere
  }
};

QTEST_MAIN(TestInsertion)
#include "test_insertion.moc"
