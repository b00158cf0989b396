// SPDX-License-Identifier: Apache-2.0
// Files: project save/open round trip (atomic, exact pairs), photo loading off the GUI
// thread, .artcam export/import, full-resolution export, and the pairs table editing both ways.
#include "core/effects/effect_table.h"
#include "core/io/artcam_file.h"
#include "core/io/image_io.h"
#include "ui/depth_commands.h"
#include "ui/depth_model.h"
#include "ui/panels/tensor_panel.h"
#include "tests/support/icc_files.h"
#include "tests/ui/ui_fixtures.h"
#include "tests/ui/session_wait.h"
#include "ui/export_options_dialog.h"
#include "ui/commands.h"
#include "ui/document.h"
#include "ui/panels/pairs_panel.h"
#include "ui/project_file.h"
#include "ui/session.h"

#include <QComboBox>
#include <QDir>
#include <QSettings>
#include <QSignalSpy>
#include <QStandardPaths>
#include <QTableView>
#include <QTemporaryDir>
#include <QtTest/QtTest>

#include <OpenImageIO/imageio.h>

using namespace artcam;
using namespace artcam::ui;

class TestSession : public QObject {
  Q_OBJECT

  QTemporaryDir dir_;

  QString writeSamplePhoto() {
    const QString path = dir_.filePath("photo.png");
    const PhotoPtr p = ui::test::syntheticPhoto();
    const Status s = writeImage(path.toStdString(), p->full.image);
    if (!s) qWarning("%s", s.message.c_str());
    return path;
  }

 private slots:
  void initTestCase() {
    QStandardPaths::setTestModeEnabled(true);
    QVERIFY(dir_.isValid());
    // A Session starts from the export options the last one set (kept in QSettings); the
    // exports below assume the defaults, whatever an earlier run of this program chose.
    QSettings().remove("export");
  }

  void projectRoundTripIsExact() {
    Project p;
    p.photo_path = dir_.filePath("photo.png");
    p.pairs = ui::test::ninePairs();
    p.pairs[3].enabled = false;
    p.pairs[0].source = {1.0 / 3.0, 2.0 / 7.0};  // needs all 17 digits
    p.model = ModelClass::Homography;
    p.view.scale = 1.5;
    p.view.centre = QPointF(100.25, 50.5);
    p.view.preview_mode = 2;
    const QString path = dir_.filePath("a.artcamproj");
    QVERIFY(writeProject(path, p).ok);
    const Result<Project> back = readProject(path);
    QVERIFY2(back.ok(), back.status.message.c_str());
    QCOMPARE(back->photo_path, p.photo_path);
    QVERIFY(back->pairs == p.pairs);
    QCOMPARE(back->model, p.model);
    QCOMPARE(back->view.scale, 1.5);
    QCOMPARE(back->view.centre, p.view.centre);
    QCOMPARE(back->view.preview_mode, 2);
    // The photo is stored relative to the project, so the folder can move.
    QFile f(path);
    QVERIFY(f.open(QIODevice::ReadOnly));
    QVERIFY(f.readAll().contains("\"photo\": \"photo.png\""));
  }

  void projectErrorsNameTheCause() {
    const auto newer = parseProject(
        R"({"format":"artcam-studio-project","version":99,"photo":"x.png"})", "p.artcamproj");
    QVERIFY(!newer.ok());
    QVERIFY(QString::fromStdString(newer.status.message).contains("newer"));
    const auto bad = parseProject(
        R"({"format":"artcam-studio-project","version":1,"photo":"x.png","pairs":[{"source":[1],"target":[2,3]}]})",
        "p.artcamproj");
    QVERIFY(!bad.ok());
    QVERIFY(QString::fromStdString(bad.status.message).contains("/pairs/0/source"));
  }

  void sessionSavesAndReopens() {
    const QString photo = writeSamplePhoto();
    Document doc;
    Session session(&doc, nullptr);
    session.setInteractive(false);
    session.openPhoto(photo);
    QTRY_VERIFY_WITH_TIMEOUT(doc.photo() != nullptr, 20000);
    QCOMPARE(doc.frame().width, 320);
    for (const Pair& p : ui::test::ninePairs()) doc.undoStack()->push(new AddPairCommand(&doc, p));
    QVERIFY(doc.isModified());
    const QString project = dir_.filePath("session.artcamproj");
    QVERIFY(ui::test::saveAndWait(session, project));
    QVERIFY(!doc.isModified());
    const std::vector<Pair> saved = doc.pairs();

    Document doc2;
    Session session2(&doc2, nullptr);
    session2.setInteractive(false);
    QSignalSpy errors(&session2, &Session::errorOccurred);
    session2.openPath(project);
    QTRY_VERIFY_WITH_TIMEOUT(doc2.photo() != nullptr || !errors.isEmpty(), 20000);
    QVERIFY2(errors.isEmpty(),
             errors.isEmpty() ? "" : qPrintable(errors.front().front().toString()));
    QVERIFY(doc2.pairs() == saved);
    QVERIFY(doc2.fit().status.ok);
    QCOMPARE(doc2.camera().stages()[0].q, doc.camera().stages()[0].q);
    QVERIFY(!doc2.isModified());
  }

  // A photo with more than four channels (an EXR with depth) opens with its first four, and the
  // status line names the channels left out.
  void extraChannelsAreNamedOnLoad() {
    const QString file = dir_.filePath("five.exr");
    OIIO::ImageSpec spec(32, 24, 5, OIIO::TypeDesc::FLOAT);
    spec.channelnames = {"R", "G", "B", "A", "Z"};
    spec.alpha_channel = 3;
    std::vector<float> pixels(32 * 24 * 5, 0.5f);
    auto out = OIIO::ImageOutput::create(file.toStdString());
    QVERIFY(out && out->open(file.toStdString(), spec) &&
            out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()) && out->close());
    Document doc;
    Session session(&doc, nullptr);
    session.setInteractive(false);
    QSignalSpy status(&session, &Session::statusMessage);
    session.openPhoto(file);
    QTRY_VERIFY_WITH_TIMEOUT(doc.photo() != nullptr, 20000);
    QCOMPARE(doc.photo()->full.image.channels, 4);
    bool named = false;
    for (const QList<QVariant>& m : status)
      named = named || (m.front().toString().contains("Loaded five.exr") &&
                        m.front().toString().contains("(Z) are not shown or exported"));
    QVERIFY(named);
  }

  void missingPhotoIsAnErrorNamingTheFile() {
    Document doc;
    Session session(&doc, nullptr);
    session.setInteractive(false);
    QSignalSpy errors(&session, &Session::errorOccurred);
    session.openPhoto(dir_.filePath("does-not-exist.png"));
    QTRY_COMPARE_WITH_TIMEOUT(errors.size(), 1, 20000);
    QVERIFY(errors.front().front().toString().contains("does-not-exist.png"));
    QVERIFY(!doc.photo());
  }

  void artcamExportImportAndImageExport() {
    Document doc;
    Session session(&doc, nullptr);
    session.setInteractive(false);
    doc.reset(ui::test::syntheticPhoto(), ui::test::ninePairs(), ModelClass::Quadratic);
    QVERIFY(doc.fit().status.ok);
    const QString cam = dir_.filePath("cam.artcam");
    QVERIFY(ui::test::writeAndWait(session, [&] { return session.exportArtcam(cam); }));

    Document doc2;
    Session session2(&doc2, nullptr);
    session2.setInteractive(false);
    doc2.reset(ui::test::syntheticPhoto());
    QVERIFY(ui::test::importAndWait(session2, cam));
    QCOMPARE(doc2.pairs().size(), size_t{9});
    doc2.undoStack()->push(new SetModelCommand(&doc2, ModelClass::Quadratic));
    QCOMPARE(doc2.camera().stages()[0].q, doc.camera().stages()[0].q);
    doc2.undoStack()->undo();
    doc2.undoStack()->undo();  // the import is one undo step
    QCOMPARE(doc2.pairs().size(), size_t{0});

    QSignalSpy finished(&session, &Session::exportFinished);
    const QString out = dir_.filePath("warped.png");
    session.exportImage(out);
    QTRY_COMPARE_WITH_TIMEOUT(finished.size(), 1, 60000);
    QVERIFY2(finished.front().at(0).toBool(), qPrintable(finished.front().at(1).toString()));
    const Result<LoadedImage> back = readImage(out.toStdString());
    QVERIFY(back.ok());
    QCOMPARE(back->image.width, 320);
    QCOMPARE(back->image.height, 240);
  }

  // The export dialog's colour space reaches the file: an Adobe RGB photo exported "As the
  // photo" keeps its profile and its codes, "sRGB" is re-encoded and labelled sRGB.
  void exportColourSpaceFromTheDialog() {
    ExportOptions current;
    current.write.colour_space = WriteImageOptions::ColourSpace::Srgb;
    ExportOptionsDialog dialog(current, "out.png");
    auto* combo = dialog.findChild<QComboBox*>("colourSpace");
    QVERIFY(combo);
    QCOMPARE(dialog.options().write.colour_space, WriteImageOptions::ColourSpace::Srgb);
    combo->setCurrentIndex(combo->findData(int(WriteImageOptions::ColourSpace::Input)));
    QCOMPARE(dialog.options().write.colour_space, WriteImageOptions::ColourSpace::Input);

    // A flat Adobe RGB colour, so every pixel the camera covers keeps it.
    const std::uint16_t code[3] = {13107, 39321, 26214};
    std::vector<std::uint16_t> pixels(320 * 240 * 3);
    for (size_t k = 0; k < pixels.size(); ++k) pixels[k] = code[k % 3];
    const std::vector<unsigned char> adobe = artcam::test::adobeRgbProfile();
    const QString photo_path = dir_.filePath("adobe.png");
    QVERIFY(artcam::test::write16(photo_path.toStdString(), 320, 240, 3, pixels, adobe));
    Result<LoadedImage> loaded = readImage(photo_path.toStdString());
    QVERIFY2(loaded.ok(), loaded.status.message.c_str());
    QVERIFY(loaded->info.icc);
    Document doc;
    Session session(&doc, nullptr);
    session.setInteractive(false);
    doc.reset(makePhoto(photo_path, std::move(*loaded.value)), ui::test::ninePairs(),
              ModelClass::Quadratic);
    QVERIFY(doc.fit().status.ok);

    auto exportWith = [&](WriteImageOptions::ColourSpace space, const QString& name,
                          std::vector<std::uint16_t>& centre) {
      ExportOptions options;
      options.write.colour_space = space;
      session.setExportOptions(options);
      QSignalSpy finished(&session, &Session::exportFinished);
      const QString out = dir_.filePath(name);
      session.exportImage(out);
      if (!QTest::qWaitFor([&] { return finished.size() == 1; }, 60000)) return std::vector<unsigned char>{};
      if (!finished.front().at(0).toBool()) qWarning("%s", qPrintable(finished.front().at(1).toString()));
      auto in = OIIO::ImageInput::open(out.toStdString());
      if (!in) return std::vector<unsigned char>{};
      const OIIO::ImageSpec spec = in->spec();
      std::vector<std::uint16_t> all(static_cast<size_t>(spec.width) * spec.height * spec.nchannels);
      in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT16, all.data());
      const size_t at = (static_cast<size_t>(spec.height / 2) * spec.width + spec.width / 2) * spec.nchannels;
      centre.assign(all.begin() + at, all.begin() + at + 3);
      return artcam::test::profileOf(spec);
    };
    std::vector<std::uint16_t> kept, srgb;
    QVERIFY(exportWith(WriteImageOptions::ColourSpace::Input, "as-photo.png", kept) == adobe);
    for (int c = 0; c < 3; ++c) QVERIFY2(std::abs(int(kept[c]) - int(code[c])) <= 2, qPrintable(QString::number(kept[c])));
    const std::vector<unsigned char> srgb_profile =
        exportWith(WriteImageOptions::ColourSpace::Srgb, "srgb.png", srgb);
    QVERIFY(!srgb_profile.empty() && srgb_profile != adobe);
    // Adobe's green primary lies outside sRGB: this green-heavy colour's red comes out lower.
    QVERIFY2(srgb[0] + 1000 < kept[0], qPrintable(QString("%1 vs %2").arg(srgb[0]).arg(kept[0])));
  }

  void importTakesEveryKindAndKeepsIt() {
    Document doc;
    Session session(&doc, nullptr);
    session.setInteractive(false);
    doc.reset(ui::test::syntheticPhoto());
    TensorPanel tensors(&doc);
    // Chromatic aberration: three layers, one per colour (the paper's Fig 4), made for another
    // frame size: it is scaled to the photo and every layer is kept.
    const QString ca = dir_.filePath("ca.artcam");
    QVERIFY(writeArtcam(ca.toStdString(), buildEffect("chromatic-aberration", {}, {600, 400})).ok);
    QVERIFY(ui::test::importAndWait(session, ca));
    QVERIFY(doc.manualCamera());
    QCOMPARE(doc.artcam().kind(), ArtcamKind::Layered);
    QCOMPARE(doc.artcam().layers.size(), size_t{3});
    QCOMPARE(doc.artcam().sourceSize(), (FrameSize{320, 240}));
    QVERIFY2(tensors.summary().contains("layered") && tensors.summary().contains("3 layers"),
             qPrintable(tensors.summary()));
    // A tensor edit changes the geometry (layer 1) and keeps the other layers.
    tensors.setEntry(0, 0, 0, 0, 0.5);
    QCOMPARE(doc.artcam().layers.size(), size_t{3});
    // Saved and reopened, the project keeps the whole camera.
    const QString project = dir_.filePath("ca.artcamproj");
    const auto p = session.currentProject();
    QVERIFY(p);
    QVERIFY(writeProject(project, *p).ok);
    const auto back = readProject(project);
    QVERIFY2(back.ok(), back.status.message.c_str());
    QVERIFY(back->manual_camera);
    QCOMPARE(back->manual_camera->layers.size(), size_t{3});
    // An attributed camera (aerial perspective reads depth): its colour and depth blocks stay.
    const QString ap = dir_.filePath("ap.artcam");
    QVERIFY(writeArtcam(ap.toStdString(), buildEffect("aerial-perspective", {}, {320, 240})).ok);
    QVERIFY(ui::test::importAndWait(session, ap));
    QCOMPARE(doc.artcam().kind(), ArtcamKind::Attributed);
    QVERIFY(readsDepth(doc.artcam()));
    QVERIFY2(tensors.summary().contains("depth"), qPrintable(tensors.summary()));
    doc.undoStack()->undo();
    QCOMPARE(doc.artcam().kind(), ArtcamKind::Layered);
  }

  void depthMapAndExportOptions() {
    Document doc;
    Session session(&doc, nullptr);
    session.setInteractive(false);
    doc.reset(ui::test::syntheticPhoto());
    const QString depth_path = dir_.filePath("depth.exr");
    QVERIFY(!session.exportDepthMap(depth_path));  // nothing painted yet
    QVERIFY(!QFile::exists(depth_path));
    // A plane over the left half at depth 3 everywhere (three anchors at one depth).
    DepthPlaneLayer layer = doc.depth()->makeLayer();
    layer.mask.fillPolygon({{0, 0}, {160, 0}, {160, 240}, {0, 240}});
    layer.anchors = {{{10.5, 10.5}, 3.0}, {{150.5, 10.5}, 3.0}, {{10.5, 230.5}, 3.0}};
    doc.undoStack()->push(new AddDepthLayerCommand(doc.depth(), layer));
    QVERIFY(ui::test::writeAndWait(session, [&] { return session.exportDepthMap(depth_path); }));
    const Result<LoadedImage> depth = readImage(depth_path.toStdString());
    QVERIFY2(depth.ok(), depth.status.message.c_str());
    QCOMPARE(depth->image.channels, 1);
    QCOMPARE(depth->info.pixel_type, std::string("float"));
    QVERIFY(std::abs(depth->image.pixel(40, 120)[0] - 3.0f) < 1e-5f);
    QCOMPARE(depth->image.pixel(280, 120)[0], 0.0f);  // no depth on the right: 0

    // Crop to the valid area: a barrel lens pulls the frame's edges in, so the valid picture is
    // smaller than the photo, and opaque (no alpha written).
    const QString lens = dir_.filePath("barrel.artcam");
    QVERIFY(writeArtcam(lens.toStdString(), buildEffect("barrel", {}, {320, 240})).ok);
    QVERIFY(ui::test::importAndWait(session, lens));
    ExportOptions options;
    options.crop_to_valid = true;
    session.setExportOptions(options);
    QSignalSpy finished(&session, &Session::exportFinished);
    const QString out = dir_.filePath("cropped.png");
    session.exportImage(out);
    QTRY_COMPARE_WITH_TIMEOUT(finished.size(), 1, 60000);
    QVERIFY2(finished.front().at(0).toBool(), qPrintable(finished.front().at(1).toString()));
    const Result<LoadedImage> back = readImage(out.toStdString());
    QVERIFY(back.ok());
    QVERIFY2(back->image.width < 320 && back->image.height < 240 && back->image.width > 200,
             qPrintable(QString("%1x%2").arg(back->image.width).arg(back->image.height)));
    QCOMPARE(back->image.channels, 3);
  }

  void exportCanBeCancelled() {
    Document doc;
    Session session(&doc, nullptr);
    session.setInteractive(false);
    // Large enough that the export is still running when Cancel arrives.
    doc.reset(ui::test::syntheticPhoto(3000, 3000), ui::test::ninePairs(3000, 3000), ModelClass::Quadratic);
    QSignalSpy finished(&session, &Session::exportFinished);
    const QString out = dir_.filePath("cancelled.png");
    session.exportImage(out);
    session.cancelExport();
    QTRY_COMPARE_WITH_TIMEOUT(finished.size(), 1, 60000);
    QVERIFY(!finished.front().at(0).toBool());
    QVERIFY(finished.front().at(1).toString().contains("cancelled"));
    QVERIFY(!QFile::exists(out));  // nothing partial left behind
  }

  void pairsTableEditsBothWays() {
    Document doc;
    doc.reset(ui::test::syntheticPhoto(), ui::test::ninePairs());
    PairsPanel panel(&doc);
    QAbstractItemModel* model = panel.table()->model();
    QCOMPARE(model->rowCount(), 9);
    QVERIFY(model->setData(model->index(2, PairsTableModel::TargetX), 123.5, Qt::EditRole));
    QCOMPARE(doc.pairs()[2].target.x(), 123.5);
    QCOMPARE(doc.undoStack()->count(), 1);
    QVERIFY(model->setData(model->index(2, PairsTableModel::Enabled), Qt::Unchecked,
                           Qt::CheckStateRole));
    QVERIFY(!doc.pairs()[2].enabled);
    doc.undoStack()->undo();
    doc.undoStack()->undo();
    QVERIFY(doc.pairs() == ui::test::ninePairs());
    QCOMPARE(model->data(model->index(2, PairsTableModel::TargetX), Qt::EditRole).toDouble(),
             ui::test::ninePairs()[2].target.x());
    // Selection travels both ways.
    doc.setSelection({1, 4});
    QCOMPARE(panel.table()->selectionModel()->selectedRows().size(), 2);
    panel.table()->selectRow(6);
    QCOMPARE(doc.selection(), std::vector<int>{6});
  }

  void bannerCountsMissingPairs() {
    Document doc;
    doc.reset(ui::test::syntheticPhoto());
    PairsPanel panel(&doc);
    doc.undoStack()->push(new SetModelCommand(&doc, ModelClass::Quadratic));
    std::vector<Pair> pairs = ui::test::ninePairs();
    for (int i = 0; i < 5; ++i)
      doc.undoStack()->push(new AddPairCommand(&doc, pairs[static_cast<size_t>(i)]));
    QVERIFY2(panel.bannerText().contains("4 more"), qPrintable(panel.bannerText()));
  }
};

QTEST_MAIN(TestSession)
#include "test_session.moc"
