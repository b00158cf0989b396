// SPDX-License-Identifier: Apache-2.0
// Channels beyond colour and alpha (an EXR's Z, a fifth TIFF channel) that an output format cannot
// hold (PNG) are not warped: artcam warp says so, naming the file and the channels, and lists
// them in --json; files of four channels or fewer give no such warning. (Into OpenEXR they are
// warped: tests/app/test_cli_exr_channels.cpp.)
#include "tests/app/cli_run.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QTemporaryDir>
#include <QtTest/QtTest>

using artcam::test::artcamCli;
using Run = artcam::test::CliRun;

namespace {

bool writeChannels(const QString& path, const std::vector<std::string>& names) {
  OIIO::ImageSpec spec(64, 48, static_cast<int>(names.size()), OIIO::TypeDesc::HALF);
  spec.channelnames = names;
  spec.alpha_channel = names.size() > 3 ? 3 : -1;
  OIIO::ImageBuf buf(spec);
  std::vector<float> value(names.size(), 0.5f);
  OIIO::ImageBufAlgo::fill(buf, value);
  return buf.write(path.toStdString());
}

}  // namespace

class TestCliChannels : public QObject {
  Q_OBJECT

 private slots:
  void extraChannelsAreNamedNotDroppedSilently() {
    QTemporaryDir dir;
    const QString cam = dir.filePath("lens.artcam");
    QCOMPARE(artcamCli({"preset", "barrel", "--k", "-0.05", "--size", "64x48", "-o", cam}).exit_code, 0);
    const QString five = dir.filePath("five.exr");
    QVERIFY(writeChannels(five, {"R", "G", "B", "A", "Z"}));
    const Run r = artcamCli({"warp", five, cam, "-o", dir.filePath("out.png"), "--json", "-q"});
    QVERIFY2(r.exit_code == 0, qPrintable(r.err));
    QVERIFY2(r.err.contains("five.exr: channels beyond colour and alpha (Z) are not warped"),
             qPrintable(r.err));
    const QJsonObject j = QJsonDocument::fromJson(r.out.toUtf8()).object();
    QCOMPARE(j["dropped_channels"].toArray(), QJsonArray({"Z"}));

    const QString four = dir.filePath("four.exr");
    QVERIFY(writeChannels(four, {"R", "G", "B", "A"}));
    const Run plain = artcamCli({"warp", four, cam, "-o", dir.filePath("out4.exr"), "--json", "-q"});
    QVERIFY2(plain.exit_code == 0, qPrintable(plain.err));
    QVERIFY2(!plain.err.contains("not warped"), qPrintable(plain.err));
    QVERIFY(!QJsonDocument::fromJson(plain.out.toUtf8()).object().contains("dropped_channels"));
  }
};

QTEST_GUILESS_MAIN(TestCliChannels)
#include "test_cli_channels.moc"
