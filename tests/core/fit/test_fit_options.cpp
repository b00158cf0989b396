// SPDX-License-Identifier: Apache-2.0
// The fit options' checks (FitOptions::check, ColourFitOptions::check, LinesFitOptions::check,
// core/fit/options_check.h): the defaults pass; a field outside its range fails naming the
// field, its range and its value, in the caller's words when it gives them; and the fit entry
// points return that failure themselves, so a caller that never calls check (the studio) is
// held to the same ranges. Before the checks, a robust threshold of -1 px fitted as if it
// were 1 px (its square), and a threshold of 0 dE00 made every colour sample an outlier.
#include "core/fit/fit_colour.h"
#include "core/fit/fit_image.h"
#include "core/fit/fit_lines.h"

#include <QtTest/QtTest>

#include <cmath>
#include <limits>

using namespace artcam;

namespace {

const FrameSize kFrame{600, 400};

// 20 matches of a translation by (3, -2) px, spread over the frame.
std::vector<PointMatch> shiftedGrid() {
  std::vector<PointMatch> m;
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 5; ++i) {
      const Eigen::Vector2d s(60.0 + 120.0 * i, 50.0 + 100.0 * j);
      m.push_back({s, s + Eigen::Vector2d(3.0, -2.0), true});
    }
  return m;
}

}  // namespace

class TestFitOptions : public QObject {
  Q_OBJECT

 private slots:
  void defaultsPass() {
    QVERIFY(FitOptions{}.check().ok);
    QVERIFY(ColourFitOptions{}.check().ok);
    QVERIFY(LinesFitOptions{}.check().ok);
  }

  void aFieldOutsideItsRangeIsNamed() {
    FitOptions fit;
    fit.robust_threshold_px = -1.0;
    QCOMPARE(QString::fromStdString(fit.check().message),
             "robust_threshold_px must be a number above 0, got -1");
    fit = {};
    fit.click_sigma_px = std::numeric_limits<double>::quiet_NaN();
    QCOMPARE(QString::fromStdString(fit.check().message),
             "click_sigma_px must be a number above 0, got nan");
    fit = {};
    fit.auto_improvement = 1.5;
    QCOMPARE(QString::fromStdString(fit.check().message),
             "auto_improvement must be a number above 0, at most 1, got 1.5");
    fit = {};
    fit.restarts = -1;
    QCOMPARE(QString::fromStdString(fit.check().message),
             "restarts must be a whole number from 0 to 1000, got -1");
    fit = {};
    fit.model = static_cast<ModelClass>(42);
    QCOMPARE(QString::fromStdString(fit.check().message),
             "model must be one of auto, translation, similarity, affine, homography or "
             "quadratic, got 42");

    ColourFitOptions colour;
    colour.robust_confidence = 0.0;
    QCOMPARE(QString::fromStdString(colour.check().message),
             "robust_confidence must be a number above 0, at most 1, got 0");
    colour = {};
    colour.robust_max_iterations = 0;
    QCOMPARE(QString::fromStdString(colour.check().message),
             "robust_max_iterations must be a whole number from 1 to 10000000, got 0");

    LinesFitOptions lines;
    lines.min_pole_margin = -0.1;
    QCOMPARE(QString::fromStdString(lines.check().message),
             "min_pole_margin must be a number from 0 to 1, got -0.1");
    lines = {};
    lines.auto_min_gain_px = -1.0;
    QCOMPARE(QString::fromStdString(lines.check().message),
             "auto_min_gain_px must be a number of at least 0, got -1");
  }

  // The first field out of range is the one reported, in the caller's words where it has them.
  void namesAreTheCallers() {
    FitOptions fit;
    fit.restarts = 5000;
    fit.robust_threshold_px = 0.0;
    const FieldNames cli = [](std::string_view field) -> std::string {
      return field == "robust_threshold_px" ? "--threshold" : "";
    };
    QCOMPARE(QString::fromStdString(fit.check(cli).message),
             "restarts must be a whole number from 0 to 1000, got 5000");
    fit.restarts = 0;
    QCOMPARE(QString::fromStdString(fit.check(cli).message),
             "--threshold must be a number above 0, got 0");
  }

  // The entry points refuse what check refuses, with its message, and fit nothing.
  void entryPointsHoldEveryCallerToTheRanges() {
    const std::vector<PointMatch> matches = shiftedGrid();
    FitOptions fit;
    QVERIFY(fitImageCamera(matches, kFrame, kFrame, fit).status.ok);
    fit.robust = true;
    fit.robust_threshold_px = -1.0;
    const FitSummary image = fitImageCamera(matches, kFrame, kFrame, fit);
    QVERIFY(!image.status.ok);
    QCOMPARE(image.status.message, fit.check().message);

    std::vector<PointMatch> object;
    for (const PointMatch& m : matches)
      object.push_back({Eigen::Vector3d(m.source.x(), m.source.y(), 1.0 + 0.01 * m.source.x()),
                        Eigen::Vector3d(m.target.x(), m.target.y(), 2.0), true});
    fit = {};
    fit.restarts = -3;
    QVERIFY(!fitObjectCamera(object, fit).status.ok);
    QCOMPARE(fitObjectCamera(object, fit).status.message, fit.check().message);

    std::vector<PointMatch> samples;
    for (int k = 0; k < 24; ++k) {
      const Eigen::Vector3d c(0.1 + 0.03 * k, 0.8 - 0.02 * k, 0.2 + 0.5 * std::sin(k));
      samples.push_back({c, Eigen::Vector3d(0.9 * c), true});
    }
    ColourFitOptions colour;
    QVERIFY(fitColourSamples(samples, colour).status.ok);
    colour.robust = true;
    colour.robust_threshold_de = 0.0;
    const ColourFitSummary refused = fitColourSamples(samples, colour);
    QVERIFY(!refused.status.ok);
    QCOMPARE(refused.status.message, colour.check().message);

    std::vector<LineTrace> traced = {{"a", {{10, 10}, {300, 12}, {590, 10}}, true},
                                     {"b", {{10, 390}, {300, 388}, {590, 390}}, true}};
    LinesFitOptions lines;
    lines.max_iterations = 0;
    const LinesFitSummary line_fit = fitLinesCamera(traced, {}, kFrame, kFrame, lines);
    QVERIFY(!line_fit.status.ok);
    QCOMPARE(line_fit.status.message, lines.check().message);
  }
};

QTEST_APPLESS_MAIN(TestFitOptions)
#include "test_fit_options.moc"
