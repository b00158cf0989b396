// The .artcam extras of attributed cameras (artcam_file.h): layers and depth_output round-trip
// bit-exactly, older readers still read the main camera, bad fields are named by JSON path.
#include "core/effects/chromatic.h"
#include "core/effects/depth_of_field.h"
#include "core/io/artcam_file.h"

#include <QtTest/QtTest>
#include <QTemporaryDir>

using namespace artcam;

class TestArtcamExtras : public QObject {
  Q_OBJECT

 private slots:
  void layersRoundTrip() {
    const FrameSize size{600, 400};
    const std::vector<Camera> layers = colourShiftLayers({{0.05, 0.1 / 3.0, -0.03}}, size, size);
    const ArtcamDocument doc{layers[0], {}, std::nullopt};
    ArtcamExtras extras;
    extras.layers = {layers[1], layers[2]};
    QTemporaryDir dir;
    const std::string path = dir.filePath("cs.artcam").toStdString();
    QVERIFY(writeArtcamFile(path, doc, extras).ok);
    const auto read = readArtcamEffectFile(path);
    QVERIFY2(read.ok(), qPrintable(QString::fromStdString(read.status.message)));
    const std::vector<Camera> all = read->allLayers();
    QCOMPARE(all.size(), size_t{3});
    for (size_t l = 0; l < 3; ++l)
      for (size_t i = 0; i < all[l].stages()[0].q.size(); ++i)
        QVERIFY(all[l].stages()[0].q[i] == layers[l].stages()[0].q[i]);  // bit-exact
    QCOMPARE(read->extras.depth_output, std::string("depth"));
    // A reader that knows nothing of layers still gets the first one.
    const auto plain = readArtcamFile(path);
    QVERIFY(plain.ok());
    QVERIFY(plain->camera.stages()[0].q[0] == layers[0].stages()[0].q[0]);
  }

  void depthOutputRoundTripsAndIsChecked() {
    const FrameSize size{64, 48};
    const ArtcamDocument doc{depthOfFieldCamera({2.0, 0.01}, size, size), {}, std::nullopt};
    ArtcamExtras extras;
    extras.depth_output = "blur-variance";
    const std::string text = toArtcamJson(doc, extras);
    const auto read = parseArtcamEffectJson(text, "dof.artcam");
    QVERIFY(read.ok());
    QCOMPARE(read->extras.depth_output, std::string("blur-variance"));
    std::string bad = text;
    bad.replace(bad.find("blur-variance"), 13, "blur-sigma");
    const auto refused = parseArtcamEffectJson(bad, "dof.artcam");
    QVERIFY(!refused.ok());
    QVERIFY(refused.status.message.find("dof.artcam: /depth_output") != std::string::npos);
  }

  void malformedLayerIsNamed() {
    const FrameSize size{64, 48};
    const std::vector<Camera> layers = colourShiftLayers({}, size, size);
    ArtcamExtras extras;
    extras.layers = {layers[1]};
    std::string text = toArtcamJson({layers[0], {}, std::nullopt}, extras);
    const size_t at = text.find("\"layers\"");
    QVERIFY(at != std::string::npos);
    text.replace(text.find("\"stages\"", at), 8, "\"stagez\"");
    const auto refused = parseArtcamEffectJson(text, "x.artcam");
    QVERIFY(!refused.ok());
    QVERIFY2(refused.status.message.find("/layers/0/stages: missing") != std::string::npos,
             refused.status.message.c_str());
  }
};

QTEST_GUILESS_MAIN(TestArtcamExtras)
#include "test_artcam_extras.moc"
