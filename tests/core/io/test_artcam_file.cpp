// SPDX-License-Identifier: Apache-2.0
// .artcam files: bit-exact round trips (random and edge doubles), and every refusal names the
// file and the JSON path or line of the problem.
#include "core/colour/composite.h"
#include "core/io/artcam_file.h"
#include "tests/support/test_support.h"

#include <QtTest/QtTest>

#include <nlohmann/json.hpp>

#include <bit>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <limits>

using namespace artcam;
using Json = nlohmann::json;

namespace {

bool sameBits(double a, double b) {
  return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

// Doubles across the whole range: random bit patterns plus the edges a naive writer loses.
std::vector<double> awkwardDoubles(size_t random_count) {
  std::vector<double> values{0.0,
                             -0.0,
                             1.0,
                             -1.0,
                             0.1,
                             1.0 / 3.0,
                             1e300,
                             -1e300,
                             1e-300,
                             std::numeric_limits<double>::max(),
                             std::numeric_limits<double>::lowest(),
                             std::numeric_limits<double>::min(),
                             std::numeric_limits<double>::denorm_min(),
                             -std::numeric_limits<double>::denorm_min(),
                             3.5 * std::numeric_limits<double>::denorm_min(),
                             std::nextafter(1.0, 2.0),
                             9007199254740993.0,
                             123456789012345678.0};
  while (values.size() < random_count) {
    const double v = std::bit_cast<double>(static_cast<std::uint64_t>(test::rng()()));
    if (std::isfinite(v)) values.push_back(v);
  }
  return values;
}

Artcam richDocument() {
  // Position + colour, two stages, every entry an awkward double (tensors kept as written).
  const std::vector<Block> blocks{{BlockKind::Position, 3}, {BlockKind::Colour, 4}};
  const std::vector<double> values = awkwardDoubles(2 * 7 * 7 * 7);
  size_t next = 0;
  std::vector<Stage> stages(2);
  for (Stage& stage : stages)
    for (int i = 0; i < 7; ++i) {
      Eigen::MatrixXd q(7, 7);
      for (int r = 0; r < 7; ++r)
        for (int c = 0; c < 7; ++c) q(r, c) = values[next++];
      stage.q.push_back(q);
    }
  Artcam document(Camera(blocks, stages, {4000, 3000}, {1920, 1080}));
  for (int m = 0; m < 12; ++m) {
    PointMatch match{Eigen::Vector2d(test::uniform(0, 4000), test::uniform(0, 3000)),
                     Eigen::Vector2d(test::uniform(0, 1920), test::uniform(0, 1080)), m % 5 != 3};
    document.matches.push_back(match);
  }
  FitRecord fit;
  fit.model = "quadratic";
  fit.matches = 10;
  fit.rms_px = 0.123456789012345678;
  fit.max_px = 0.5;
  fit.residuals_px = awkwardDoubles(400);
  fit.singular_values = {1e-17, 2.5e-9, 0.75};
  fit.reason = "held-out error 0.2 px lower than homography; \"quoted\" \\ and ü";
  fit.criterion = "aic";
  fit.models = {{"homography", 3.25, 4.5, 120.75, ""},
                {"quadratic", 0.1234567890123, -1.0, 34.5, "bends between the pairs"}};
  document.fit = fit;
  return document;
}

const char* kValid = R"({
  "format": "artcam",
  "version": 1,
  "blocks": [{"kind": "position", "size": 3}],
  "frames": {"source": [640, 480], "target": [640, 480]},
  "stages": [{"tensors": [[[0, 0, 0.5], [0, 0, 0], [0.5, 0, 0]],
                          [[0, 0, 0], [0, 0, 0.5], [0, 0.5, 0]],
                          [[0, 0, 0], [0, 0, 0], [0, 0, 1]]]}],
  "matches": [{"source": [1, 2], "target": [3, 4]}, {"source": [5, 6], "target": [7, 8], "enabled": false}],
  "fit": {"model": "homography", "matches": 2, "rms_px": 0.25, "max_px": 0.5}
})";

}  // namespace

class TestArtcamFile : public QObject {
  Q_OBJECT

  // The message of a refused document, checked to be one line naming cam.artcam.
  static QString refusal(const std::string& text) {
    const Result<Artcam> result = parseArtcam(text, "cam.artcam");
    if (result.ok()) return "ACCEPTED";
    const QString message = QString::fromStdString(result.status.message);
    if (!message.startsWith("cam.artcam: ") || message.contains('\n'))
      return "BADLY FORMED: " + message;
    return message;
  }
  static std::string mutated(const std::function<void(Json&)>& change) {
    Json j = Json::parse(kValid);
    change(j);
    return j.dump(1);
  }

#define EXPECT_REFUSAL(text, fragment)                                            \
  do {                                                                            \
    const QString m = refusal(text);                                              \
    if (!m.contains(QString::fromUtf8(fragment))) QFAIL(qPrintable("got: " + m)); \
  } while (0)

 private slots:
  void validDocumentParses() {
    const Result<Artcam> result = parseArtcam(kValid, "cam.artcam");
    QVERIFY2(result.ok(), result.status.message.c_str());
    QCOMPARE(result->main().sourceSize(), (FrameSize{640, 480}));
    QCOMPARE(result->matches.size(), size_t(2));
    QVERIFY(result->matches[0].enabled);
    QVERIFY(!result->matches[1].enabled);
    QCOMPARE(result->matches[1].target[1], 8.0);
    QVERIFY(result->fit.has_value());
    QCOMPARE(result->fit->model, std::string("homography"));
    QVERIFY(result->fit->residuals_px.empty());
    const auto mapped = targetFromSourceNormalized(result->main(), Eigen::Vector2d(0.25, -0.5));
    QVERIFY(mapped && (*mapped - Eigen::Vector2d(0.25, -0.5)).norm() == 0.0);
  }

  void readsTheBundledSample() {
    const Result<Artcam> sample = readArtcam(test::resourcePath("sample.artcam"));
    QVERIFY2(sample.ok(), sample.status.message.c_str());
    QVERIFY(sample->main().sourceSize().isImage());
  }

  void roundTripIsBitExact() {
    QTemporaryDir dir;
    const std::string path = dir.filePath("cam.artcam").toStdString();
    const Artcam original = richDocument();
    const Status written = writeArtcam(path, original);
    QVERIFY2(written.ok, written.message.c_str());
    const Result<Artcam> read = readArtcam(path);
    QVERIFY2(read.ok(), read.status.message.c_str());

    QCOMPARE(read->main().blocks(), original.main().blocks());
    QCOMPARE(read->main().sourceSize(), original.main().sourceSize());
    QCOMPARE(read->main().targetSize(), original.main().targetSize());
    QCOMPARE(read->main().stages().size(), original.main().stages().size());
    for (size_t s = 0; s < original.main().stages().size(); ++s)
      for (size_t i = 0; i < 7; ++i)
        for (int r = 0; r < 7; ++r)
          for (int c = 0; c < 7; ++c) {
            const double a = original.main().stages()[s].q[i](r, c);
            const double b = read->main().stages()[s].q[i](r, c);
            if (!sameBits(a, b))
              QFAIL(qPrintable(QString("stage %1 tensor %2 (%3,%4): %5 read back as %6")
                                   .arg(s)
                                   .arg(i)
                                   .arg(r)
                                   .arg(c)
                                   .arg(a, 0, 'g', 17)
                                   .arg(b, 0, 'g', 17)));
          }
    QCOMPARE(read->matches.size(), original.matches.size());
    for (size_t m = 0; m < original.matches.size(); ++m) {
      QVERIFY(read->matches[m].source == original.matches[m].source);  // exact, ==
      QVERIFY(read->matches[m].target == original.matches[m].target);
      QCOMPARE(read->matches[m].enabled, original.matches[m].enabled);
    }
    QVERIFY(read->fit.has_value());
    QCOMPARE(read->fit->model, original.fit->model);
    QCOMPARE(read->fit->reason, original.fit->reason);
    QCOMPARE(read->fit->criterion, std::string("aic"));
    QCOMPARE(read->fit->models.size(), size_t{2});
    QCOMPARE(read->fit->models[0].model, std::string("homography"));
    QCOMPARE(read->fit->models[0].held_out_rms_px, 4.5);
    QCOMPARE(read->fit->models[1].held_out_rms_px, -1.0);  // not computable: not written
    QVERIFY(sameBits(read->fit->models[1].rms_px, 0.1234567890123));
    QCOMPARE(read->fit->models[1].criterion, 34.5);
    QCOMPARE(read->fit->models[1].note, std::string("bends between the pairs"));
    QCOMPARE(read->fit->matches, original.fit->matches);
    QVERIFY(sameBits(read->fit->rms_px, original.fit->rms_px));
    QCOMPARE(read->fit->residuals_px.size(), original.fit->residuals_px.size());
    for (size_t k = 0; k < original.fit->residuals_px.size(); ++k)
      QVERIFY2(sameBits(read->fit->residuals_px[k], original.fit->residuals_px[k]),
               qPrintable(QString::number(original.fit->residuals_px[k], 'g', 17)));
    QVERIFY(read->fit->singular_values == original.fit->singular_values);
    // Writing what was read gives the same text: nothing drifts over save cycles.
    QCOMPARE(toArtcamJson(*read), toArtcamJson(original));
  }

  // A compositing camera's second-colour block (core/colour/composite.h) is written by its name
  // and read back as the same block, with every tensor bit for bit; a second-colour block of the
  // wrong size, or one without the colour block it blends into, is refused naming the place.
  void secondColourBlockRoundTrips() {
    const Camera composite = compositeCamera(CompositeOp::Multiply, 0.3, {96, 64});
    const std::string text = toArtcamJson(Artcam(composite));
    QVERIFY2(text.find("\"second-colour\"") != std::string::npos, text.c_str());
    const Result<Artcam> read = parseArtcam(text, "cam.artcam");
    QVERIFY2(read.ok(), read.status.message.c_str());
    QVERIFY(read->main().blocks() == composite.blocks());
    QCOMPARE(read->main().layout().find(BlockKind::SecondColour), 2);
    for (size_t i = 0; i < composite.stages()[0].q.size(); ++i)
      for (int r = 0; r < 11; ++r)
        for (int c = 0; c < 11; ++c)
          QVERIFY(sameBits(read->main().stages()[0].q[i](r, c), composite.stages()[0].q[i](r, c)));
    QCOMPARE(toArtcamJson(*read), text);

    Json j = Json::parse(text);
    j["blocks"][2]["size"] = 3;
    EXPECT_REFUSAL(j.dump(1), "cam.artcam: /blocks/2/size");
    // [position 3 | second-colour 4] with its seven 7×7 tensors, all zero.
    Json alone = Json::parse(text);
    alone["blocks"] = Json::array({Json{{"kind", "position"}, {"size", 3}},
                                   Json{{"kind", "second-colour"}, {"size", 4}}});
    Json tensors = Json::array();
    for (int i = 0; i < 7; ++i) {
      Json t = Json::array();
      for (int r = 0; r < 7; ++r) t.push_back(Json::array({0, 0, 0, 0, 0, 0, 0}));
      tensors.push_back(t);
    }
    alone["stages"] = Json::array({Json{{"tensors", tensors}}});
    EXPECT_REFUSAL(alone.dump(1), "a second-colour block needs a colour block");
  }

  void mappedPointsAreBitIdentical() {
    const Camera camera = test::randomRationalCamera({800, 600}, {1024, 768}, 0.2);
    const std::string text = toArtcamJson(Artcam(camera));
    const Result<Artcam> read = parseArtcam(text, "cam.artcam");
    QVERIFY2(read.ok(), read.status.message.c_str());
    for (int t = 0; t < 200; ++t) {
      const Eigen::Vector2d p(test::uniform(0, 800), test::uniform(0, 600));
      const auto a = targetPixelFromSourcePixel(camera, p);
      const auto b = targetPixelFromSourcePixel(read->main(), p);
      QCOMPARE(a.has_value(), b.has_value());
      if (a) QVERIFY(sameBits((*a)[0], (*b)[0]) && sameBits((*a)[1], (*b)[1]));
    }
  }

  void writesReadableJson() {
    const std::string text =
        toArtcamJson(Artcam(Camera::identity({{BlockKind::Position, 3}}, {64, 48}, {64, 48})));
    QVERIFY(text.rfind("{\n  \"format\": \"artcam\",\n  \"version\": 1,", 0) == 0);
    QVERIFY2(text.find("[0.0, 0.0, 0.5]") != std::string::npos, text.c_str());  // a row per line
    QVERIFY(text.find("\"matches\"") == std::string::npos);  // optional parts omitted when empty
  }

  void nonSymmetricTensorsAreKeptAsWritten() {
    const std::string text = mutated([](Json& j) { j["stages"][0]["tensors"][0][0][2] = 1.0; });
    const Result<Artcam> read = parseArtcam(text, "cam.artcam");
    QVERIFY2(read.ok(), read.status.message.c_str());
    QCOMPARE(read->main().stages()[0].q[0](0, 2), 1.0);
    QCOMPARE(read->main().stages()[0].q[0](2, 0), 0.5);
  }

  void refusesStructuralErrorsByPath() {
    EXPECT_REFUSAL(mutated([](Json& j) { j["frames"].erase("source"); }),
                   "cam.artcam: /frames/source: missing");
    EXPECT_REFUSAL(mutated([](Json& j) { j.erase("stages"); }), "/stages: missing");
    EXPECT_REFUSAL(mutated([](Json& j) {
                     j["stages"][0]["tensors"][2][1] = {0, 0};
                   }),
                   "cam.artcam: /stages/0/tensors/2/1: expected 3 numbers, found 2");
    EXPECT_REFUSAL(mutated([](Json& j) { j["stages"][0]["tensors"].erase(2); }),
                   "/stages/0/tensors: expected 3 tensors (one per element), found 2");
    EXPECT_REFUSAL(mutated([](Json& j) { j["stages"][0]["tensors"][1].erase(0); }),
                   "/stages/0/tensors/1: expected 3 rows, found 2");
    EXPECT_REFUSAL(mutated([](Json& j) { j["stages"][0]["tensors"][0][0][1] = "x"; }),
                   "/stages/0/tensors/0/0/1: expected a number, found \"x\"");
    EXPECT_REFUSAL(mutated([](Json& j) { j["stages"][0]["tensors"][0][0][1] = nullptr; }),
                   "/stages/0/tensors/0/0/1: expected a number, found null");
    EXPECT_REFUSAL(mutated([](Json& j) { j["stages"] = Json::array(); }),
                   "/stages: expected at least one stage");
    EXPECT_REFUSAL(mutated([](Json& j) { j["blocks"][0]["kind"] = "smell"; }),
                   "/blocks/0/kind: unknown block kind \"smell\"");
    EXPECT_REFUSAL(mutated([](Json& j) { j["blocks"][0]["size"] = 5; }),
                   "/blocks/0/size: 5 elements");
    EXPECT_REFUSAL(mutated([](Json& j) { j["frames"]["target"] = {640}; }),
                   "/frames/target: expected [w, h]");
    EXPECT_REFUSAL(mutated([](Json& j) {
                     j["frames"]["target"] = {640.5, 480};
                   }),
                   "/frames/target/0: expected a whole number");
    EXPECT_REFUSAL(mutated([](Json& j) { j["frames"]["target"] = {0, 0}; }), "invalid camera: ");
    EXPECT_REFUSAL(mutated([](Json& j) {
                     j["matches"][1]["target"] = {1, 2, 3};
                   }),
                   "/matches/1/target: expected 2 numbers, found 3");
    EXPECT_REFUSAL(mutated([](Json& j) { j["matches"][0]["enabled"] = 1; }),
                   "/matches/0/enabled: expected true or false");
    EXPECT_REFUSAL(mutated([](Json& j) { j["fit"].erase("rms_px"); }), "/fit/rms_px: missing");
    EXPECT_REFUSAL("[1, 2]", "cam.artcam: expected a JSON object at the top level");
  }

  void refusesOtherFormatsAndNewerVersions() {
    EXPECT_REFUSAL(mutated([](Json& j) { j["version"] = 2; }),
                   "cam.artcam: written by a newer ARTcam (version 2; this build reads up to 1)");
    EXPECT_REFUSAL(mutated([](Json& j) { j["version"] = 0; }),
                   "/version: expected a whole number of at least 1");
    EXPECT_REFUSAL(mutated([](Json& j) { j["version"] = "1"; }),
                   "/version: expected a whole number");
    EXPECT_REFUSAL(mutated([](Json& j) { j.erase("version"); }), "/version: missing");
    EXPECT_REFUSAL(mutated([](Json& j) { j["format"] = "photoshop"; }),
                   "/format: expected \"artcam\", found \"photoshop\"");
    EXPECT_REFUSAL(mutated([](Json& j) { j.erase("format"); }), "/format: missing");
  }

  void refusesNonFiniteNumbers() {
    std::string overflow = kValid;
    overflow.replace(overflow.find("0.5"), 3, "1e999");
    EXPECT_REFUSAL(overflow, "cam.artcam: line 6, column 35: not a finite number: 1e999");
    std::string underflow = kValid;  // correctly rounded to 0, like any other literal
    underflow.replace(underflow.find("0.5"), 3, "1e-999");
    QCOMPARE(refusal(underflow), QString("ACCEPTED"));
    std::string nan = kValid;
    nan.replace(nan.find("0.5"), 3, "NaN");
    EXPECT_REFUSAL(nan, "line 6, column");
    EXPECT_REFUSAL(nan, "invalid JSON");
  }

  void refusesSyntaxErrorsWithLineAndColumn() {
    std::string missing_comma = kValid;
    missing_comma.erase(missing_comma.find("\"artcam\",") + 8, 1);
    EXPECT_REFUSAL(missing_comma, "cam.artcam: line 3, column 11: invalid JSON: syntax error");
    const std::string truncated = std::string(kValid).substr(0, std::string(kValid).size() / 2);
    EXPECT_REFUSAL(truncated, "unexpected end of input");
    EXPECT_REFUSAL("", "line 1, column 1: invalid JSON");
  }

  void refusesMissingFiles() {
    QTemporaryDir dir;
    const std::string path = dir.filePath("nope.artcam").toStdString();
    const Result<Artcam> read = readArtcam(path);
    QVERIFY(!read.ok());
    QVERIFY(read.status.message.rfind(path + ": cannot read", 0) == 0);
  }

  void writeRefusesNonFiniteAndKeepsTheOldFile() {
    QTemporaryDir dir;
    const std::string path = dir.filePath("cam.artcam").toStdString();
    Artcam document = richDocument();
    QVERIFY(writeArtcam(path, document).ok);
    std::ifstream before_stream(path);
    const std::string before((std::istreambuf_iterator<char>(before_stream)), {});

    document.fit->rms_px = std::numeric_limits<double>::quiet_NaN();
    Status status = writeArtcam(path, document);
    QVERIFY(!status.ok);
    QVERIFY2(status.message == path + ": cannot write: /fit/rms_px is not a finite number",
             status.message.c_str());
    QVERIFY_THROWS_EXCEPTION(std::invalid_argument, toArtcamJson(document));

    document = richDocument();
    document.matches[3].target[1] = std::numeric_limits<double>::infinity();
    status = writeArtcam(path, document);
    QVERIFY2(!status.ok && status.message.find("/matches/3/target/1") != std::string::npos,
             status.message.c_str());

    document = richDocument();
    document.main().stages()[1].q[4](2, 3) = std::numeric_limits<double>::quiet_NaN();
    status = writeArtcam(path, document);
    QVERIFY2(!status.ok && status.message.find("/stages: stage 1 tensor 4 has a non-finite") !=
                               std::string::npos,
             status.message.c_str());

    std::ifstream after_stream(path);
    const std::string after((std::istreambuf_iterator<char>(after_stream)), {});
    QVERIFY(after == before);
    QCOMPARE(QDir(dir.path()).entryList(QDir::AllEntries | QDir::Hidden | QDir::NoDotAndDotDot),
             QStringList{"cam.artcam"});
  }
};

QTEST_GUILESS_MAIN(TestArtcamFile)
#include "test_artcam_file.moc"
