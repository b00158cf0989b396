// SPDX-License-Identifier: Apache-2.0
// The .artcam fields of attributed cameras (artcam_file.h): layers and depth_output round-trip
// bit-exactly, the first layer stays the top-level camera, bad fields are named by JSON path.
#include "core/effects/chromatic.h"
#include "core/effects/depth_of_field.h"
#include "core/io/artcam_file.h"

#include <QtTest/QtTest>
#include <fstream>
#include <iterator>
#include <QTemporaryDir>

using namespace artcam;

class TestArtcamExtras : public QObject {
  Q_OBJECT

 private slots:
  void layersRoundTrip() {
    const FrameSize size{600, 400};
    const std::vector<Camera> layers = colourShiftLayers({{0.05, 0.1 / 3.0, -0.03}}, size, size);
    Artcam doc;
    doc.layers = layers;
    QTemporaryDir dir;
    const std::string path = dir.filePath("cs.artcam").toStdString();
    QVERIFY(writeArtcam(path, doc).ok);
    const auto read = readArtcam(path);
    QVERIFY2(read.ok(), qPrintable(QString::fromStdString(read.status.message)));
    const std::vector<Camera>& all = read->layers;
    QCOMPARE(all.size(), size_t{3});
    for (size_t l = 0; l < 3; ++l)
      for (size_t i = 0; i < all[l].stages()[0].q.size(); ++i)
        QVERIFY(all[l].stages()[0].q[i] == layers[l].stages()[0].q[i]);  // bit-exact
    QCOMPARE(read->depth_output, DepthOutput::Depth);
    QCOMPARE(read->kind(), ArtcamKind::Layered);
    // The first layer is the top-level camera: what a reader ignoring "layers" gets.
    std::ifstream in(path);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    QVERIFY(text.find("\"layers\"") > text.find("\"stages\""));
    QVERIFY(read->main().stages()[0].q[0] == layers[0].stages()[0].q[0]);
  }

  void depthOutputRoundTripsAndIsChecked() {
    const FrameSize size{64, 48};
    Artcam doc(depthOfFieldCamera({2.0, 0.01}, size, size));
    doc.depth_output = DepthOutput::BlurVariance;
    const std::string text = toArtcamJson(doc);
    const auto read = parseArtcam(text, "dof.artcam");
    QVERIFY(read.ok());
    QCOMPARE(read->depth_output, DepthOutput::BlurVariance);
    std::string bad = text;
    bad.replace(bad.find("blur-variance"), 13, "blur-sigma");
    const auto refused = parseArtcam(bad, "dof.artcam");
    QVERIFY(!refused.ok());
    QVERIFY(refused.status.message.find("dof.artcam: /depth_output") != std::string::npos);
  }

  void malformedLayerIsNamed() {
    const FrameSize size{64, 48};
    const std::vector<Camera> layers = colourShiftLayers({}, size, size);
    Artcam doc;
    doc.layers = {layers[0], layers[1]};
    std::string text = toArtcamJson(doc);
    const size_t at = text.find("\"layers\"");
    QVERIFY(at != std::string::npos);
    text.replace(text.find("\"stages\"", at), 8, "\"stagez\"");
    const auto refused = parseArtcam(text, "x.artcam");
    QVERIFY(!refused.ok());
    QVERIFY2(refused.status.message.find("/layers/0/stages: missing") != std::string::npos,
             refused.status.message.c_str());
  }
};

QTEST_GUILESS_MAIN(TestArtcamExtras)
#include "test_artcam_extras.moc"
