// SPDX-License-Identifier: Apache-2.0
// `artcam warp` on hostile photos (the readers' side is tests/core/io/test_hostile_images.cpp):
// truncated, empty, a giant header, not an image, a directory. Each run must exit with status 1,
// print one error line naming the photo (libpng's own line aside), and leave no output (nor a
// temporary file) behind.
#include "tests/app/cli_run.h"
#include "tests/core/io/hostile_bytes.h"

#include <QDir>
#include <QFile>
#include <QTemporaryDir>
#include <QtTest/QtTest>

using namespace artcam::test;

class TestHostileWarp : public QObject {
  Q_OBJECT

  QTemporaryDir dir_;
  QString path(const QString& name) const { return dir_.filePath(name); }

  void write(const QString& name, const QByteArray& bytes) {
    QFile f(path(name));
    QVERIFY(f.open(QIODevice::WriteOnly));
    f.write(bytes);
  }

 private slots:
  void hostilePhotosFailCleanly_data() {
    QTest::addColumn<QString>("photo");
    QTest::newRow("truncated png") << "cut.png";
    QTest::newRow("empty file") << "empty.png";
    QTest::newRow("giant header") << "giant.png";
    QTest::newRow("not an image") << "notes.jpg";
    QTest::newRow("directory") << "folder.png";
    QTest::newRow("missing") << "missing.png";
  }

  void hostilePhotosFailCleanly() {
    QFETCH(QString, photo);
    QFile coffee(QStringLiteral(ARTCAM_SOURCE_DIR "/resources/coffee.png"));
    QVERIFY(coffee.open(QIODevice::ReadOnly));
    const QByteArray png = coffee.readAll();
    write("cut.png", png.left(png.size() / 3));
    write("empty.png", {});
    write("giant.png", QByteArray::fromStdString(pngHeaderOnly(100000, 100000)));
    write("notes.jpg", "not a photo\n");
    QDir(dir_.path()).mkpath("folder.png");

    const QString out_dir = path("out-" + photo);
    QVERIFY(QDir().mkpath(out_dir));
    const QString out = out_dir + "/warped.png";
    const CliRun run =
        artcamCli({"warp", path(photo),
                   QStringLiteral(ARTCAM_SOURCE_DIR "/resources/sample.artcam"), "-o", out});
    QCOMPARE(run.exit_code, 1);
    // One line of ours names the photo. libpng prints its own "libpng error: …" line to stderr
    // before OIIO reports the failure; that library noise is the only other line allowed.
    const QStringList lines = run.err.trimmed().split('\n');
    QCOMPARE(lines.filter(path(photo)).size(), 1);
    for (const QString& line : lines)
      QVERIFY2(line.contains(path(photo)) || line.startsWith("libpng "), qPrintable(run.err));
    QVERIFY2(QDir(out_dir).isEmpty(), qPrintable(QDir(out_dir).entryList().join(", ")));
  }
};

QTEST_GUILESS_MAIN(TestHostileWarp)
#include "test_hostile_warp.moc"
