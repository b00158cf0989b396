// SPDX-License-Identifier: Apache-2.0
// Depth files (depth_file.h): 16-bit counts with a scale, float EXR as stored, disparity with a
// baseline·focal factor or inverse depth, holes as 0, the summary, errors naming the file.
// Fixtures written here with OIIO.
#include "core/io/depth_file.h"

#include <OpenImageIO/imagebuf.h>

#include <QTemporaryDir>
#include <QtTest/QtTest>

#include <cmath>
#include <filesystem>
#include <cstdint>
#include <vector>

using namespace artcam;

namespace {

template <class T>
bool writeGrey(const std::string& path, int w, int h, const std::vector<T>& values,
               OIIO::TypeDesc type) {
  OIIO::ImageSpec spec(w, h, 1, type);
  OIIO::ImageBuf buf(spec);
  buf.set_pixels(OIIO::ROI::All(), type, values.data());
  return buf.write(path);
}

}  // namespace

class TestDepthFile : public QObject {
  Q_OBJECT

 private slots:
  void sixteenBitCountsTimesScale() {
    QTemporaryDir dir;
    const std::string path = dir.filePath("d.png").toStdString();
    const std::vector<std::uint16_t> counts = {0, 1, 1000, 65535, 2500, 40000};
    QVERIFY(writeGrey(path, 3, 2, counts, OIIO::TypeDesc::UINT16));
    DepthFileOptions o;
    o.scale = 0.001;  // millimetres → metres
    DepthFileSummary summary;
    const auto depth = readDepthFile(path, o, &summary);
    QVERIFY2(depth.ok(), qPrintable(QString::fromStdString(depth.status.message)));
    for (size_t i = 0; i < counts.size(); ++i)
      QVERIFY2(std::abs(depth->data[i] - counts[i] * 0.001) <= 1e-6 * (1 + counts[i] * 0.001),
               qPrintable(QString("pixel %1: %2, expected %3")
                              .arg(i)
                              .arg(depth->data[i])
                              .arg(counts[i] * 0.001)));
    QCOMPARE(summary.holes, 1LL);  // the 0 count
    QCOMPARE(depth->data[0], 0.0f);
  }

  void disparityBecomesDepth() {
    QTemporaryDir dir;
    const std::string path = dir.filePath("disp.exr").toStdString();
    const std::vector<float> disparity = {10.0f, 20.0f, 0.0f, 2.5f};
    QVERIFY(writeGrey(path, 2, 2, disparity, OIIO::TypeDesc::FLOAT));
    DepthFileOptions o;
    o.baseline_focal = 50.0;
    const auto depth = readDepthFile(path, o);
    QVERIFY(depth.ok());
    QCOMPARE(depth->data[0], 5.0f);
    QCOMPARE(depth->data[1], 2.5f);
    QCOMPARE(depth->data[2], 0.0f);  // zero disparity: a hole, not inf
    QCOMPARE(depth->data[3], 20.0f);
  }

  void floatIsAsStoredAndErrorsNameTheFile() {
    QTemporaryDir dir;
    const std::string path = dir.filePath("z.exr").toStdString();
    const std::vector<float> z = {1.25f, 7.5f, -1.0f, std::nanf("")};
    QVERIFY(writeGrey(path, 4, 1, z, OIIO::TypeDesc::FLOAT));
    const auto depth = readDepthFile(path);
    QVERIFY(depth.ok());
    QCOMPARE(depth->data[0], 1.25f);
    QCOMPARE(depth->data[1], 7.5f);
    QCOMPARE(depth->data[2], 0.0f);
    QCOMPARE(depth->data[3], 0.0f);
    const auto missing = readDepthFile(dir.filePath("nope.exr").toStdString());
    QVERIFY(!missing.ok());
    QVERIFY(missing.status.message.find("nope.exr") != std::string::npos);
    DepthFileOptions bad;
    bad.scale = 0.0;
    QVERIFY(!readDepthFile(path, bad).ok());
  }

  // A float TIFF cut in half: the decoder reports damaged strips yet returns success, which
  // left the lower half of the map as holes. The reader refuses it, naming the file, the first
  // decoder error and how many more there were.
  void truncatedMapIsRefused() {
    QTemporaryDir dir;
    const std::string path = dir.filePath("z.tif").toStdString();
    const int w = 400, h = 300;
    std::vector<float> z(static_cast<size_t>(w) * h);
    for (size_t i = 0; i < z.size(); ++i) z[i] = 1.0f + static_cast<float>(i % 977) * 0.01f;
    QVERIFY(writeGrey(path, w, h, z, OIIO::TypeDesc::FLOAT));
    QVERIFY(readDepthFile(path).ok());
    const auto size = std::filesystem::file_size(path);
    std::filesystem::resize_file(path, size / 2);
    const auto cut = readDepthFile(path);
    QVERIFY(!cut.ok());
    QVERIFY2(cut.status.message.rfind(path + ": cannot read", 0) == 0, cut.status.message.c_str());
    QVERIFY2(cut.status.message.find('\n') == std::string::npos, cut.status.message.c_str());
    QVERIFY2(cut.status.message.size() < 400, cut.status.message.c_str());
  }

  // The one reader's remaining rules (depth_file.h): a float file ignores the count scale;
  // inverse depth is disparity with baseline·focal 1 after the count scale; the summary names
  // the stored type and the depth range; a file that is not an image is refused by name.
  void scaleInverseAndSummary() {
    QTemporaryDir dir;
    const std::string exr = dir.filePath("z.exr").toStdString();
    QVERIFY(writeGrey(exr, 2, 1, std::vector<float>{1.25f, 4.0f}, OIIO::TypeDesc::FLOAT));
    DepthFileOptions mm;
    mm.scale = 0.001;
    DepthFileSummary summary;
    const auto as_stored = readDepthFile(exr, mm, &summary);
    QVERIFY(as_stored.ok());
    QCOMPARE(as_stored->data[1], 4.0f);
    QCOMPARE(summary.pixel_type, std::string("float"));
    QCOMPARE(summary.min_depth, 1.25);
    QCOMPARE(summary.max_depth, 4.0);

    const std::string png = dir.filePath("inv.png").toStdString();
    QVERIFY(writeGrey(png, 2, 1, std::vector<std::uint16_t>{500, 2000}, OIIO::TypeDesc::UINT16));
    DepthFileOptions inverse;
    inverse.scale = 0.001;  // counts of 1/1000 per metre
    inverse.inverse = true;
    const auto z = readDepthFile(png, inverse, &summary);
    QVERIFY(z.ok());
    QVERIFY(std::abs(z->data[0] - 1.0 / 0.5) < 1e-6);
    QVERIFY(std::abs(z->data[1] - 1.0 / 2.0) < 1e-6);
    QCOMPARE(summary.pixel_type, std::string("uint16"));

    const QString text = dir.filePath("notes.png");
    QFile f(text);
    QVERIFY(f.open(QIODevice::WriteOnly));
    f.write("not a picture");
    f.close();
    const auto refused = readDepthFile(text.toStdString());
    QVERIFY(!refused.ok());
    QVERIFY2(refused.status.message.find(text.toStdString() + ": cannot read") == 0,
             refused.status.message.c_str());
  }
};

QTEST_GUILESS_MAIN(TestDepthFile)
#include "test_depth_file.moc"
