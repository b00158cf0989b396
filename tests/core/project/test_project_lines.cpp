// SPDX-License-Identifier: Apache-2.0
// Straight lines in the project: saved and read back point for point (version 4; a version 3
// file still reads, with no lines), and the document's geometry fitted from lines and pairs is
// the line fit's camera (core/fit/fit_lines.h), so the studio, `artcam export` and
// `artcam fit --lines` make one camera. The truth is a lens made here: u = U / (1 - k |U|²).
#include "core/fit/fit_lines.h"
#include "core/model/frames.h"
#include "core/project/document_camera.h"
#include "core/project/studio_project.h"

#include <QtTest/QtTest>

#include <cmath>

using namespace artcam;

namespace {

const FrameSize kFrame{1200, 800};
const double kK = 0.1;

Eigen::Vector2d photoFromScene(const Eigen::Vector2d& scene_px) {
  const Eigen::Vector2d s = normalizedFromPixel(kFrame, scene_px);
  return pixelFromNormalized(kFrame, s * (2.0 / (1.0 + std::sqrt(1.0 + 4.0 * kK * s.squaredNorm()))));
}

LineTrace edge(const std::string& label, Eigen::Vector2d a, Eigen::Vector2d b, int n) {
  LineTrace line{label, {}, true};
  for (int k = 0; k < n; ++k) line.points.push_back(photoFromScene(a + (b - a) * (k / (n - 1.0))));
  return line;
}

std::vector<LineTrace> facadeLines() {
  return {edge("top", {40, 40}, {1160, 40}, 12), edge("bottom", {40, 760}, {1160, 760}, 12),
          edge("left", {50, 30}, {50, 770}, 10), edge("right", {1150, 30}, {1150, 770}, 10),
          edge("roof", {60, 400}, {600, 40}, 10)};
}

}  // namespace

class TestProjectLines : public QObject {
  Q_OBJECT

 private slots:
  void linesSurviveTheProjectFile() {
    StudioProject p;
    p.photo_path = "/x/p.png";
    p.lines = facadeLines();
    p.lines[2].enabled = false;
    const Result<StudioProject> back =
        parseStudioProject(studioProjectToJson(p, "/x/a.artcamproj"), "/x/a.artcamproj");
    QVERIFY2(back.ok(), back.status.message.c_str());
    QCOMPARE(back->lines.size(), p.lines.size());
    for (size_t i = 0; i < p.lines.size(); ++i) {
      QCOMPARE(back->lines[i].label, p.lines[i].label);
      QCOMPARE(back->lines[i].enabled, p.lines[i].enabled);
      QCOMPARE(back->lines[i].points.size(), p.lines[i].points.size());
      for (size_t k = 0; k < p.lines[i].points.size(); ++k)
        QVERIFY(back->lines[i].points[k] == p.lines[i].points[k]);  // bit for bit
    }
    const Result<StudioProject> old = parseStudioProject(
        R"({"format":"artcam-studio-project","version":3,"photo":"p.png","pairs":[]})",
        "/d/o.artcamproj");
    QVERIFY2(old.ok(), old.status.message.c_str());
    QVERIFY(old->lines.empty());
  }

  // The lines' model and each line's role are kept; a project without them reads as auto with
  // no roles, and an unknown name is refused naming its place.
  void lineModelAndRolesSurvive() {
    StudioProject p;
    p.photo_path = "/x/p.png";
    p.lines = facadeLines();
    p.lines[0].role = LineRole::Horizontal;
    p.lines[2].role = LineRole::Vertical;
    p.line_model = LineModel::Radial;
    const std::string json = studioProjectToJson(p, "/x/a.artcamproj");
    const Result<StudioProject> back = parseStudioProject(json, "/x/a.artcamproj");
    QVERIFY2(back.ok(), back.status.message.c_str());
    QCOMPARE(back->line_model, LineModel::Radial);
    QCOMPARE(back->lines[0].role, LineRole::Horizontal);
    QCOMPARE(back->lines[1].role, LineRole::None);
    QCOMPARE(back->lines[2].role, LineRole::Vertical);
    const Result<StudioProject> bad = parseStudioProject(
        R"({"format":"artcam-studio-project","version":4,"photo":"p.png","line_model":"fisheye"})",
        "/d/o.artcamproj");
    QVERIFY(!bad.ok());
    QVERIFY2(bad.status.message.find("/line_model") != std::string::npos,
             bad.status.message.c_str());
    const Result<StudioProject> bad_role =
        parseStudioProject(R"({"format":"artcam-studio-project","version":4,"photo":"p.png",)"
                           R"("lines":[{"points":[[1,1],[2,2],[3,4]],"role":"diagonal"}]})",
                           "/d/o.artcamproj");
    QVERIFY(!bad_role.ok());
    QVERIFY2(bad_role.status.message.find("/lines/0/role") != std::string::npos,
             bad_role.status.message.c_str());
  }

  void documentGeometryIsTheLineFit() {
    DocumentFitInputs in;
    in.frame = kFrame;
    in.lines = facadeLines();
    // Two pairs straight from the lens (scene = where the photo point belongs).
    for (const Eigen::Vector2d& scene : {Eigen::Vector2d(300, 200), Eigen::Vector2d(900, 600)}) {
      PointMatch m;
      m.source = photoFromScene(scene);
      m.target = scene;
      in.matches.push_back(m);
    }
    const DocumentFit doc = fitDocumentGeometry(in);
    QVERIFY2(doc.fit.status.ok, doc.fit.status.message.c_str());
    QCOMPARE(doc.line_bows.size(), in.lines.size());
    const LinesFitSummary direct = fitLinesCamera(in.lines, in.matches, kFrame, kFrame);
    QVERIFY(direct.status.ok);
    for (const Eigen::Vector2d& p : {Eigen::Vector2d(10, 10), Eigen::Vector2d(600, 400),
                                     Eigen::Vector2d(1190, 790)}) {
      const auto a = targetPixelFromSourcePixel(doc.camera, p);
      const auto b = targetPixelFromSourcePixel(direct.camera, p);
      QVERIFY(a && b);
      QVERIFY((*a - *b).norm() < 1e-9);
    }
    // The lens itself, away from the pairs and lines: a photo point lands on its scene point.
    const Eigen::Vector2d scene(700, 300);
    const auto mapped = targetPixelFromSourcePixel(doc.camera, photoFromScene(scene));
    QVERIFY(mapped);
    QVERIFY2((*mapped - scene).norm() < 0.05, qPrintable(QString::number((*mapped - scene).norm())));
    for (double r : doc.residual_by_pair) QVERIFY2(r >= 0 && r < 0.05, qPrintable(QString::number(r)));
  }
};

QTEST_GUILESS_MAIN(TestProjectLines)
#include "test_project_lines.moc"
