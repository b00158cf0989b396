// SPDX-License-Identifier: Apache-2.0
// The Lines panel and the model row while lines drive the fit. The textbook plumb-line set (two
// horizontal and two vertical grid lines of tests/support/barrel_grid.h, a 90 px grid through a
// barrel lens) is traced point by point through the line commands, as the Line tool does: the
// document's camera must keep the grid's spacing within 3 % of its 90 px truth; the panel lists
// the lines with their remaining bow, deletes a selected line in ONE undo step, toggles one off
// and gives lines a horizontal or vertical role (showing the tilt against it); the model row
// offers Radial and disables the pairs-only models; the Pairs panel says the lines drive the
// fit instead of reporting an empty pairs fit.
#include "tests/support/barrel_grid.h"
#include "tests/ui/ui_fixtures.h"
#include "ui/document.h"
#include "ui/line_commands.h"
#include "ui/panels/lines_panel.h"
#include "ui/panels/pairs_panel.h"

#include <QAbstractButton>
#include <QTableView>
#include <QtTest/QtTest>

#include <memory>

using namespace artcam;
using namespace artcam::ui;
using artcam::test::BarrelGrid;

class TestLinesPanel : public QObject {
  Q_OBJECT

  BarrelGrid grid_;
  std::unique_ptr<Document> doc_;

  void trace(const std::vector<LineTrace>& lines) {
    for (const LineTrace& l : lines) {
      for (const Eigen::Vector2d& p : l.points) pushAddLinePoint(doc_.get(), p);
      QVERIFY(pushEndLine(doc_.get()));
    }
  }

 private slots:
  void init() {
    doc_ = std::make_unique<Document>();
    doc_->reset(ui::test::syntheticPhoto(grid_.frame.width, grid_.frame.height));
  }
  void cleanup() { doc_.reset(); }

  void plumbLinesKeepTheGridSpacing_data() {
    QTest::addColumn<int>("seed");
    for (int seed : {1, 2, 3}) QTest::addRow("seed %d", seed) << seed;
  }
  void plumbLinesKeepTheGridSpacing() {
    QFETCH(int, seed);
    trace(grid_.plumbLines(true, seed));
    QVERIFY(doc_->linesDriveFit());
    QVERIFY2(doc_->fit().status.ok, doc_->fit().status.message.c_str());
    const auto c = grid_.check(doc_->camera());
    qInfo("seed %d: spacing %.1f–%.1f px (truth 90), covered %.1f %%; %s", seed, c.min_spacing_px,
          c.max_spacing_px, 100 * c.covered, doc_->fit().record.reason.c_str());
    QVERIFY2(c.worst_ratio_error <= 0.03, qPrintable(QString::number(c.worst_ratio_error)));
    QVERIFY2(c.covered >= 0.99, qPrintable(QString::number(c.covered)));
  }

  void panelListsSelectsAndDeletes() {
    const std::vector<LineTrace> lines = grid_.plumbLines(true, 2);
    trace(lines);
    LinesPanel panel(doc_.get());
    QAbstractItemModel* m = panel.table()->model();
    QCOMPARE(m->rowCount(), 4);
    for (int row = 0; row < 4; ++row) {
      QCOMPARE(m->index(row, LinesTableModel::Label).data().toString(),
               QString::fromStdString(doc_->lines()[static_cast<size_t>(row)].label));
      QCOMPARE(m->index(row, LinesTableModel::Points).data().toInt(),
               static_cast<int>(lines[static_cast<size_t>(row)].points.size()));
      // The remaining bow, as the fit measured it: well under the photo's bend.
      bool ok = false;
      const double bow = m->index(row, LinesTableModel::Bow).data().toDouble(&ok);
      QVERIFY(ok);
      QVERIFY2(bow < 1.5, qPrintable(QString::number(bow)));
    }
    QVERIFY(panel.summaryText().startsWith("Lines drive the fit"));

    // One bad line: select it, Delete, one Ctrl+Z brings it back exactly.
    const LineSet before = doc_->lineSet();
    const int steps = doc_->undoStack()->index();
    panel.selectLine(2);
    QCOMPARE(panel.selectedLines(), std::vector<int>{2});
    QVERIFY(panel.deleteSelected());
    QCOMPARE(m->rowCount(), 3);
    for (const LineTrace& l : doc_->lines()) QVERIFY(l.label != before.lines[2].label);
    QCOMPARE(doc_->undoStack()->index(), steps + 1);
    doc_->undoStack()->undo();
    QVERIFY(doc_->lineSet() == before);
    QCOMPARE(m->rowCount(), 4);

    // The check box turns a line off: drawn, not fitted, no bow.
    QVERIFY(m->setData(m->index(0, LinesTableModel::Enabled), Qt::Unchecked, Qt::CheckStateRole));
    QVERIFY(!doc_->lines()[0].enabled);
    QCOMPARE(doc_->lineBows().size(), size_t{3});
    QCOMPARE(m->index(0, LinesTableModel::Bow).data().toString(), QString("off"));
    doc_->undoStack()->undo();
    QVERIFY(doc_->lineSet() == before);

    // Roles: the grid's rows are level and its columns plumb in the scene, and the radial lens
    // turns nothing, so the corrected lines' tilt from their roles is near 0; a role does not
    // change the camera.
    const Eigen::Vector2d probe(900, 700);
    const Eigen::Vector2d was = *targetPixelFromSourcePixel(doc_->camera(), probe);
    panel.table()->clearSelection();
    panel.selectLine(0);
    panel.table()->selectionModel()->select(
        m->index(1, 0), QItemSelectionModel::Select | QItemSelectionModel::Rows);
    QVERIFY(panel.setSelectedRole(LineRole::Horizontal));
    panel.selectLine(2);
    panel.table()->selectionModel()->select(
        m->index(3, 0), QItemSelectionModel::Select | QItemSelectionModel::Rows);
    QVERIFY(panel.setSelectedRole(LineRole::Vertical));
    QCOMPARE(m->index(0, LinesTableModel::Role).data().toString(), QString("H"));
    QCOMPARE(m->index(3, LinesTableModel::Role).data().toString(), QString("V"));
    for (int row = 0; row < 4; ++row) {
      bool ok = false;
      const double tilt = m->index(row, LinesTableModel::Tilt).data().toDouble(&ok);
      QVERIFY(ok);
      QVERIFY2(std::abs(tilt) < 0.2, qPrintable(QString::number(tilt)));
    }
    QCOMPARE(*targetPixelFromSourcePixel(doc_->camera(), probe), was);
    doc_->undoStack()->undo();
    QCOMPARE(m->index(3, LinesTableModel::Role).data().toString(), QString());
    QCOMPARE(m->index(0, LinesTableModel::Role).data().toString(), QString("H"));
  }

  void modelRowForLines() {
    PairsPanel pairs(doc_.get());
    // No lines: Radial does not apply, the pairs models do.
    QVERIFY(!pairs.radialButton()->isEnabled());
    QVERIFY(pairs.modelButton(ModelClass::Homography)->isEnabled());
    trace(grid_.plumbLines(true, 2));
    QVERIFY(pairs.radialButton()->isEnabled());
    QVERIFY(pairs.modelButton(ModelClass::Auto)->isEnabled());
    QVERIFY(pairs.modelButton(ModelClass::Quadratic)->isEnabled());
    for (ModelClass m : {ModelClass::Translation, ModelClass::Similarity, ModelClass::Affine,
                         ModelClass::Homography}) {
      QVERIFY(!pairs.modelButton(m)->isEnabled());
      QVERIFY(pairs.modelButton(m)->toolTip().contains("Lines drive the fit"));
    }
    QVERIFY(pairs.modelButton(ModelClass::Auto)->isChecked());
    // The banner names what drives the fit, not an empty pairs fit.
    QVERIFY2(pairs.bannerText().startsWith("Lines drive the fit"), qPrintable(pairs.bannerText()));
    QVERIFY(!pairs.bannerText().contains("0 matches"));

    // Quadr. forces the quadratic, Radial the radial lens; each one undo step.
    const Camera auto_camera = doc_->camera();
    pairs.modelButton(ModelClass::Quadratic)->click();
    QCOMPARE(doc_->fit().record.model, std::string("quadratic"));
    QVERIFY(pairs.modelButton(ModelClass::Quadratic)->isChecked());
    pairs.radialButton()->click();
    QCOMPARE(doc_->lineModel(), LineModel::Radial);
    QCOMPARE(doc_->fit().record.model, std::string("radial"));
    QVERIFY(pairs.radialButton()->isChecked());
    const auto c = grid_.check(doc_->camera());
    QVERIFY2(c.worst_ratio_error <= 0.03, qPrintable(QString::number(c.worst_ratio_error)));
    doc_->undoStack()->undo();
    QCOMPARE(doc_->fit().record.model, std::string("quadratic"));
    doc_->undoStack()->undo();
    QCOMPARE(doc_->lineModel(), LineModel::Auto);
    QCOMPARE(doc_->model(), ModelClass::Auto);
    for (const Eigen::Vector2d& p :
         {Eigen::Vector2d(10, 10), Eigen::Vector2d(900, 700), Eigen::Vector2d(480, 100)})
      QCOMPARE(*targetPixelFromSourcePixel(doc_->camera(), p),
               *targetPixelFromSourcePixel(auto_camera, p));
    QVERIFY(pairs.modelButton(ModelClass::Auto)->isChecked());

    // A disabled button clicked from code changes nothing.
    pairs.modelButton(ModelClass::Homography)->click();
    QCOMPARE(doc_->model(), ModelClass::Auto);
  }
};

QTEST_MAIN(TestLinesPanel)
#include "test_lines_panel.moc"
