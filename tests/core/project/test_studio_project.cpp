// SPDX-License-Identifier: Apache-2.0
// The project file's one reader and writer (core/project/studio_project.h): a project survives
// a round trip field by field, the version is the lowest that holds its parts, and damaged
// files are refused naming the JSON path. Base64 against RFC 4648's test vectors.
#include "core/effects/effect_table.h"
#include "core/io/artcam_file.h"
#include "core/project/studio_project.h"
#include "core/util/base64.h"

#include <QtTest/QtTest>

#include <string>

using namespace artcam;

namespace {

const char* kHeader = R"({"format":"artcam-studio-project","version":3,"photo":"p.png",)";

std::string refusal(const std::string& rest) {
  const Result<StudioProject> r = parseStudioProject(std::string(kHeader) + rest, "/d/x.artcamproj");
  return r.ok() ? std::string("(accepted)") : r.status.message;
}

}  // namespace

class TestStudioProject : public QObject {
  Q_OBJECT

 private slots:
  void base64MatchesTheRfc() {
    const std::pair<const char*, const char*> vectors[] = {
        {"", ""}, {"f", "Zg=="}, {"fo", "Zm8="}, {"foo", "Zm9v"}, {"foob", "Zm9vYg=="},
        {"fooba", "Zm9vYmE="}, {"foobar", "Zm9vYmFy"}};
    for (const auto& [plain, coded] : vectors) {
      const std::string p(plain);
      const std::vector<uint8_t> bytes(p.begin(), p.end());
      QCOMPARE(encodeBase64(bytes), std::string(coded));
      const auto back = decodeBase64(coded);
      QVERIFY(back && *back == bytes);
    }
    for (const char* bad : {"Zg=", "Z===", "Zm9v!A==", "=Zm9", "Zg==Zg=="})
      QVERIFY2(!decodeBase64(bad), bad);
  }

  void roundTripKeepsEveryField() {
    StudioProject p;
    p.photo_path = "/data/trip/photo.jpg";
    p.pairs.push_back({Eigen::Vector2d(10.25, 20.5), Eigen::Vector2d(11.0, 19.75), true});
    p.pairs.push_back({Eigen::Vector2d(0.1, 1e-7), Eigen::Vector2d(599.9, 399.9), false});
    p.model = ModelClass::Quadratic;
    p.manual_camera = buildEffect("chromatic-aberration", {{"red", {0.01}}}, {600, 400});
    p.effects = {{"aerial-perspective", {{"near", {0.5}}, {"haze", {0.1, 0.2, 0.3}}}},
                 {"depth-of-field", {{"focus", {3.0}}}}};
    ProjectDepthLayer layer;
    layer.name = "Table \"front\"";
    layer.mask = RegionMask(600, 400);
    layer.mask.fillPolygon({{10, 10}, {300, 20}, {200, 390}});
    layer.anchors = {{{20.5, 30.5}, 2.0}, {{250.5, 30.5}, 2.5}, {{200.5, 300.5}, 1.25}};
    p.depth_layers.push_back(layer);
    p.depth_map = ProjectDepthMap{"/data/trip/depth.exr", {0.001, true, 0.0}};
    p.view_json = R"({"scale":2,"centre":[1,2]})";
    p.parts_json = R"({"insertion":{"a":1}})";
    const std::string text = studioProjectToJson(p, "/data/trip/trip.artcamproj");
    QVERIFY(text.find("\"photo\": \"photo.jpg\"") != std::string::npos);  // relative on disk
    QVERIFY(text.find("\"version\": 3") != std::string::npos);
    const Result<StudioProject> back = parseStudioProject(text, "/data/trip/trip.artcamproj");
    QVERIFY2(back.ok(), back.status.message.c_str());
    QCOMPARE(back->photo_path, p.photo_path);
    QCOMPARE(back->pairs.size(), p.pairs.size());
    for (size_t i = 0; i < p.pairs.size(); ++i) {
      QVERIFY(back->pairs[i].source == p.pairs[i].source);
      QVERIFY(back->pairs[i].target == p.pairs[i].target);
      QCOMPARE(back->pairs[i].enabled, p.pairs[i].enabled);
    }
    QCOMPARE(back->model, ModelClass::Quadratic);
    QVERIFY(back->manual_camera);
    QCOMPARE(toArtcamJson(*back->manual_camera), toArtcamJson(*p.manual_camera));
    QVERIFY(back->effects == p.effects);
    QCOMPARE(back->depth_layers.size(), size_t{1});
    QVERIFY(back->depth_layers[0] == layer);
    QVERIFY(back->depth_map);
    QCOMPARE(back->depth_map->path, p.depth_map->path);
    QCOMPARE(back->depth_map->options.scale, 0.001);
    QVERIFY(back->depth_map->options.inverse);
    QCOMPARE(back->view_json, std::string(R"({"scale":2,"centre":[1,2]})"));
    QCOMPARE(back->parts_json, p.parts_json);
  }

  void versionIsTheLowestThatHoldsTheParts() {
    StudioProject p;
    p.photo_path = "/x/p.png";
    QVERIFY(studioProjectToJson(p, "/x/a.artcamproj").find("\"version\": 1") != std::string::npos);
    p.parts_json = R"({"colour":{}})";
    QVERIFY(studioProjectToJson(p, "/x/a.artcamproj").find("\"version\": 2") != std::string::npos);
    p.effects = {{"barrel", {}}};
    QVERIFY(studioProjectToJson(p, "/x/a.artcamproj").find("\"version\": 3") != std::string::npos);
    p.lines = {LineTrace{"1", {{1, 2}, {3, 4}, {5, 7}}, true}};
    QVERIFY(studioProjectToJson(p, "/x/a.artcamproj").find("\"version\": 4") != std::string::npos);
    // A second image (the compositing effects' input): version 5, its path relative beneath the
    // project's folder and absolute once read.
    p.second_path = "/x/layers/over.png";
    const std::string with_second = studioProjectToJson(p, "/x/a.artcamproj");
    QVERIFY(with_second.find("\"version\": 5") != std::string::npos);
    QVERIFY2(with_second.find("\"path\": \"layers/over.png\"") != std::string::npos,
             with_second.c_str());
    const Result<StudioProject> back = parseStudioProject(with_second, "/x/a.artcamproj");
    QVERIFY2(back.ok(), back.status.message.c_str());
    QCOMPARE(back->second_path.value_or(""), std::string("/x/layers/over.png"));
    p.second_path.reset();
    p.finish = "charcoal";
    const std::string with_finish = studioProjectToJson(p, "/x/a.artcamproj");
    QVERIFY(with_finish.find("\"version\": 5") != std::string::npos);
    QCOMPARE(parseStudioProject(with_finish, "/x/a.artcamproj")->finish, std::string("charcoal"));
    const Result<StudioProject> newer = parseStudioProject(
        R"({"format":"artcam-studio-project","version":6,"photo":"p.png"})", "/d/n.artcamproj");
    QVERIFY(!newer.ok());
    QVERIFY2(newer.status.message.find("n.artcamproj: written by a newer ARTcam Studio") == 0,
             newer.status.message.c_str());
  }

  void damagedFilesNameThePlace() {
    const std::pair<std::string, std::string> cases[] = {
        {R"("effects":[{"effect":"blurr"}]})",
         "x.artcamproj: /effects/0/effect: unknown effect \"blurr\""},
        {R"("effects":[{"effect":"barrel","params":{"k":[0.9]}}]})",
         "x.artcamproj: /effects/0/params/k: k = 0.9 is outside its range"},
        {R"("effects":[{"effect":"barrel","params":{"rate":[0.1]}}]})",
         "x.artcamproj: /effects/0/params/rate: not a parameter of barrel"},
        {R"("effects":{}})", "x.artcamproj: /effects: expected an array"},
        {R"("pairs":[{"source":[1,"a"],"target":[0,0]}]})",
         "x.artcamproj: /pairs/0/source: expected [x, y]"},
        {R"("depth":{"layers":[{"size":[2,2],"mask":"%%%%"}]}})",
         "x.artcamproj: /depth/layers/0/mask: not base64"},
        {R"("depth":{"layers":[{"size":[2,2],"mask":"AAQ=","anchors":[{"pixel":[0,0],"depth":-1}]}]}})",
         "x.artcamproj: /depth/layers/0/anchors/0/depth: expected a number greater than 0"},
        {R"("camera":{"format":"artcam"}})", "x.artcamproj: /camera"},
        {R"("view":[1]})", "x.artcamproj: /view: expected an object"},
        {R"("lines":[{"points":[[1,2],[3]]}]})",
         "x.artcamproj: /lines/0/points/1: expected [x, y]"},
        // The match readers' bound (fit_record.h), as the CSV reader keeps it.
        {R"("pairs":[{"source":[1e300,2],"target":[0,0]}]})",
         "x.artcamproj: /pairs/0/source/0: 1e+300 is beyond any pixel coordinate (|value| > 1e9)"},
        {R"("pairs":[{"source":[1,2],"target":[0,-2e9]}]})",
         "x.artcamproj: /pairs/0/target/1: -2000000000.0 is beyond any pixel coordinate"},
        {R"("lines":[{"points":[[1,2],[3,4e12]]}]})",
         "x.artcamproj: /lines/0/points/1/1: 4000000000000.0 is beyond any pixel coordinate"},
        {R"("lines":[{"label":"a","points":[[1,2]],"enabled":1}]})",
         "x.artcamproj: /lines/0/enabled: expected true or false"},
        {R"("second":{"path":""}})", "x.artcamproj: /second/path: missing"},
        {R"("second":"over.png"})", "x.artcamproj: /second: expected an object"},
        {R"("finish":"crayon"})", "x.artcamproj: /finish: unknown finish \"crayon\" (pencil"},
    };
    for (const auto& [rest, want] : cases) {
      const std::string got = refusal(rest);
      QVERIFY2(got.find(want) == 0, (rest + " -> " + got).c_str());
      QVERIFY2(got.find('\n') == std::string::npos, got.c_str());
    }
  }

  void colourBlockComesFromTheColourPart() {
    StudioProject p;
    QVERIFY(projectColourBlock(p, "x")->has_value() == false);
    p.parts_json = R"({"colour":{"colour_block":{"format":"nope"}}})";
    const auto bad = projectColourBlock(p, "x.artcamproj");
    QVERIFY(!bad.ok());
    QVERIFY2(bad.status.message.find("x.artcamproj: /parts/colour/colour_block") == 0,
             bad.status.message.c_str());
  }
};

QTEST_GUILESS_MAIN(TestStudioProject)
#include "test_studio_project.moc"
