// SPDX-License-Identifier: Apache-2.0
// CSV match and point lists: exact numbers, tolerated noise (comments, CRLF, BOM, spaces) and
// refusals that name the file, the line and the cause.
#include "core/io/matches_csv.h"
#include "tests/support/test_support.h"

#include <QtTest/QtTest>

#include <bit>
#include <cmath>
#include <cstdint>
#include <fstream>

using namespace artcam;

class TestMatchesCsv : public QObject {
  Q_OBJECT

  QTemporaryDir dir_;

  std::string write(const std::string& name, const std::string& text) {
    const std::string path = dir_.filePath(QString::fromStdString(name)).toStdString();
    std::ofstream(path, std::ios::binary) << text;
    return path;
  }
  // The refusal message for `text` read as matches.csv, or "ACCEPTED".
  QString refusal(const std::string& text, int dimension = 2) {
    const std::string path = write("matches.csv", text);
    const auto result = readMatchesCsv(path, dimension);
    if (result.ok()) return "ACCEPTED";
    QString message = QString::fromStdString(result.status.message);
    return message.replace(QString::fromStdString(path), "matches.csv");
  }

 private slots:
  void readsMatchesExactly() {
    const std::string path = write("m.csv",
                                   "\xEF\xBB\xBF# pairs clicked on IMG_0001\r\n"
                                   "src_x, src_y, dst_x, dst_y\r\n"
                                   "\r\n"
                                   "0.1,2,+3.5,-4e-3\r\n"
                                   "   # indented comment\n"
                                   "10.25 ,\t20.5, 1e2 ,0.30000000000000004\n");
    const auto result = readMatchesCsv(path);
    QVERIFY2(result.ok(), result.status.message.c_str());
    QCOMPARE(result->size(), size_t(2));
    QVERIFY((*result)[0].source == Eigen::Vector2d(0.1, 2));
    QVERIFY((*result)[0].target == Eigen::Vector2d(3.5, -4e-3));
    QVERIFY((*result)[1].target == Eigen::Vector2d(100, 0.30000000000000004));
    QVERIFY((*result)[1].enabled);
  }

  void readsThreeDimensionsAndEnabledColumn() {
    const std::string path =
        write("m3.csv",
              "src_x,src_y,src_z,dst_x,dst_y,dst_z,enabled\n1,2,3,4,5,6,1\n7,8,9,10,11,12,false\n");
    const auto result = readMatchesCsv(path, 3);
    QVERIFY2(result.ok(), result.status.message.c_str());
    QCOMPARE(result->size(), size_t(2));
    QVERIFY((*result)[1].source == Eigen::Vector3d(7, 8, 9));
    QVERIFY((*result)[1].target == Eigen::Vector3d(10, 11, 12));
    QVERIFY((*result)[0].enabled);
    QVERIFY(!(*result)[1].enabled);
  }

  void refusalsNameLineAndCause() {
    const std::string header = "src_x,src_y,dst_x,dst_y\n";
    QCOMPARE(refusal(header + "1,2,3,4\n# c\n\n1,2,3,4\n1,2,3,4\n1,2,3\n"),
             QString("matches.csv:7: expected 4 numbers, found 3"));
    QCOMPARE(refusal(header + "1,2,3,4,\n"), QString("matches.csv:2: expected 4 numbers, found 5"));
    QCOMPARE(
        refusal("1,2,3,4\n"),
        QString("matches.csv:1: expected the header src_x,src_y,dst_x,dst_y, found \"1,2,3,4\""));
    QCOMPARE(refusal(""),
             QString("matches.csv: empty, expected the header src_x,src_y,dst_x,dst_y"));
    QCOMPARE(refusal(header + "1,nan,3,4\n"),
             QString("matches.csv:2: column 2 (src_y): not a finite number: \"nan\""));
    QCOMPARE(refusal(header + "1,2,inf,4\n"),
             QString("matches.csv:2: column 3 (dst_x): not a finite number: \"inf\""));
    QCOMPARE(refusal(header + "1,2,3,1e999\n"),
             QString("matches.csv:2: column 4 (dst_y): out of range for a double: \"1e999\""));
    // A finite but absurd value is refused at its row (a fit would overflow far from it).
    QCOMPARE(refusal(header + "1,2,3,4\n100,100,1e300,99\n"),
             QString("matches.csv:3: column 3 (dst_x): \"1e300\" is beyond any coordinate or "
                     "colour (|value| > 1e9)"));
    QCOMPARE(refusal(header + "1,2.5px,3,4\n"),
             QString("matches.csv:2: column 2 (src_y): not a number: \"2.5px\""));
    QCOMPARE(refusal(header + "1,,3,4\n"), QString("matches.csv:2: column 2 (src_y): empty"));
    QCOMPARE(refusal(header + "1;2;3;4\n"), QString("matches.csv:2: expected 4 numbers, found 1"));
    QCOMPARE(
        refusal("src_x,src_y,dst_x,dst_y,enabled\n1,2,3,4,maybe\n"),
        QString(
            "matches.csv:2: column 5 (enabled): expected 0, 1, true or false, found \"maybe\""));
    QVERIFY(
        refusal(header + "1,2,3,4\n", 3)
            .startsWith(
                "matches.csv:1: expected the header src_x,src_y,src_z,dst_x,dst_y,dst_z, found"));
    const auto missing = readMatchesCsv(dir_.filePath("absent.csv").toStdString());
    QVERIFY(!missing.ok() &&
            missing.status.message.find("absent.csv: cannot read") != std::string::npos);
  }

  void writeReadRoundTripIsExact() {
    std::vector<PointMatch> matches;
    for (int m = 0; m < 50; ++m) {
      const double a = std::bit_cast<double>(static_cast<std::uint64_t>(test::rng()()) >> 2);
      matches.push_back({Eigen::Vector2d(test::uniform(-1e4, 1e4), a),
                         Eigen::Vector2d(1.0 / (m + 3), -0.0), m % 7 != 2});
    }
    const std::string path = dir_.filePath("round.csv").toStdString();
    const Status written = writeMatchesCsv(path, matches);
    QVERIFY2(written.ok, written.message.c_str());
    const auto read = readMatchesCsv(path);
    QVERIFY2(read.ok(), read.status.message.c_str());
    QCOMPARE(read->size(), matches.size());
    for (size_t m = 0; m < matches.size(); ++m) {
      QVERIFY((*read)[m].source == matches[m].source);
      QVERIFY((*read)[m].target == matches[m].target);
      QCOMPARE((*read)[m].enabled, matches[m].enabled);
    }
    matches[4].target[0] = std::numeric_limits<double>::quiet_NaN();
    QVERIFY(!writeMatchesCsv(path, matches).ok);
  }

  void readsPointLists() {
    const auto with_header = readPointsCsv(write("p.csv", "x,y\n1.5,2\n# c\n3,4\r\n"));
    QVERIFY2(with_header.ok(), with_header.status.message.c_str());
    QCOMPARE(with_header->size(), size_t(2));
    QVERIFY((*with_header)[1] == Eigen::Vector2d(3, 4));
    const auto bare = readPointsCsv(write("q.csv", "1,2\n"));
    QVERIFY(bare.ok() && bare->size() == 1);
    const std::string bad = write("r.csv", "x,y\n1,2\n3\n");
    const auto refused = readPointsCsv(bad);
    QVERIFY(!refused.ok());
    QCOMPARE(QString::fromStdString(refused.status.message),
             QString::fromStdString(bad + ":3: expected 2 numbers, found 1"));
    const auto late_header = readPointsCsv(write("s.csv", "1,2\nx,y\n"));
    QVERIFY(!late_header.ok() &&
            late_header.status.message.find(":2: column 1 (x): not a number") != std::string::npos);
  }

  void readsColourSamplesLinearAndSrgbEncoded() {
    const std::string text =
        "src_r,src_g,src_b,dst_r,dst_g,dst_b\n"
        "0.5,0.25,0,1,0.04045,0.2\n"
        "1.5,-0.1,0.3,0.1,0.2,0.3\n";
    const std::string path = write("colours.csv", text);
    const auto linear = readColourSamplesCsv(path);
    QVERIFY2(linear.ok(), linear.status.message.c_str());
    QCOMPARE(linear->size(), size_t(2));
    QVERIFY((*linear)[0].source == Eigen::Vector3d(0.5, 0.25, 0));
    QVERIFY((*linear)[1].source == Eigen::Vector3d(1.5, -0.1, 0.3));  // linear: kept as written
    QVERIFY((*linear)[0].target == Eigen::Vector3d(1, 0.04045, 0.2));
    // sRGB-encoded: IEC 61966-2-1 decoding, evaluated here from the standard's formula.
    const auto decoded = readColourSamplesCsv(path, ColourEncoding::Srgb);
    QVERIFY2(decoded.ok(), decoded.status.message.c_str());
    const auto srgb = [](double v) {
      const double a = std::abs(v);
      const double d = a <= 0.04045 ? a / 12.92 : std::pow((a + 0.055) / 1.055, 2.4);
      return v < 0 ? -d : d;
    };
    for (size_t k = 0; k < 2; ++k)
      for (int i = 0; i < 3; ++i) {
        QVERIFY(std::abs((*decoded)[k].source[i] - srgb((*linear)[k].source[i])) < 1e-15);
        QVERIFY(std::abs((*decoded)[k].target[i] - srgb((*linear)[k].target[i])) < 1e-15);
      }
    QCOMPARE((*decoded)[0].target[0], 1.0);
    QVERIFY(std::abs((*decoded)[0].target[1] - 0.04045 / 12.92) < 1e-18);
  }

  void colourSampleRefusalsNameLineAndCause() {
    const std::string path = write("c.csv", "src_x,src_y,dst_x,dst_y\n1,2,3,4\n");
    QCOMPARE(QString::fromStdString(readColourSamplesCsv(path).status.message)
                 .replace(QString::fromStdString(path), "c.csv"),
             QString("c.csv:1: expected the header src_r,src_g,src_b,dst_r,dst_g,dst_b, found "
                     "\"src_x,src_y,dst_x,dst_y\""));
    const std::string bad = write("c2.csv", "src_r,src_g,src_b,dst_r,dst_g,dst_b\n0.1,0.2,0.3,0.4,x,0.6\n");
    QCOMPARE(QString::fromStdString(readColourSamplesCsv(bad).status.message)
                 .replace(QString::fromStdString(bad), "c2.csv"),
             QString("c2.csv:2: column 5 (dst_g): not a number: \"x\""));
  }
};

QTEST_GUILESS_MAIN(TestMatchesCsv)
#include "test_matches_csv.moc"
