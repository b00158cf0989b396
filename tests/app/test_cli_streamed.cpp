// SPDX-License-Identifier: Apache-2.0
// `artcam warp` and `batch` on a photo whose decode and output would pass the memory budget
// (ARTCAM_MAX_MEMORY_MB): streamed in bands instead of refused, writing the very bytes the
// whole-image warp writes, metadata included; a camera that reads the photo out of order is
// refused naming the memory it would need, with no output left behind.
#include "tests/app/cli_files.h"
#include "tests/app/cli_run.h"
#include "core/io/stored_image.h"

#include <QTemporaryDir>
#include <QtTest/QtTest>

using namespace artcam;
using namespace artcam::test;

namespace {

// 900 × 600 RGB: 1.6 MB decoded, 2.2 MB as RGBA output; a 2 MiB budget holds neither together.
constexpr int kW = 900, kH = 600;
const QStringList kSmallBudget = {QStringLiteral("ARTCAM_MAX_MEMORY_MB=2")};

}  // namespace

class TestCliStreamed : public QObject {
  Q_OBJECT

  QTemporaryDir dir_;
  QString path(const QString& name) const { return dir_.filePath(name); }

 private slots:
  void initTestCase() {
    QVERIFY(dir_.isValid());
    QVERIFY(writeNoisePhoto(path("photo.png"), kW, kH));
    const CliRun jpeg = artcamCli({"warp", path("photo.png"), resourcePath("sample.artcam").c_str(),
                                   "-o", path("photo.jpg"), "--quiet"});
    QVERIFY2(jpeg.exit_code == 0, qPrintable(jpeg.err));
  }

  void sameBytesAsTheWholeImageWarp_data() {
    QTest::addColumn<QString>("input");
    QTest::addColumn<QString>("output");
    QTest::addColumn<bool>("whole_file");  // false: TIFF stamps the time of writing (DateTime)
    QTest::newRow("png -> png") << "photo.png" << "out.png" << true;
    QTest::newRow("jpg -> jpg") << "photo.jpg" << "out.jpg" << true;
    QTest::newRow("png -> tif") << "photo.png" << "out.tif" << false;
  }

  void sameBytesAsTheWholeImageWarp() {
    QFETCH(QString, input);
    QFETCH(QString, output);
    QFETCH(bool, whole_file);
    const QString camera = QString::fromStdString(resourcePath("sample.artcam"));
    const QString whole = path("whole-" + output), streamed = path("streamed-" + output);
    // The photo's XMP history stamps the time of saving; SOURCE_DATE_EPOCH pins it, so the two
    // runs may fall in different seconds and still write one file.
    const QStringList same_time = {QStringLiteral("SOURCE_DATE_EPOCH=1764000000")};
    const CliBytesRun a =
        artcamCliPiped({"warp", path(input), camera, "-o", whole, "--quiet"}, {}, same_time);
    QVERIFY2(a.exit_code == 0, qPrintable(a.err));
    QVERIFY2(!a.out.contains("streamed gather warp"), a.out.constData());
    const CliBytesRun b = artcamCliPiped({"warp", path(input), camera, "-o", streamed, "--quiet"},
                                         {}, kSmallBudget + same_time);
    QVERIFY2(b.exit_code == 0, qPrintable(b.err));
    QVERIFY2(b.out.contains("streamed gather warp") && b.out.contains("photo rows held"),
             b.out.constData());
    const auto pixels = [](const QString& file) {
      auto image = readStoredImage(file.toStdString());
      return image ? QByteArray(reinterpret_cast<const char*>(image->bytes.data()),
                                static_cast<qsizetype>(image->bytes.size()))
                   : QByteArray();
    };
    if (input == "photo.jpg")  // artcam's own JPEG: its history gets this save, at that time
      QVERIFY(fileBytes(whole).contains("stEvt:when=\"2025-11-24T16:00:00Z\""));
    const QByteArray x = whole_file ? fileBytes(whole) : pixels(whole);
    const QByteArray y = whole_file ? fileBytes(streamed) : pixels(streamed);
    QVERIFY(!x.isEmpty());
    qsizetype first = 0;
    while (first < std::min(x.size(), y.size()) && x[first] == y[first]) ++first;
    QVERIFY2(x == y, qPrintable(QString("%1 vs %2 bytes, first difference at byte %3")
                                    .arg(x.size()).arg(y.size()).arg(first)));
  }

  void batchStreamsToo() {
    const QString camera = QString::fromStdString(resourcePath("sample.artcam"));
    QDir().mkpath(path("batch-out"));
    const CliBytesRun run = artcamCliPiped(
        {"batch", camera, path("photo.png"), "-o", path("batch-out"), "--quiet"}, {}, kSmallBudget);
    QVERIFY2(run.exit_code == 0, qPrintable(run.err));
    const CliRun whole = artcamCli({"warp", path("photo.png"), camera, "-o", path("batch-whole.png"), "--quiet"});
    QVERIFY(whole.exit_code == 0);
    QCOMPARE(fileBytes(path("batch-out/photo.png")), fileBytes(path("batch-whole.png")));
  }

  // Upside down: the first output rows need the photo's last rows, and every row stays needed.
  void outOfOrderCameraIsRefusedNamingTheMemory() {
    QFile csv(path("flip.csv"));
    QVERIFY(csv.open(QIODevice::WriteOnly));
    csv.write("src_x,src_y,dst_x,dst_y\n0,0,0,600\n900,0,900,600\n0,600,0,0\n900,600,900,0\n"
              "450,150,450,450\n150,450,150,150\n");
    csv.close();
    const CliRun fit = artcamCli({"fit", path("flip.csv"), "--model", "homography", "--size",
                                  "900x600", "-o", path("flip.artcam")});
    QVERIFY2(fit.exit_code == 0, qPrintable(fit.err));
    const CliBytesRun run = artcamCliPiped(
        {"warp", path("photo.png"), path("flip.artcam"), "-o", path("flip.png"), "--quiet"}, {},
        {QStringLiteral("ARTCAM_MAX_MEMORY_MB=1")});
    QCOMPARE(run.exit_code, 1);
    QVERIFY2(run.err.contains("photo.png: cannot warp in bands") && run.err.contains("600 rows") &&
                 run.err.contains("memory budget of 1.0 MiB") && run.err.count('\n') <= 3,
             qPrintable(run.err));
    QVERIFY(!QFile::exists(path("flip.png")));
    QVERIFY(hiddenFiles(dir_.path()).isEmpty());
  }
};

QTEST_GUILESS_MAIN(TestCliStreamed)
#include "test_cli_streamed.moc"
