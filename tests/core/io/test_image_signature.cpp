// SPDX-License-Identifier: Apache-2.0
// The image readers choose their decoder from the file's first bytes (image_input.cpp,
// createReader): a file that is no image format's is refused at once, in the same words for
// every name it may have, instead of being handed to every reader OpenImageIO has (some crawl
// through megabytes: 100 MB of zeros named .png took 9 s); a real image under a wrong
// extension, and a format without a signature under its own extension, still read.
#include "core/io/image_io.h"
#include "core/io/stored_image.h"

#include <QtTest/QtTest>

#include <chrono>

using namespace artcam;

namespace {

std::string zeros(const QTemporaryDir& dir, const QString& name, qint64 bytes) {
  const QString path = dir.filePath(name);
  QFile f(path);
  if (!f.open(QIODevice::WriteOnly) || !f.resize(bytes)) return {};
  return path.toStdString();
}

ImageF gradient() {
  ImageF image(32, 16, 3);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      for (int c = 0; c < 3; ++c) image.pixel(x, y)[c] = static_cast<float>(x + y + c) / 50.0f;
  return image;
}

}  // namespace

class TestImageSignature : public QObject {
  Q_OBJECT

 private slots:
  void bytesOfNoFormatAreRefusedAtOnce_data() {
    QTest::addColumn<QString>("name");
    QTest::newRow("named .png") << "zeros.png";
    QTest::newRow("named .exr") << "zeros.exr";
    QTest::newRow("unknown extension") << "zeros.dat";
    QTest::newRow("no extension (as a spooled stdin)") << "zeros";
  }
  void bytesOfNoFormatAreRefusedAtOnce() {
    QFETCH(QString, name);
    QTemporaryDir dir;
    const std::string path = zeros(dir, name, qint64{32} << 20);
    QVERIFY(!path.empty());
    const auto start = std::chrono::steady_clock::now();
    const Result<LoadedImage> read = readImage(path);
    const Result<StoredShape> shape = readStoredShape(path);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    QVERIFY(!read);
    QVERIFY(!shape);
    const std::string want = path + ": cannot read: not an image this build reads";
    QVERIFY2(read.status.message.rfind(want, 0) == 0, read.status.message.c_str());
    QVERIFY2(shape.status.message.rfind(want, 0) == 0, shape.status.message.c_str());
    QVERIFY2(seconds < 0.5, qPrintable(QString("took %1 s").arg(seconds)));
  }

  void anImageUnderAWrongExtensionStillReads() {
    QTemporaryDir dir;
    const std::string png = dir.filePath("g.png").toStdString();
    QVERIFY(writeImage(png, gradient()).ok);
    const std::string misnamed = dir.filePath("g.jpg").toStdString();
    QVERIFY(QFile::copy(QString::fromStdString(png), QString::fromStdString(misnamed)));
    const Result<LoadedImage> read = readImage(misnamed);
    QVERIFY2(read, read.status.message.c_str());
    QCOMPARE(read->info.format_name, std::string("png"));
    QCOMPARE(read->image.width, 32);
  }

  void aFormatWithoutSignatureReadsUnderItsExtension() {
    // Targa has no signature: its extension alone chooses its reader.
    QTemporaryDir dir;
    const std::string tga = dir.filePath("g.tga").toStdString();
    QVERIFY(writeImage(tga, gradient()).ok);
    const Result<LoadedImage> read = readImage(tga);
    QVERIFY2(read, read.status.message.c_str());
    QCOMPARE(read->info.format_name, std::string("targa"));
    QCOMPARE(read->image.height, 16);
  }
};

QTEST_GUILESS_MAIN(TestImageSignature)
#include "test_image_signature.moc"
