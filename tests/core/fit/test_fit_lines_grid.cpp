// SPDX-License-Identifier: Apache-2.0
// The plumb-line set a user traces on a photographed grid (tests/support/barrel_grid.h: 90 px
// squares through a division or a polynomial barrel lens, edges clicked with a quarter pixel
// of hand noise): the fitted camera is judged on the whole grid. Every spacing between
// neighbouring grid nodes, corrected, must be within 3 % of the 90 px truth (a keystone or a
// stretch shows as spacings that drift across the frame), and the corrected picture must fill
// the frame (no empty band). Two horizontals alone, and with two verticals added: the second
// set must not make the camera worse.
#include "core/fit/fit_lines.h"
#include "tests/support/barrel_grid.h"

#include <QtTest/QtTest>

using namespace artcam;
using artcam::test::BarrelGrid;

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
    QFETCH(bool, verticals);
    QFETCH(QString, model);
    QFETCH(int, seed);
    BarrelGrid grid;
    grid.division = division;
    grid.k = k;
    const std::vector<LineTrace> lines = grid.plumbLines(verticals, seed);
    // The photo is visibly bent: an identity camera fails the spacing check.
    const auto photo =
        grid.check(Camera::identity({Block{BlockKind::Position, 3}}, grid.frame, grid.frame));
    QVERIFY2(photo.worst_ratio_error > 0.05, qPrintable(QString::number(photo.worst_ratio_error)));
    LinesFitOptions options;
    options.model = *lineModelFromName(model.toStdString());
    const LinesFitSummary fit = fitLinesCamera(lines, {}, grid.frame, grid.frame, options);
    QVERIFY2(fit.status.ok, fit.status.message.c_str());
    const auto c = grid.check(fit.camera);
    qInfo("%s: spacing %.1f–%.1f px (truth %.0f), worst %.2f %%, covered %.1f %%; %s",
          qPrintable(model), c.min_spacing_px, c.max_spacing_px, grid.spacing_px,
          100 * c.worst_ratio_error, 100 * c.covered, fit.reason.c_str());
    QVERIFY(c.mapped);
    QVERIFY2(c.worst_ratio_error <= 0.03, qPrintable(QString::number(c.worst_ratio_error)));
    QVERIFY2(c.covered >= 0.99, qPrintable(QString::number(c.covered)));
  }
};

QTEST_GUILESS_MAIN(TestFitLinesGrid)
#include "test_fit_lines_grid.moc"
