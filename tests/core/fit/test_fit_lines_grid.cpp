// SPDX-License-Identifier: Apache-2.0
// The plumb-line set a user traces on a photographed grid: a square grid of 90 px on a 960×720
// photo, seen through a barrel lens made outside the code under test, one of two kinds: the
// division lens of the project's own barrel pictures, scene = u / (1 - k |u|²) in the normalised
// frame (photo points by the closed-form inverse of tests/support/straight_lines.h), and a
// polynomial in the SCENE radius, photo = c + (s - c)(1 + k1 ρ²) with ρ = |s - c| / 600 px, a
// different family from the fit's, which it can only approximate, as with a real lens. Edges are
// traced as a user clicks them (a handful of points, a quarter pixel of hand noise); the fitted
// camera is then judged on the whole grid: every spacing between neighbouring grid nodes,
// corrected, must be within 3 % of the 90 px truth (a keystone or a stretch shows as spacings that
// drift across the frame), and the corrected picture must fill the frame (no empty band).
#include "core/fit/fit_lines.h"
#include "core/model/frames.h"
#include "tests/support/straight_lines.h"

#include <QtTest/QtTest>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

using namespace artcam;

namespace {

const FrameSize kFrame{960, 720};
const Eigen::Vector2d kCentre(480, 360);
constexpr double kSpacing = 90.0;

// The lens of the running case: division (k > 0 barrel) or polynomial (k1 < 0 barrel).
struct Lens {
  bool division = true;
  double k = 0.25;
};
Lens g_lens;

Eigen::Vector2d photoFromScene(const Eigen::Vector2d& scene_px) {
  if (g_lens.division)
    return pixelFromNormalized(
        kFrame, test::radialPhotoFromScene(g_lens.k, normalizedFromPixel(kFrame, scene_px)));
  const Eigen::Vector2d d = scene_px - kCentre;
  const double rho2 = d.squaredNorm() / (600.0 * 600.0);
  return kCentre + d * (1 + g_lens.k * rho2);
}

bool inPhoto(const Eigen::Vector2d& p) {
  return p.x() >= 0 && p.y() >= 0 && p.x() <= kFrame.width && p.y() <= kFrame.height;
}

// A grid line of the scene traced in the photo: `clicks` points spread along it, those the
// photo shows, with hand noise.
LineTrace traced(const std::string& label, bool horizontal, double at_px, std::mt19937& rng) {
  std::normal_distribution<double> hand(0.0, 0.25);
  LineTrace line;
  line.label = label;
  const int clicks = 8;
  const double length = horizontal ? kFrame.width : kFrame.height;
  for (int k = 0; k < clicks; ++k) {
    const double along = 20 + (length - 40) * k / (clicks - 1.0);
    const Eigen::Vector2d s =
        horizontal ? Eigen::Vector2d(along, at_px) : Eigen::Vector2d(at_px, along);
    const Eigen::Vector2d p = photoFromScene(s) + Eigen::Vector2d(hand(rng), hand(rng));
    if (inPhoto(p)) line.points.push_back(p);
  }
  return line;
}

struct GridCheck {
  double worst_ratio_error = 0;  // max |spacing / 90 - 1| over neighbouring nodes
  double min_spacing = 1e9, max_spacing = 0;
  double covered = 0;  // fraction of the target frame the corrected photo covers
  bool mapped = true;
};

GridCheck checkGrid(const Camera& camera) {
  GridCheck out;
  // Grid nodes: every 90 px from the centre, the ones the photo shows.
  const int n = 8;
  std::vector<std::vector<std::optional<Eigen::Vector2d>>> nodes(2 * n + 1);
  for (int i = -n; i <= n; ++i)
    for (int j = -n; j <= n; ++j) {
      const Eigen::Vector2d p = photoFromScene(kCentre + kSpacing * Eigen::Vector2d(i, j));
      std::optional<Eigen::Vector2d> y;
      if (inPhoto(p)) {
        const auto mapped = targetPixelFromSourcePixel(camera, p);
        if (!mapped) out.mapped = false;
        y = mapped;
      }
      nodes[static_cast<size_t>(i + n)].push_back(y);
    }
  const auto measure = [&](const std::optional<Eigen::Vector2d>& a,
                           const std::optional<Eigen::Vector2d>& b) {
    if (!a || !b) return;
    const double d = (*a - *b).norm();
    out.min_spacing = std::min(out.min_spacing, d);
    out.max_spacing = std::max(out.max_spacing, d);
    out.worst_ratio_error = std::max(out.worst_ratio_error, std::abs(d / kSpacing - 1));
  };
  for (size_t i = 0; i < nodes.size(); ++i)
    for (size_t j = 0; j < nodes[i].size(); ++j) {
      if (i + 1 < nodes.size()) measure(nodes[i][j], nodes[i + 1][j]);
      if (j + 1 < nodes[i].size()) measure(nodes[i][j], nodes[i][j + 1]);
    }
  // Coverage: the photo sampled every 2 px, mapped, marking 8 px cells of the target frame.
  const int cw = kFrame.width / 8, ch = kFrame.height / 8;
  std::vector<char> hit(static_cast<size_t>(cw * ch), 0);
  for (double y = 1; y < kFrame.height; y += 2)
    for (double x = 1; x < kFrame.width; x += 2) {
      const auto t = targetPixelFromSourcePixel(camera, {x, y});
      if (!t) continue;
      const int cx = static_cast<int>(std::floor(t->x() / 8)),
                cy = static_cast<int>(std::floor(t->y() / 8));
      if (cx >= 0 && cy >= 0 && cx < cw && cy < ch) hit[static_cast<size_t>(cy * cw + cx)] = 1;
    }
  out.covered = static_cast<double>(std::count(hit.begin(), hit.end(), 1)) / hit.size();
  return out;
}

std::vector<LineTrace> plumbLines(bool with_verticals, int seed) {
  std::mt19937 rng(static_cast<unsigned>(seed));
  std::vector<LineTrace> lines = {traced("top", true, kCentre.y() - 3 * kSpacing, rng),
                                  traced("bottom", true, kCentre.y() + 3 * kSpacing, rng)};
  if (with_verticals) {
    lines.push_back(traced("left", false, kCentre.x() - 4 * kSpacing, rng));
    lines.push_back(traced("right", false, kCentre.x() + 4 * kSpacing, rng));
  }
  return lines;
}

}  // namespace

class TestFitLinesGrid : public QObject {
  Q_OBJECT

 private slots:
  void gridSpacingKept_data() {
    QTest::addColumn<bool>("division");
    QTest::addColumn<double>("k");
    QTest::addColumn<bool>("verticals");
    QTest::addColumn<QString>("model");
    QTest::addColumn<int>("seed");
    const struct {
      const char* name;
      bool division;
      double k;
    } lenses[] = {{"division 0.25", true, 0.25},
                  {"division 0.1", true, 0.1},
                  {"polynomial -0.06", false, -0.06}};
    for (const auto& lens : lenses)
      for (int seed : {1, 2, 3}) {
        QTest::addRow("%s, 2 horizontal, auto, seed %d", lens.name, seed)
            << lens.division << lens.k << false << "auto" << seed;
        QTest::addRow("%s, 2 horizontal + 2 vertical, auto, seed %d", lens.name, seed)
            << lens.division << lens.k << true << "auto" << seed;
        QTest::addRow("%s, 2 horizontal + 2 vertical, radial, seed %d", lens.name, seed)
            << lens.division << lens.k << true << "radial" << seed;
      }
  }
  void gridSpacingKept() {
    QFETCH(bool, division);
    QFETCH(double, k);
    g_lens = {division, k};
    QFETCH(bool, verticals);
    QFETCH(QString, model);
    QFETCH(int, seed);
    const std::vector<LineTrace> lines = plumbLines(verticals, seed);
    // The photo is visibly bent: an identity camera fails the spacing check.
    const GridCheck photo =
        checkGrid(Camera::identity({Block{BlockKind::Position, 3}}, kFrame, kFrame));
    QVERIFY2(photo.worst_ratio_error > 0.05, qPrintable(QString::number(photo.worst_ratio_error)));
    LinesFitOptions options;
    options.model = *lineModelFromName(model.toStdString());
    const LinesFitSummary fit = fitLinesCamera(lines, {}, kFrame, kFrame, options);
    QVERIFY2(fit.status.ok, fit.status.message.c_str());
    const GridCheck grid = checkGrid(fit.camera);
    qInfo("%s: spacing %.1f–%.1f px (truth %.0f), worst %.2f %%, covered %.1f %%; %s",
          qPrintable(model), grid.min_spacing, grid.max_spacing, kSpacing,
          100 * grid.worst_ratio_error, 100 * grid.covered, fit.reason.c_str());
    QVERIFY(grid.mapped);
    QVERIFY2(grid.worst_ratio_error <= 0.03, qPrintable(QString::number(grid.worst_ratio_error)));
    QVERIFY2(grid.covered >= 0.99, qPrintable(QString::number(grid.covered)));
  }
};

QTEST_GUILESS_MAIN(TestFitLinesGrid)
#include "test_fit_lines_grid.moc"
