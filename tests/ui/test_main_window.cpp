// SPDX-License-Identifier: Apache-2.0
// The assembled window: opens the sample photo off the GUI thread, shows the fit and render
// figures in the status bar, zoom shortcuts, modified marker, and a clean shutdown with a
// render in flight.
#include "tests/support/test_support.h"
#include "tests/ui/ui_fixtures.h"
#include "ui/canvas.h"
#include "ui/commands.h"
#include "ui/document.h"
#include "ui/fit_status.h"
#include "ui/main_window.h"
#include "ui/preview_controller.h"
#include "ui/session.h"
#include "ui/tools/depth_tool.h"
#include "ui/tools/depth_tool_settings.h"
#include "ui/tools/pair_tool.h"

#include <QAction>
#include <QDragEnterEvent>
#include <QDropEvent>
#include <QMimeData>
#include <QStandardPaths>
#include <QUrl>
#include <QtTest/QtTest>

using namespace artcam;
using namespace artcam::ui;

class TestMainWindow : public QObject {
  Q_OBJECT

 private slots:
  void initTestCase() { QStandardPaths::setTestModeEnabled(true); }

  void opensPhotoAndShowsFit() {
    MainWindow window;
    window.session()->setInteractive(false);
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    window.session()->openPath(QString::fromStdString(artcam::test::resourcePath("coffee.png")));
    QTRY_VERIFY_WITH_TIMEOUT(window.document()->photo() != nullptr, 30000);
    QCOMPARE(window.document()->frame().width, 600);
    QVERIFY(window.windowTitle().startsWith("coffee.png"));
    Document* doc = window.document();
    for (const Pair& p : ui::test::ninePairs(600, 400))
      doc->undoStack()->push(new AddPairCommand(doc, p));
    QVERIFY(window.isWindowModified());
    QTRY_VERIFY_WITH_TIMEOUT(
        window.preview()->imageIsFinal() &&
            window.preview()->imageGeneration() == window.preview()->requestedGeneration(),
        30000);
    QVERIFY(window.fitStatus()->residualText().contains("RMS"));
    QVERIFY(window.fitStatus()->modelText().startsWith("Model: "));
    QVERIFY(window.fitStatus()->renderText().contains("ms"));

    // Zoom shortcuts reach the canvas.
    window.canvas()->setFocus();
    QTest::keyClick(&window, Qt::Key_1, Qt::ControlModifier);
    QCOMPARE(window.canvas()->view().scale(), 1.0);
    QTest::keyClick(&window, Qt::Key_Equal, Qt::ControlModifier);
    QCOMPARE(window.canvas()->view().scale(), 1.25);
    QTest::keyClick(&window, Qt::Key_0, Qt::ControlModifier);
    ViewTransform fitted;
    fitted.fit(QSizeF(window.canvas()->size()), QSizeF(600, 400));
    QCOMPARE(window.canvas()->view().scale(), fitted.scale());

    // For a look at the assembled window when run by hand.
    window.grab().save(QDir::temp().filePath("artcam_studio_main_window.png"));

    // Closing mid-render must not hang or crash (the worker is joined in the destructor).
    doc->undoStack()->undo();
    QVERIFY(window.close());  // non-interactive session: no prompt
  }

  void droppedFileOpens() {
    MainWindow window;
    window.session()->setInteractive(false);
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    QMimeData mime;
    mime.setUrls(
        {QUrl::fromLocalFile(QString::fromStdString(artcam::test::resourcePath("coffee.png")))});
    const QPoint at(200, 200);
    QDragEnterEvent enter(at, Qt::CopyAction, &mime, Qt::LeftButton, Qt::NoModifier);
    QCoreApplication::sendEvent(&window, &enter);
    QVERIFY(enter.isAccepted());
    QDropEvent drop(QPointF(at), Qt::CopyAction, &mime, Qt::LeftButton, Qt::NoModifier);
    QCoreApplication::sendEvent(&window, &drop);
    QTRY_VERIFY_WITH_TIMEOUT(window.document()->photo() != nullptr, 30000);
  }

  void shortcutsAreUniqueAndSwitchTools() {
    // Qt silently ignores a shortcut two actions share: every one must be unique.
    MainWindow window;
    QMap<QString, QString> owner;
    for (QAction* a : window.findChildren<QAction*>())
      for (const QKeySequence& k : a->shortcuts()) {
        const QString key = k.toString();
        QVERIFY2(!owner.contains(key) || owner[key] == a->text(),
                 qPrintable(QString("%1: %2 and %3").arg(key, owner[key], a->text())));
        owner[key] = a->text();
      }
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    window.canvas()->setFocus();
    QTest::keyClick(&window, Qt::Key_B);
    auto* brush = dynamic_cast<DepthTool*>(window.canvas()->tool());
    QVERIFY(brush && brush->mode() == DepthToolMode::Brush);
    QTest::keyClick(&window, Qt::Key_D);
    auto* points = dynamic_cast<DepthTool*>(window.canvas()->tool());
    QVERIFY(points && points->mode() == DepthToolMode::Points);
    QTest::keyClick(&window, Qt::Key_P);
    QVERIFY(dynamic_cast<PairTool*>(window.canvas()->tool()));
    const double r = window.depthToolSettings()->radius();
    QTest::keyClick(&window, Qt::Key_BracketRight);
    QCOMPARE(window.depthToolSettings()->radius(), r * 1.25);
  }
};

QTEST_MAIN(TestMainWindow)
#include "test_main_window.moc"
