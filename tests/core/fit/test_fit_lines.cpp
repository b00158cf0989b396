// SPDX-License-Identifier: Apache-2.0
// Lens calibration from straight lines against a scene made in code: a façade of straight
// edges on a 6000×4000 frame, photographed through a known lens that one quadratic camera
// represents exactly, u = U / (1 - k |U|²) from photo to scene in the normalised frame (the
// photo's points are its closed-form inverse). The fit sees some edges; the HELD-OUT edges,
// measured with the tests' own total-least-squares line (tests/support/straight_lines.h), must
// come out straight to 0.5 px, and the camera must agree with the true lens, which the
// least-change gauge picks.
#include "core/fit/fit_lines.h"
#include "core/model/frames.h"
#include "tests/support/straight_lines.h"

#include <QtTest/QtTest>

#include <Eigen/Geometry>

#include <cmath>
#include <functional>
#include <random>

using namespace artcam;
using artcam::test::bowOf;

namespace {

const FrameSize kFrame{6000, 4000};
using Lens = std::function<Eigen::Vector2d(const Eigen::Vector2d&)>;  // normalised, photo→scene

// The centred radial lens and its closed-form inverse: |U| = r / (1 - k r²) solved for r.
Lens radialLens(double k) {
  return [k](const Eigen::Vector2d& u) { return Eigen::Vector2d(u / (1 - k * u.squaredNorm())); };
}

struct Scene {
  std::function<Eigen::Vector2d(const Eigen::Vector2d&)> photo_from_scene;  // normalised
  Lens scene_from_photo;
};

Scene radialScene(double k, Eigen::Vector2d centre = Eigen::Vector2d::Zero()) {
  return {[k, centre](const Eigen::Vector2d& s) { return Eigen::Vector2d(test::radialPhotoFromScene(k, s - centre) + centre); },
          [k, centre](const Eigen::Vector2d& u) {
            return Eigen::Vector2d(radialLens(k)(u - centre) + centre);
          }};
}

// A straight scene edge from a to b (scene pixels), sampled at n points, taken into the photo
// (pixels); points that fall outside the photo are dropped, as nobody could click them.
LineTrace edge(const Scene& scene, const std::string& label, Eigen::Vector2d a, Eigen::Vector2d b,
               int n, double noise_px = 0.0, std::mt19937* rng = nullptr) {
  LineTrace line;
  line.label = label;
  std::normal_distribution<double> gauss(0.0, noise_px);
  for (int k = 0; k < n; ++k) {
    const Eigen::Vector2d s = a + (b - a) * (k / (n - 1.0));
    Eigen::Vector2d p =
        pixelFromNormalized(kFrame, scene.photo_from_scene(normalizedFromPixel(kFrame, s)));
    if (noise_px > 0) p += Eigen::Vector2d(gauss(*rng), gauss(*rng));
    if (p.x() < 0 || p.y() < 0 || p.x() > kFrame.width || p.y() > kFrame.height) continue;
    line.points.push_back(p);
  }
  return line;
}

// A façade: horizontal and vertical edges across the frame (fitted, with the clicks' noise) and
// other edges, two diagonals among them, held out (exact: they measure the camera, not clicks).
void facade(const Scene& scene, std::vector<LineTrace>& fitted, std::vector<LineTrace>& held_out,
            double noise_px = 0.0) {
  std::mt19937 rng(7);
  const double w = kFrame.width, h = kFrame.height;
  for (double y : {150.0, 1100.0, 2900.0, 3850.0})
    fitted.push_back(edge(scene, "h" + std::to_string(int(y)), {100, y}, {w - 100, y}, 40, noise_px, &rng));
  for (double x : {200.0, 1500.0, 4600.0, 5800.0})
    fitted.push_back(edge(scene, "v" + std::to_string(int(x)), {x, 100}, {x, h - 100}, 30, noise_px, &rng));
  // Two roof edges: oblique lines are what tell a quadratic's uv terms apart (a shear u + a uv
  // keeps every horizontal and vertical edge straight).
  fitted.push_back(edge(scene, "roof1", {150, 1900}, {2900, 150}, 40, noise_px, &rng));
  fitted.push_back(edge(scene, "roof2", {3100, 200}, {5850, 2100}, 40, noise_px, &rng));
  for (double y : {500.0, 3400.0})
    held_out.push_back(edge(scene, "H" + std::to_string(int(y)), {300, y}, {w - 300, y}, 40));
  for (double x : {700.0, 5300.0})
    held_out.push_back(edge(scene, "V" + std::to_string(int(x)), {x, 200}, {x, h - 200}, 30));
  held_out.push_back(edge(scene, "D1", {300, 300}, {w - 300, h - 300}, 50));
  held_out.push_back(edge(scene, "D2", {600, h - 200}, {w - 900, 250}, 50));
}

double worstBow(const Camera& camera, const std::vector<LineTrace>& lines) {
  double worst = 0;
  for (const LineTrace& line : lines) {
    std::vector<Eigen::Vector2d> mapped;
    for (const auto& p : line.points) {
      const auto y = targetPixelFromSourcePixel(camera, p);
      if (!y) return std::numeric_limits<double>::infinity();
      mapped.push_back(*y);
    }
    worst = std::max(worst, bowOf(mapped));
  }
  return worst;
}

double worstBowInPhoto(const std::vector<LineTrace>& lines) {
  double worst = 0;
  for (const LineTrace& line : lines) worst = std::max(worst, bowOf(line.points));
  return worst;
}

// Largest distance between the fitted camera and a lens over a grid of the photo, in pixels.
double worstMapError(const Camera& camera, const Lens& lens) {
  double worst = 0;
  for (int j = 0; j <= 10; ++j)
    for (int i = 0; i <= 10; ++i) {
      const Eigen::Vector2d p(kFrame.width * i / 10.0, kFrame.height * j / 10.0);
      const auto y = targetPixelFromSourcePixel(camera, p);
      if (!y) return std::numeric_limits<double>::infinity();
      const Eigen::Vector2d truth = pixelFromNormalized(kFrame, lens(normalizedFromPixel(kFrame, p)));
      worst = std::max(worst, (*y - truth).norm());
    }
  return worst;
}

}  // namespace

class TestFitLines : public QObject {
  Q_OBJECT

 private slots:
  void heldOutEdgesStraight_data() {
    QTest::addColumn<double>("k");
    QTest::addColumn<QString>("model");
    QTest::addColumn<double>("noise");
    QTest::newRow("barrel, auto") << 0.05 << "auto" << 0.0;
    QTest::newRow("barrel, quadratic") << 0.05 << "quadratic" << 0.0;
    QTest::newRow("pincushion, auto") << -0.04 << "auto" << 0.0;
    QTest::newRow("barrel, 0.2 px clicks") << 0.05 << "auto" << 0.2;
  }
  void heldOutEdgesStraight() {
    QFETCH(double, k);
    QFETCH(QString, model);
    QFETCH(double, noise);
    const Scene scene = radialScene(k);
    std::vector<LineTrace> fitted, held_out;
    facade(scene, fitted, held_out, noise);
    // The photo's edges are visibly bent, so a fit that did nothing would fail.
    QVERIFY2(worstBowInPhoto(held_out) > 20.0, qPrintable(QString::number(worstBowInPhoto(held_out))));
    LinesFitOptions options;
    options.model = *lineModelFromName(model.toStdString());
    const LinesFitSummary fit = fitLinesCamera(fitted, {}, kFrame, kFrame, options);
    QVERIFY2(fit.status.ok, fit.status.message.c_str());
    const double bow = worstBow(fit.camera, held_out);
    qInfo("%s: held-out worst bow %.4g px (photo %.4g px); %s", qPrintable(model), bow,
          worstBowInPhoto(held_out), fit.report().c_str());
    QVERIFY2(bow <= 0.5, qPrintable(QString::number(bow)));
    // Least change at the centre is the true lens's own gauge: the camera is the lens.
    const double map_error = worstMapError(fit.camera, scene.scene_from_photo);
    qInfo("iterations %d, undetermined %d", fit.iterations, fit.undetermined);
    qInfo("worst distance from the true lens %.4g px", map_error);
    QVERIFY2(map_error < (noise > 0 ? 5.0 : 0.05), qPrintable(QString::number(map_error)));
    // The reported bows are the fitted lines' bows.
    QCOMPARE(fit.bows.size(), fitted.size());
    QVERIFY(std::abs(fit.max_bow_px - worstBow(fit.camera, fitted)) < 1e-9);
  }

  // A lens centred off the frame centre: the radial model about the centre cannot straighten
  // it, the quadratic can (its numerator and denominator are quadratics of u - c), and auto
  // must notice.
  void decentredLensNeedsTheQuadratic() {
    const Scene scene = radialScene(0.05, Eigen::Vector2d(0.12, -0.08));
    std::vector<LineTrace> fitted, held_out;
    facade(scene, fitted, held_out);
    LinesFitOptions radial;
    radial.model = LineModel::Radial;
    const LinesFitSummary only_radial = fitLinesCamera(fitted, {}, kFrame, kFrame, radial);
    QVERIFY(only_radial.status.ok);
    const double radial_bow = worstBow(only_radial.camera, held_out);
    QVERIFY2(radial_bow > 2.0, qPrintable(QString::number(radial_bow)));
    const LinesFitSummary fit = fitLinesCamera(fitted, {}, kFrame, kFrame);
    QVERIFY2(fit.status.ok, fit.status.message.c_str());
    QCOMPARE(fit.model, LineModel::Quadratic);
    const double bow = worstBow(fit.camera, held_out);
    qInfo("decentred: radial %.4g px, auto %.4g px; %s", radial_bow, bow, fit.report().c_str());
    QVERIFY2(bow <= 0.5, qPrintable(QString::number(bow)));
  }

  // Pairs fix what lines cannot (a homography after the lens): target = H(lens(photo)).
  void pairsCombineWithLines() {
    const Scene scene = radialScene(0.05);
    std::vector<LineTrace> fitted, held_out;
    facade(scene, fitted, held_out);
    Eigen::Matrix3d h;
    h << 1.05, 0.04, 0.03, -0.02, 0.97, -0.05, 0.03, -0.02, 1.0;  // normalised, column form
    const auto truth = [&](const Eigen::Vector2d& photo_px) {
      const Eigen::Vector2d s = scene.scene_from_photo(normalizedFromPixel(kFrame, photo_px));
      const Eigen::Vector3d y = h * s.homogeneous();
      return pixelFromNormalized(kFrame, y.hnormalized());
    };
    std::vector<PointMatch> pairs;
    for (const Eigen::Vector2d& p : {Eigen::Vector2d(800, 600), Eigen::Vector2d(5200, 500),
                                    Eigen::Vector2d(5100, 3500), Eigen::Vector2d(900, 3300),
                                    Eigen::Vector2d(3000, 2000), Eigen::Vector2d(3100, 800)}) {
      PointMatch m;
      m.source = p;
      m.target = truth(p);
      pairs.push_back(m);
    }
    const LinesFitSummary fit = fitLinesCamera(fitted, pairs, kFrame, kFrame);
    QVERIFY2(fit.status.ok, fit.status.message.c_str());
    qInfo("pairs: %s; iterations %d", fit.report().c_str(), fit.iterations);
    QCOMPARE(fit.pair_residuals_px.size(), pairs.size());
    for (double e : fit.pair_residuals_px) QVERIFY2(e < 0.5, qPrintable(QString::number(e)));
    QVERIFY2(worstBow(fit.camera, held_out) <= 0.5,
             qPrintable(QString::number(worstBow(fit.camera, held_out))));
    // Away from the pairs too: the camera is H after the lens.
    double worst = 0;
    for (const Eigen::Vector2d& p : {Eigen::Vector2d(300, 300), Eigen::Vector2d(5700, 3700),
                                    Eigen::Vector2d(2000, 3000)})
      worst = std::max(worst, (*targetPixelFromSourcePixel(fit.camera, p) - truth(p)).norm());
    QVERIFY2(worst < 1.0, qPrintable(QString::number(worst)));
  }

  void refusalsNameTheCause() {
    const Scene scene = radialScene(0.05);
    std::vector<LineTrace> fitted, held_out;
    facade(scene, fitted, held_out);

    std::vector<LineTrace> short_line = fitted;
    short_line[2].points.resize(2);
    LinesFitSummary fit = fitLinesCamera(short_line, {}, kFrame, kFrame);
    QVERIFY(!fit.status.ok);
    QVERIFY2(fit.status.message.find("\"h2900\" has 2 points") != std::string::npos,
             fit.status.message.c_str());

    std::vector<LineTrace> clumped = fitted;
    clumped[0].points.assign(5, Eigen::Vector2d(1234.5, 567.5));
    fit = fitLinesCamera(clumped, {}, kFrame, kFrame);
    QVERIFY(!fit.status.ok);
    QVERIFY2(fit.status.message.find("\"h150\"") != std::string::npos &&
                 fit.status.message.find("within") != std::string::npos,
             fit.status.message.c_str());

    // Edges through the centre stay straight under the lens: they cannot tell its k.
    std::vector<LineTrace> radial_only = {
        edge(scene, "across", {500, 2000}, {5500, 2000}, 20),
        edge(scene, "down", {3000, 200}, {3000, 3800}, 20),
        edge(scene, "diagonal", {1000, 3333.3333333333333}, {5000, 666.66666666666667}, 20)};
    fit = fitLinesCamera(radial_only, {}, kFrame, kFrame);
    QVERIFY(!fit.status.ok);
    QVERIFY2(fit.status.message.find("no information about the distortion") != std::string::npos,
             fit.status.message.c_str());

    std::vector<LineTrace> few = {edge(scene, "a", {100, 150}, {5900, 150}, 5),
                                  edge(scene, "b", {200, 100}, {200, 3900}, 4)};
    LinesFitOptions quadratic;
    quadratic.model = LineModel::Quadratic;
    fit = fitLinesCamera(few, {}, kFrame, kFrame, quadratic);
    QVERIFY(!fit.status.ok);
    QVERIFY2(fit.status.message.find("4 more points") != std::string::npos, fit.status.message.c_str());
    // Auto falls back to the radial lens, which five equations determine.
    fit = fitLinesCamera(few, {}, kFrame, kFrame);
    QVERIFY2(fit.status.ok, fit.status.message.c_str());
    QCOMPARE(fit.model, LineModel::Radial);
    QVERIFY(std::abs(fit.radial_k - 0.05) < 1e-6);

    fit = fitLinesCamera({}, {}, kFrame, kFrame);
    QVERIFY(!fit.status.ok);
    QVERIFY(fit.status.message.find("no lines") != std::string::npos);
  }
};

QTEST_GUILESS_MAIN(TestFitLines)
#include "test_fit_lines.moc"
