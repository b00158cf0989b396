// SPDX-License-Identifier: Apache-2.0
// `artcam sample stereo-house` then `artcam stereo` as a user runs them; the depth map against
// the sample's ray traced depth, read back with OpenImageIO, and used by `artcam warp --depth`.
#include "tests/app/cli_run.h"

#include <OpenImageIO/imagebuf.h>

#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QTemporaryDir>
#include <QtTest/QtTest>

#include <algorithm>
#include <cmath>
#include <vector>

using artcam::test::artcamCli;
using Run = artcam::test::CliRun;

namespace {

std::vector<float> channelZero(const QString& path, int* width, int* height) {
  OIIO::ImageBuf buf(path.toStdString());
  const OIIO::ImageSpec& spec = buf.spec();
  *width = spec.width;
  *height = spec.height;
  std::vector<float> all(static_cast<size_t>(spec.width) * spec.height * spec.nchannels);
  buf.get_pixels(buf.roi(), OIIO::TypeDesc::FLOAT, all.data());
  std::vector<float> out(static_cast<size_t>(spec.width) * spec.height);
  for (size_t i = 0; i < out.size(); ++i) out[i] = all[i * spec.nchannels];
  return out;
}

}  // namespace

class TestCliStereo : public QObject {
  Q_OBJECT

 private slots:
  void depthOfTheSamplePair() {
    QTemporaryDir dir;
    Run r = artcamCli({"sample", "stereo-house", "-o", dir.path(), "--size", "480x360"});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    const QRegularExpressionMatch bf = QRegularExpression("baseline-focal ([0-9.]+)").match(r.out);
    QVERIFY2(bf.hasMatch(), qPrintable(r.out));
    r = artcamCli({"stereo", dir.filePath("house-left.png"), dir.filePath("house-right.png"),
                   "--baseline-focal", bf.captured(1), "-o", dir.filePath("depth.exr"), "--json"});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    QVERIFY2(r.out.contains("\"matched_share\""), qPrintable(r.out));
    int w = 0, h = 0, tw = 0, th = 0;
    const std::vector<float> estimate = channelZero(dir.filePath("depth.exr"), &w, &h);
    const std::vector<float> truth = channelZero(dir.filePath("house-depth.exr"), &tw, &th);
    QCOMPARE(w, 480);
    QCOMPARE(tw, w);
    std::vector<double> rel;
    for (int y = 0; y < h; ++y)
      for (int x = 120; x < w; ++x) {
        const float t = truth[static_cast<size_t>(y) * w + x],
                    e = estimate[static_cast<size_t>(y) * w + x];
        if (t > 0 && e > 0) rel.push_back(std::abs(e - t) / t);
      }
    QVERIFY(rel.size() > static_cast<size_t>(w * h / 3));
    std::nth_element(rel.begin(), rel.begin() + rel.size() / 2, rel.end());
    QVERIFY2(rel[rel.size() / 2] < 0.02, qPrintable(QString::number(rel[rel.size() / 2])));
    // The map feeds the depth block as a painted or loaded one does.
    r = artcamCli(
        {"preset", "aerial-perspective", "--size", "480x360", "-o", dir.filePath("haze.artcam")});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    r = artcamCli({"warp", dir.filePath("house-left.png"), dir.filePath("haze.artcam"), "--depth",
                   dir.filePath("depth.exr"), "-o", dir.filePath("hazy.png")});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
  }

  void unfoldsTheWalls() {
    // Fig 2 end to end: the pair, its depth, the walls the sample marks, the unfolding camera
    // and its render; the picture is as wide as the photo and about as tall as the walls are
    // (4 + 3 wide, 3.2 tall at the gable: 640 × 640·3.2/7 ≈ 293).
    QTemporaryDir dir;
    Run r = artcamCli({"sample", "stereo-house", "-o", dir.path()});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    r = artcamCli({"stereo", dir.filePath("house-left.png"), dir.filePath("house-right.png"),
                   "--baseline-focal", "140", "-o", dir.filePath("depth.exr")});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    r = artcamCli({"unfold", dir.filePath("house-left.png"), "--depth", dir.filePath("depth.exr"),
                   "--walls", dir.filePath("house-walls.csv"), "--focal", "560", "-o",
                   dir.filePath("unfold.artcam"), "--json"});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    QVERIFY2(r.out.contains("\"front\"") && r.out.contains("\"side\""), qPrintable(r.out));
    // The roof over the front wall is stretched into the band above it; the gable end is the
    // tallest and has none.
    const QJsonObject report = QJsonDocument::fromJson(r.out.toUtf8()).object();
    const QJsonArray walls = report.value("walls").toArray();
    QCOMPARE(walls.size(), 2);
    QVERIFY2(walls[0].toObject().value("roof_height").toDouble() > 0.5, qPrintable(r.out));
    QCOMPARE(walls[1].toObject().value("roof_height").toDouble(), 0.0);
    r = artcamCli({"warp", dir.filePath("house-left.png"), dir.filePath("unfold.artcam"), "-o",
                   dir.filePath("unfolded.png")});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    QVERIFY2(r.out.contains("piecewise") && r.out.contains("3 patches"), qPrintable(r.out));
    // --no-roof leaves the band empty: the walls alone.
    r = artcamCli({"unfold", dir.filePath("house-left.png"), "--depth", dir.filePath("depth.exr"),
                   "--walls", dir.filePath("house-walls.csv"), "--focal", "560", "--no-roof", "-o",
                   dir.filePath("bare.artcam")});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    QVERIFY2(!r.out.contains("roof"), qPrintable(r.out));
    r = artcamCli({"info", dir.filePath("bare.artcam")});
    QVERIFY2(r.out.contains(QRegularExpression("patches:\\s+2,")), qPrintable(r.out));
    int w = 0, h = 0;
    channelZero(dir.filePath("unfolded.png"), &w, &h);
    QCOMPARE(w, 640);
    QVERIFY2(std::abs(h - 293) <= 8, qPrintable(QString::number(h)));
    // Refusals: a required option, a broken outline file (named with its line).
    r = artcamCli({"unfold", dir.filePath("house-left.png"), "--depth", dir.filePath("depth.exr"),
                   "--walls", dir.filePath("house-walls.csv"), "-o", dir.filePath("u2.artcam")});
    QCOMPARE(r.exit_code, 2);
    QVERIFY2(r.err.contains("--focal"), qPrintable(r.err));
    QFile bad(dir.filePath("bad.csv"));
    QVERIFY(bad.open(QIODevice::WriteOnly));
    bad.write("wall,x,y\nfront,10,20\nfront,30,twenty\n");
    bad.close();
    r = artcamCli({"unfold", dir.filePath("house-left.png"), "--depth", dir.filePath("depth.exr"),
                   "--walls", dir.filePath("bad.csv"), "--focal", "560", "-o",
                   dir.filePath("u3.artcam")});
    QCOMPARE(r.exit_code, 1);
    QVERIFY2(r.err.contains("bad.csv:3"), qPrintable(r.err));
    QVERIFY(!QFile::exists(dir.filePath("u3.artcam")));
  }

  void refusals() {
    QTemporaryDir dir;
    Run r = artcamCli({"sample", "stereo-house", "-o", dir.path(), "--size", "160x120"});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    const QString left = dir.filePath("house-left.png"), right = dir.filePath("house-right.png");
    r = artcamCli({"stereo", left, right, "-o", dir.filePath("d.exr")});
    QCOMPARE(r.exit_code, 2);
    QVERIFY2(r.err.contains("--baseline-focal"), qPrintable(r.err));
    r = artcamCli({"stereo", left, right, "--baseline-focal", "0", "-o", dir.filePath("d.exr")});
    QCOMPARE(r.exit_code, 2);
    r = artcamCli({"stereo", left, right, "--baseline-focal", "50", "-o", dir.filePath("d.png")});
    QCOMPARE(r.exit_code, 2);
    QVERIFY2(r.err.contains("float"), qPrintable(r.err));
    r = artcamCli({"stereo", left, dir.filePath("missing.png"), "--baseline-focal", "50", "-o",
                   dir.filePath("d.exr")});
    QCOMPARE(r.exit_code, 1);
    QVERIFY2(r.err.contains("missing.png"), qPrintable(r.err));
    QVERIFY(!QFile::exists(dir.filePath("d.exr")));
    r = artcamCli({"stereo", left, dir.filePath("house-depth.exr"), "--baseline-focal", "50", "-o",
                   dir.filePath("d.exr"), "--block", "4"});
    QCOMPARE(r.exit_code, 2);
  }
};

QTEST_GUILESS_MAIN(TestCliStereo)
#include "test_cli_stereo.moc"
