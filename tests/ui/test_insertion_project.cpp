// SPDX-License-Identifier: Apache-2.0
// The Insertion mode's state survives a project save and reopen (grid matches, region, board,
// squares, max error, graphic and its placement), reopening adds no undo step, and a broken
// "insertion" part is named by its JSON path.
#include "tests/support/test_support.h"
#include "tests/ui/session_wait.h"
#include "ui/document.h"
#include "ui/main_window.h"
#include "ui/matting/insertion_model.h"
#include "ui/matting/insertion_panel.h"
#include "ui/matting/insertion_project.h"
#include "ui/matting/insertion_studio.h"
#include "ui/session.h"

#include <QtTest/QtTest>

#include <QJsonArray>
#include <QSignalSpy>
#include <QTemporaryDir>
#include <QUndoStack>

using namespace artcam;
using namespace artcam::ui;

namespace {

QString resource(const char* name) {
  return QString::fromStdString(artcam::test::resourcePath(name));
}

}  // namespace

class TestInsertionProject : public QObject {
  Q_OBJECT

 private slots:
  void stateSurvivesSaveAndReopen() {
    QTemporaryDir dir;
    const QString project = dir.filePath("sphere.artcamproj");
    InsertionState saved;
    {
      MainWindow window;
      window.session()->setInteractive(false);
      auto* studio = window.findChild<InsertionStudio*>();
      QVERIFY(studio);
      studio->panel()->setInteractive(false);
      window.session()->openPhoto(resource("insertion/mirror-sphere.png"));
      QTRY_VERIFY_WITH_TIMEOUT(window.document()->photo() != nullptr, 30000);
      QSignalSpy grid(studio->panel(), &InsertionPanel::gridImported);
      studio->panel()->importGridCsv(resource("insertion/mirror-sphere-grid.csv"));
      QVERIFY(grid.wait(30000));
      QSignalSpy graphic(studio->panel(), &InsertionPanel::graphicLoaded);
      studio->panel()->loadGraphic(resource("insertion/emblem.png"));
      QVERIFY(graphic.wait(30000));
      InsertionState edit = studio->model()->state();
      edit.region = {{200, 250}, {450, 250}, {450, 330}, {200, 330}};
      edit.matches.push_back({{64.0, 64.0}, {120.5, 400.25}, true});  // a table click
      edit.squares = 24;
      edit.max_error_px = 0.3;
      edit.placement.origin = {64, 32};
      edit.placement.width = 300;
      studio->model()->edit(edit, QStringLiteral("test edits"));
      saved = studio->model()->state();
      QVERIFY(saved.matches.size() > 100);
      QVERIFY(ui::test::saveAndWait(*window.session(), project));
    }
    MainWindow window;
    window.session()->setInteractive(false);
    auto* studio = window.findChild<InsertionStudio*>();
    studio->panel()->setInteractive(false);
    window.session()->openProject(project);
    QTRY_VERIFY_WITH_TIMEOUT(window.document()->photo() != nullptr, 30000);
    QTRY_VERIFY_WITH_TIMEOUT(studio->model()->state().graphic != nullptr, 30000);
    const InsertionState& back = studio->model()->state();
    QCOMPARE(back.matches, saved.matches);  // doubles written by QJson round-trip exactly
    QCOMPARE(back.region, saved.region);
    QCOMPARE(back.board_size, saved.board_size);
    QCOMPARE(back.squares, saved.squares);
    QCOMPARE(back.max_error_px, saved.max_error_px);
    QCOMPARE(back.placement, saved.placement);
    QCOMPARE(back.graphic_path, saved.graphic_path);
    QCOMPARE(back.graphic->width, saved.graphic->width);
    QCOMPARE(back.graphic->data, saved.graphic->data);
    // Opening is not an edit: nothing to undo and nothing unsaved.
    QCOMPARE(window.document()->undoStack()->count(), 0);
    QVERIFY(window.document()->undoStack()->isClean());
  }

  void emptyStateWritesNothing() { QVERIFY(insertionToJson(InsertionState{}).isEmpty()); }

  void brokenPartsAreNamed() {
    InsertionState s;
    s.matches.push_back({{1, 2}, {3, 4}});
    QJsonObject o = insertionToJson(s);
    QJsonArray matches = o["matches"].toArray();
    matches.append(QJsonObject{{"board", QJsonArray{1}}});
    o["matches"] = matches;
    const auto r = insertionFromJson(o, "p.artcamproj: /parts/insertion");
    QVERIFY(!r.ok());
    QCOMPARE(r.status.message, std::string("p.artcamproj: /parts/insertion/matches/1: expected board and photo [x, y]"));
    o = insertionToJson(s);
    o["squares"] = 1;
    QVERIFY(insertionFromJson(o, "").status.message.find("/squares") != std::string::npos);
    o = insertionToJson(s);
    matches = o["matches"].toArray();
    QJsonObject table_click = matches[0].toObject();
    table_click["on_table"] = "yes";
    matches[0] = table_click;
    o["matches"] = matches;
    QCOMPARE(insertionFromJson(o, "p").status.message,
             std::string("p/matches/0/on_table: expected true or false"));
  }
};

QTEST_MAIN(TestInsertionProject)
#include "test_insertion_project.moc"
