// Depth files (depth_file.h): 16-bit counts with a scale, float EXR as stored, disparity with a
// baseline·focal factor, holes as 0, errors naming the file. Fixtures written here with OIIO.
#include "core/io/depth_file.h"

#include <OpenImageIO/imagebuf.h>

#include <QtTest/QtTest>
#include <QTemporaryDir>

#include <cmath>
#include <cstdint>
#include <vector>

using namespace artcam;

namespace {

template <class T>
bool writeGrey(const std::string& path, int w, int h, const std::vector<T>& values, OIIO::TypeDesc type) {
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
               qPrintable(QString("pixel %1: %2, expected %3").arg(i).arg(depth->data[i]).arg(counts[i] * 0.001)));
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
};

QTEST_GUILESS_MAIN(TestDepthFile)
#include "test_depth_file.moc"
