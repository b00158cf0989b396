// SPDX-License-Identifier: Apache-2.0
// Depth from a stereo pair in the studio (File > Depth from Stereo Pair…): the ray-traced house
// pair (artcam sample stereo-house) opened as its left view, matched against the right one,
// becomes the document's depth map, shown and saved as any depth map; its depth is the traced
// truth's to a few percent (median), the very values `artcam stereo` writes, and undo takes it
// away again. A right view of another size is refused in one line.
#include "core/io/depth_file.h"
#include "core/io/image_io.h"
#include "tests/app/cli_run.h"
#include "ui/depth_model.h"
#include "ui/document.h"
#include "ui/main_window.h"
#include "ui/session.h"

#include <QSignalSpy>
#include <QTemporaryDir>
#include <QtTest/QtTest>

#include <algorithm>
#include <cmath>
#include <vector>

using namespace artcam;
using namespace artcam::ui;

class TestStereoDepth : public QObject {
  Q_OBJECT

  QTemporaryDir dir_;
  QString path(const QString& name) const { return dir_.filePath(name); }

 private slots:
  void initTestCase() {
    QVERIFY(dir_.isValid());
    const auto made = artcam::test::artcamCli({"sample", "stereo-house", "-o", path("house")});
    QVERIFY2(made.exit_code == 0, qPrintable(made.err));
    QVERIFY2(made.out.contains("140"), qPrintable(made.out));  // the pair's baseline·focal
  }

  void pairBecomesTheDepthMap() {
    MainWindow window;
    Session* session = window.session();
    session->setInteractive(false);
    session->openPhoto(path("house/house-left.png"));
    Document* doc = window.document();
    QVERIFY(QTest::qWaitFor([doc] { return doc->photo() && doc->photo()->hasFullImage(); }, 30000));
    QVERIFY(!doc->depth()->hasDepth());
    QSignalSpy loaded(session, &Session::depthMapLoaded);
    session->depthFromStereo(path("house/house-right.png"), 140.0, path("studio-depth.exr"));
    QVERIFY(loaded.wait(60000));
    QVERIFY2(loaded.first().at(0).toBool(), qPrintable(loaded.first().at(1).toString()));
    QVERIFY(doc->depth()->hasDepth());
    QVERIFY(doc->depth()->map());
    QCOMPARE(doc->depth()->map()->path, QFileInfo(path("studio-depth.exr")).absoluteFilePath());

    // Against the ray-traced truth, where both have a depth (the sky and the unmatched band have
    // none): the median relative error.
    const Result<ImageF> truth = readDepthFile(path("house/house-depth.exr").toStdString());
    const Result<ImageF> got = readDepthFile(path("studio-depth.exr").toStdString());
    QVERIFY(truth.ok() && got.ok());
    QCOMPARE(got->width, truth->width);
    std::vector<double> errors;
    for (int y = 0; y < truth->height; ++y)
      for (int x = 0; x < truth->width; ++x) {
        const double t = truth->pixel(x, y)[0], g = got->pixel(x, y)[0];
        if (t > 0 && g > 0) errors.push_back(std::abs(g - t) / t);
      }
    QVERIFY(errors.size() > size_t(truth->width) * truth->height / 4);
    std::nth_element(errors.begin(), errors.begin() + errors.size() / 2, errors.end());
    const double median = errors[errors.size() / 2];
    qInfo("studio stereo depth vs the traced truth: median relative error %.2f %% over %zu px",
          100 * median, errors.size());
    QVERIFY2(median < 0.03, qPrintable(QString::number(median)));

    // The same values as the command line's.
    const auto cli = artcam::test::artcamCli({"stereo", path("house/house-left.png"),
                                              path("house/house-right.png"), "-o",
                                              path("cli-depth.exr"), "--baseline-focal", "140"});
    QVERIFY2(cli.exit_code == 0, qPrintable(cli.err));
    const Result<ImageF> cli_depth = readDepthFile(path("cli-depth.exr").toStdString());
    QVERIFY(cli_depth.ok() && cli_depth->data == got->data);

    // Undoable, like loading a depth map.
    doc->undoStack()->undo();
    QVERIFY(!doc->depth()->map());

    // A right view of another size: refused, naming both files, nothing loaded.
    QVERIFY(writeImage(path("small.png").toStdString(), ImageF(64, 48, 3)).ok);
    loaded.clear();
    session->depthFromStereo(path("small.png"), 140.0, path("bad-depth.exr"));
    QVERIFY(loaded.wait(30000));
    QVERIFY(!loaded.first().at(0).toBool());
    const QString message = loaded.first().at(1).toString();
    QVERIFY2(message.contains("house-left.png") && message.contains("small.png"),
             qPrintable(message));
    QVERIFY(!QFile::exists(path("bad-depth.exr")));
    QVERIFY(!doc->depth()->map());

    // Never over an input of the pair.
    const QByteArray right_bytes = [&] {
      QFile f(path("house/house-right.png"));
      return f.open(QIODevice::ReadOnly) ? f.readAll() : QByteArray();
    }();
    loaded.clear();
    session->depthFromStereo(path("house/house-right.png"), 140.0, path("house/house-right.png"));
    QVERIFY(loaded.count() == 1 || loaded.wait(30000));
    QVERIFY(!loaded.first().at(0).toBool());
    QVERIFY2(loaded.first().at(1).toString().contains("refusing"),
             qPrintable(loaded.first().at(1).toString()));
    QFile f(path("house/house-right.png"));
    QVERIFY(f.open(QIODevice::ReadOnly) && f.readAll() == right_bytes);
  }
};

QTEST_MAIN(TestStereoDepth)
#include "test_stereo_depth.moc"
