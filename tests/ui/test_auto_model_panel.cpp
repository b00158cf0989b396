// SPDX-License-Identifier: Apache-2.0
// The Pairs panel says why the fit has its model: nine clicked pairs of a bulge give the
// quadratic camera under auto (the paper's nine-point drawing, Fig 5), the panel lists every
// model's error and the reason, and one click on "homography" refits as a homography (an undo
// step, like the Model menu); the status bar's tooltip carries the same reason.
#include "core/model/frames.h"
#include "tests/ui/ui_fixtures.h"
#include "ui/fit_status.h"
#include "ui/panels/pairs_panel.h"

#include <QAbstractButton>
#include <QLabel>
#include <QUndoStack>
#include <QtTest/QtTest>

#include <random>

using namespace artcam;
using namespace artcam::ui;

namespace {

// u' = u / (1 − 0.1 r²) in the normalised frame, clicked on a jittered 3×3 grid (±0.5 px).
std::vector<Pair> bulgePairs(FrameSize frame) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> jitter(0.25, 0.75), click(-0.5, 0.5);
  std::vector<Pair> out;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) {
      Pair p;
      p.source = {frame.width * (0.1 + 0.8 * (i + jitter(rng)) / 3),
                  frame.height * (0.1 + 0.8 * (j + jitter(rng)) / 3)};
      const Eigen::Vector2d u = normalizedFromPixel(frame, p.source);
      p.target = pixelFromNormalized(frame, u / (1.0 - 0.1 * u.squaredNorm())) +
                 Eigen::Vector2d(click(rng), click(rng));
      out.push_back(p);
    }
  return out;
}

}  // namespace

class TestAutoModelPanel : public QObject {
  Q_OBJECT

 private slots:
  void ninePairsOfABulgeGiveTheQuadraticAndSayWhy() {
    Document doc;
    PreviewController preview(&doc);
    PairsPanel panel(&doc);
    FitStatus status(&doc, &preview);
    const PhotoPtr photo = test::syntheticPhoto(800, 600);
    const std::vector<Pair> pairs = bulgePairs(FrameSize{800, 600});
    doc.reset(photo, pairs);
    QCOMPARE(doc.model(), ModelClass::Auto);
    QVERIFY(doc.fit().status.ok);
    QCOMPARE(doc.fit().record.model, std::string("quadratic"));
    QVERIFY(panel.modelButton(ModelClass::Auto)->isChecked());
    // Every model's error, the quadratic's near the clicks, the homography's pixels off.
    const QString scores = panel.modelScoresText();
    for (const char* m : {"translation", "similarity", "affine", "homography", "quadratic"})
      QVERIFY2(scores.contains(QString::fromUtf8(m)), m);
    QVERIFY(scores.contains(QString::number(doc.fit().record.models[3].rms_px, 'g', 3)));
    QVERIFY(doc.fit().record.models[3].rms_px > 1.0);
    QVERIFY(panel.reasonText().contains("auto chose quadratic"));
    QVERIFY(panel.reasonText().contains("information criterion"));
    QVERIFY(status.modelText().contains("quadratic"));
    QVERIFY(status.findChildren<QLabel*>().size() > 0);
    bool tooltip = false;
    for (const QLabel* l : status.findChildren<QLabel*>())
      tooltip = tooltip || l->toolTip().contains("auto chose quadratic");
    QVERIFY(tooltip);

    // One click on the homography: refit as a homography, undoable.
    const int steps = doc.undoStack()->count();
    panel.modelButton(ModelClass::Homography)->click();
    QCOMPARE(doc.model(), ModelClass::Homography);
    QCOMPARE(doc.undoStack()->count(), steps + 1);
    QVERIFY(doc.fit().status.ok);
    QCOMPARE(doc.fit().record.model, std::string("homography"));
    QVERIFY(panel.modelButton(ModelClass::Homography)->isChecked());
    QVERIFY(panel.reasonText().contains("homography chosen by hand"));
    QVERIFY(panel.reasonText().contains("auto would choose quadratic"));
    QVERIFY(status.modelText().contains("homography"));
    doc.undoStack()->undo();
    QCOMPARE(doc.model(), ModelClass::Auto);
    QCOMPARE(doc.fit().record.model, std::string("quadratic"));
    QVERIFY(panel.modelButton(ModelClass::Auto)->isChecked());
  }

  // A model's note is one long table cell (four clicked pairs: the homography's pole, with its
  // position). The scores wrap it: unwrapped, the panel's minimum width grew by the whole note
  // and the Pairs dock widened mid-session, shrinking the canvas under the user's next click.
  void aLongModelNoteWrapsInsteadOfWideningThePanel() {
    Document doc;
    PairsPanel panel(&doc);
    doc.reset(test::syntheticPhoto(600, 400));
    const int empty_width = panel.minimumSizeHint().width();
    std::vector<Pair> pairs;
    for (const auto& [s, t] : std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>>{
             {{127.42, 79.33}, {116.63, 71.91}},
             {{317.53, 95.51}, {318.20, 94.16}},
             {{436.18, 108.31}, {440.90, 104.94}},
             {{148.31, 194.61}, {142.92, 194.61}}}) {
      Pair p;
      p.source = s;
      p.target = t;
      pairs.push_back(p);
    }
    doc.reset(test::syntheticPhoto(600, 400), pairs);
    QVERIFY(doc.fit().status.ok);
    QVERIFY2(panel.modelScoresText().contains("pole"), qPrintable(panel.modelScoresText()));
    QVERIFY2(panel.minimumSizeHint().width() <= std::max(empty_width, 420),
             qPrintable(QString("minimum width %1 (empty panel: %2)")
                            .arg(panel.minimumSizeHint().width())
                            .arg(empty_width)));
  }
};

QTEST_MAIN(TestAutoModelPanel)
#include "test_auto_model_panel.moc"
