// SPDX-License-Identifier: Apache-2.0
// A project's files: a project whose photo moved opens once the photo is located (pairs, depth
// and effects kept, the export the same pixels as before the move), a located photo of another
// size is refused naming both sizes, saves and exports run as one-shot jobs, and the depth map
// export names its channel Z.
#include "core/io/depth_file.h"
#include "core/io/image_io.h"
#include "tests/ui/session_wait.h"
#include "tests/ui/ui_fixtures.h"
#include "ui/background_job.h"
#include "ui/commands.h"
#include "ui/depth_commands.h"
#include "ui/depth_model.h"
#include "ui/document.h"
#include "ui/session.h"

#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QSignalSpy>
#include <QStandardPaths>
#include <QTemporaryDir>
#include <QtTest/QtTest>

#include <OpenImageIO/imageio.h>

using namespace artcam;
using namespace artcam::ui;

namespace {

struct Saved {
  QString project, photo, exported;
  std::vector<Pair> pairs;
  std::vector<DepthPlaneLayer> layers;
  std::vector<EffectStep> effects;
};

bool exportAndWait(Session& session, const QString& out) {
  QSignalSpy finished(&session, &Session::exportFinished);
  session.exportImage(out);
  if (!finished.wait(60000)) return false;
  return finished.front().at(0).toBool();
}

// The pixels of two image files, equal exactly.
bool samePixels(const QString& a, const QString& b) {
  const Result<LoadedImage> x = readImage(a.toStdString()), y = readImage(b.toStdString());
  return x.ok() && y.ok() && x->image.width == y->image.width &&
         x->image.height == y->image.height && x->image.channels == y->image.channels &&
         x->image.data == y->image.data;
}

}  // namespace

class TestProjectFiles : public QObject {
  Q_OBJECT

  QTemporaryDir dir_;

  // A project in `folder` with pairs, a depth plane and an effect that reads it, its photo
  // beside it, and its export.
  Saved makeProject(const QString& folder) {
    Saved s;
    QDir().mkpath(dir_.filePath(folder));
    s.photo = dir_.filePath(folder + "/photo.png");
    s.project = dir_.filePath(folder + "/p.artcamproj");
    s.exported = dir_.filePath(folder + "/before.png");
    const PhotoPtr synthetic = test::syntheticPhoto();
    if (!writeImage(s.photo.toStdString(), synthetic->full.image).ok) return {};
    Document doc;
    Session session(&doc, nullptr);
    session.setInteractive(false);
    session.openPhoto(s.photo);
    if (!QTest::qWaitFor([&doc] { return doc.photo() != nullptr; }, 20000)) return {};
    for (const Pair& p : test::ninePairs()) doc.undoStack()->push(new AddPairCommand(&doc, p));
    DepthPlaneLayer layer = doc.depth()->makeLayer();
    layer.mask.fillPolygon({{0, 0}, {200, 0}, {200, 240}, {0, 240}});
    layer.anchors = {{{10.5, 10.5}, 2.0}, {{190.5, 10.5}, 3.0}, {{10.5, 230.5}, 5.0}};
    doc.undoStack()->push(new AddDepthLayerCommand(doc.depth(), layer));
    doc.setEffects({EffectStep{"aerial-perspective", {}}});
    if (!test::saveAndWait(session, s.project)) return {};
    if (!exportAndWait(session, s.exported)) return {};
    s.pairs = doc.pairs();
    s.layers = doc.depth()->layers();
    s.effects = doc.effects();
    return s;
  }

 private slots:
  void initTestCase() {
    QStandardPaths::setTestModeEnabled(true);
    QVERIFY(dir_.isValid());
  }

  // The photo moved: the prompt names the project and the missing photo, the located photo
  // brings back everything, the export is the same pixels, and a save keeps the new place.
  void movedPhotoIsLocated() {
    const Saved saved = makeProject("located");
    QVERIFY(!saved.project.isEmpty());
    const QString moved = dir_.filePath("elsewhere/photo.png");
    QVERIFY(QDir().mkpath(QFileInfo(moved).absolutePath()));
    QVERIFY(QFile::rename(saved.photo, moved));

    Document doc;
    Session session(&doc, nullptr);
    session.setInteractive(false);
    QStringList asked;
    session.setLocatePrompt([&asked, moved](const QString& project, const QString& photo) {
      asked << project << photo;
      return moved;
    });
    QSignalSpy opened(&session, &Session::projectOpened);
    session.openProject(saved.project);
    QVERIFY(opened.wait(20000));
    QVERIFY2(opened.front().at(0).toBool(), qPrintable(opened.front().at(1).toString()));
    QCOMPARE(asked, (QStringList{QFileInfo(saved.project).absoluteFilePath(),
                                 QFileInfo(saved.photo).absoluteFilePath()}));
    // The status names the project, not only its photo.
    QVERIFY2(opened.front().at(1).toString().contains("p.artcamproj"),
             qPrintable(opened.front().at(1).toString()));
    QCOMPARE(QFileInfo(doc.photo()->path).absoluteFilePath(), QFileInfo(moved).absoluteFilePath());
    QVERIFY(doc.pairs() == saved.pairs);
    QVERIFY(doc.depth()->layers() == saved.layers);
    QVERIFY(doc.effects() == saved.effects);
    QVERIFY(doc.isModified());  // the new place is not saved yet
    const QString after = dir_.filePath("located/after.png");
    QVERIFY(exportAndWait(session, after));
    QVERIFY(samePixels(saved.exported, after));
    QVERIFY(test::saveOwnAndWait(session));
    const Result<Project> back = readProject(saved.project);
    QVERIFY2(back.ok(), back.status.message.c_str());
    QCOMPARE(back->photo_path, QFileInfo(moved).absoluteFilePath());
  }

  void locatedPhotoOfAnotherSizeIsRefused() {
    const Saved saved = makeProject("wrong-size");
    QVERIFY(!saved.project.isEmpty());
    QVERIFY(QFile::remove(saved.photo));
    const QString other = dir_.filePath("wrong-size/small.png");
    QVERIFY(writeImage(other.toStdString(), test::syntheticPhoto(64, 48)->full.image).ok);
    Document doc;
    Session session(&doc, nullptr);
    session.setInteractive(false);
    session.setLocatePrompt([other](const QString&, const QString&) { return other; });
    QSignalSpy opened(&session, &Session::projectOpened);
    session.openProject(saved.project);
    QVERIFY(opened.wait(20000));
    QVERIFY(!opened.front().at(0).toBool());
    const QString message = opened.front().at(1).toString();
    QVERIFY2(message.contains("p.artcamproj") && message.contains("small.png") &&
                 message.contains("64x48") && message.contains("320x240"),
             qPrintable(message));
    QVERIFY(!doc.photo());
  }

  void missingPhotoWithoutLocateNamesTheProject() {
    const Saved saved = makeProject("gave-up");
    QVERIFY(!saved.project.isEmpty());
    QVERIFY(QFile::remove(saved.photo));
    Document doc;
    Session session(&doc, nullptr);
    session.setInteractive(false);
    session.setLocatePrompt([](const QString&, const QString&) { return QString(); });
    QSignalSpy opened(&session, &Session::projectOpened);
    session.openProject(saved.project);
    QVERIFY(opened.wait(20000));
    QVERIFY(!opened.front().at(0).toBool());
    const QString message = opened.front().at(1).toString();
    QVERIFY2(message.startsWith("p.artcamproj: ") && message.contains(saved.photo),
             qPrintable(message));
  }

  // Saves and file exports are handed to one-shot jobs: when the call returns, the write is a
  // job still to be delivered, and the file is there when its signal comes.
  void savesAndExportsRunAsJobs() {
    Document doc;
    Session session(&doc, nullptr);
    session.setInteractive(false);
    doc.reset(test::syntheticPhoto(), test::ninePairs(), ModelClass::Quadratic);
    DepthPlaneLayer layer = doc.depth()->makeLayer();
    layer.mask.fillPolygon({{0, 0}, {160, 0}, {160, 240}, {0, 240}});
    layer.anchors = {{{10.5, 10.5}, 3.0}, {{150.5, 10.5}, 3.0}, {{10.5, 230.5}, 3.0}};
    doc.undoStack()->push(new AddDepthLayerCommand(doc.depth(), layer));
    QTRY_COMPARE_WITH_TIMEOUT(BackgroundJob::runningCount(), 0, 20000);

    QSignalSpy saved(&session, &Session::projectSaved);
    const QString project = dir_.filePath("jobs.artcamproj");
    QVERIFY(session.saveProjectTo(project));
    QVERIFY(BackgroundJob::runningCount() > 0);
    QVERIFY(saved.wait(20000));
    QVERIFY(saved.front().at(0).toBool());
    QVERIFY(QFile::exists(project));
    QVERIFY(!doc.isModified());

    QSignalSpy written(&session, &Session::fileWritten);
    const QString depth = dir_.filePath("jobs-depth.exr");
    QVERIFY(session.exportDepthMap(depth));
    QVERIFY(BackgroundJob::runningCount() > 0);
    QVERIFY(written.wait(20000));
    QVERIFY(written.front().at(0).toBool());
    const QString cam = dir_.filePath("jobs.artcam");
    QVERIFY(session.exportArtcam(cam));
    QVERIFY(BackgroundJob::runningCount() > 0);
    QVERIFY(written.wait(20000));
    QVERIFY(written.at(1).at(0).toBool());
    QVERIFY(QFile::exists(cam));

    // The depth map names its one channel Z, as compositors do, and reads back as depth.
    auto in = OIIO::ImageInput::open(depth.toStdString());
    QVERIFY(in);
    QCOMPARE(in->spec().nchannels, 1);
    QCOMPARE(in->spec().channelnames.at(0), std::string("Z"));
    in->close();
    const Result<ImageF> back = readDepthFile(depth.toStdString());
    QVERIFY2(back.ok(), back.status.message.c_str());
    QVERIFY(std::abs(back->pixel(40, 120)[0] - 3.0f) < 1e-5f);
    QCOMPARE(back->pixel(280, 120)[0], 0.0f);
  }
};

QTEST_MAIN(TestProjectFiles)
#include "test_project_files.moc"
