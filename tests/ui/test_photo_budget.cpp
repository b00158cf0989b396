// SPDX-License-Identifier: Apache-2.0
// The studio opens a photo only if it can hold it: the photo as float, its depth raster and
// its full-size render, against the memory budget (ARTCAM_MAX_MEMORY_MB here), checked from the
// header before a pixel is decoded. A photo the command line reads (the float photo alone fits)
// may still be too large for the studio: refused in one line naming the file, not grown into.
#include "core/io/image_io.h"
#include "core/model/image.h"
#include "ui/image_loader.h"

#include <QSignalSpy>
#include <QTemporaryDir>
#include <QtTest/QtTest>

using namespace artcam;
using namespace artcam::ui;

namespace {

QString writeGrey(const QTemporaryDir& dir, const QString& name, int side) {
  ImageF image(side, side, 3);
  for (float& v : image.data) v = 0.5f;
  const QString path = dir.filePath(name);
  return writeImage(path.toStdString(), image).ok ? path : QString();
}

struct Load {
  bool loaded = false;
  QString failure;
};

Load loadInStudio(const QString& path, bool first_look) {
  ImageLoader loader(path);
  loader.setFirstLook(first_look);
  QSignalSpy loaded(&loader, &ImageLoader::loaded);
  QSignalSpy failed(&loader, &ImageLoader::failed);
  QSignalSpy finished(&loader, &ImageLoader::finished);
  loader.start();
  if (!finished.wait(60000)) return {};
  Load load;
  load.loaded = !loaded.isEmpty();
  if (!failed.isEmpty()) load.failure = failed.first().first().toString();
  return load;
}

}  // namespace

class TestPhotoBudget : public QObject {
  Q_OBJECT

  QTemporaryDir dir_;

 private slots:
  void initTestCase() {
    QVERIFY(dir_.isValid());
    // 20 MiB: a 1000² RGB photo is 16 MB as float (the readers' own check passes it) but 40 MB
    // as the studio holds it; a 400² one is 6.4 MB there.
    qputenv("ARTCAM_MAX_MEMORY_MB", "20");
  }
  void cleanupTestCase() { qunsetenv("ARTCAM_MAX_MEMORY_MB"); }

  void theReadersAloneWouldTakeIt() {
    const QString path = writeGrey(dir_, "big.png", 1000);
    QVERIFY(!path.isEmpty());
    const Result<LoadedImage> read = readImage(path.toStdString());
    QVERIFY2(read.ok(), read.status.message.c_str());
  }

  void aPhotoTooLargeForTheStudioIsRefusedBeforeDecoding_data() {
    QTest::addColumn<QString>("name");
    QTest::addColumn<bool>("first_look");
    QTest::newRow("png") << "big.png" << false;
    QTest::newRow("jpeg, first look") << "big.jpg" << true;
  }
  void aPhotoTooLargeForTheStudioIsRefusedBeforeDecoding() {
    QFETCH(QString, name);
    QFETCH(bool, first_look);
    const QString path = writeGrey(dir_, name, 1000);
    QVERIFY(!path.isEmpty());
    const Load load = loadInStudio(path, first_look);
    QVERIFY(!load.loaded);
    QVERIFY2(load.failure.startsWith(path + ": cannot open: 1000x1000 pixels need "),
             qPrintable(load.failure));
    QVERIFY2(load.failure.contains("more than the memory budget of 20.0 MiB"),
             qPrintable(load.failure));
    QCOMPARE(load.failure.count('\n'), 0);
  }

  void aPhotoThatFitsOpens() {
    const QString path = writeGrey(dir_, "small.png", 400);
    QVERIFY(!path.isEmpty());
    const Load load = loadInStudio(path, false);
    QVERIFY2(load.loaded, qPrintable(load.failure));
  }
};

QTEST_MAIN(TestPhotoBudget)
#include "test_photo_budget.moc"
