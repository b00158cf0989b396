// SPDX-License-Identifier: Apache-2.0
// The window holds still and remembers: the toolbars fit the default 1400 px, no button moves
// when the Undo label names a long command or the fit's reason rewraps, every key is one
// action's, window and export options come back after a restart (QSettings in a temporary
// folder), the status bar forgets the old photo's cursor and a refused photo's progress, an
// imported camera with a pole in the frame is warned about, and the camera export proposes a
// file name.
#include "core/effects/effect_table.h"
#include "core/io/artcam_file.h"
#include "tests/ui/ui_fixtures.h"
#include "ui/colour/colour_dock.h"
#include "ui/commands.h"
#include "ui/document.h"
#include "ui/fit_status.h"
#include "ui/main_window.h"
#include "ui/panels/pairs_panel.h"
#include "ui/session.h"

#include <QAbstractButton>
#include <QAction>
#include <QApplication>
#include <QFile>
#include <QFileDialog>
#include <QLabel>
#include <QMessageBox>
#include <QProgressBar>
#include <QRegularExpression>
#include <QSettings>
#include <QSignalSpy>
#include <QStandardPaths>
#include <QStatusBar>
#include <QTemporaryDir>
#include <QTimer>
#include <QToolBar>
#include <QToolButton>
#include <QtTest/QtTest>

#include <functional>

using namespace artcam;
using namespace artcam::ui;

namespace {

// Runs `look` on the first modal dialog of type T that opens, then closes it (rejects).
template <typename T>
void whenModal(std::function<void(T*)> look) {
  auto* timer = new QTimer;
  timer->setInterval(20);
  QObject::connect(timer, &QTimer::timeout, timer, [timer, look] {
    auto* dialog = qobject_cast<T*>(QApplication::activeModalWidget());
    if (!dialog) return;
    timer->stop();
    timer->deleteLater();
    look(dialog);
    dialog->reject();
  });
  timer->start();
}

QRect geometryIn(const QWidget* w, const QWidget* top) {
  return QRect(w->mapTo(top, QPoint(0, 0)), w->size());
}

}  // namespace

class TestCalmWindow : public QObject {
  Q_OBJECT

 private slots:
  void initTestCase() {
    QStandardPaths::setTestModeEnabled(true);
    QVERIFY(dir_.isValid());
    // Every QSettings() of this run reads and writes under the temporary folder.
    QSettings::setPath(QSettings::NativeFormat, QSettings::UserScope, dir_.filePath("settings"));
    QSettings::setPath(QSettings::IniFormat, QSettings::UserScope, dir_.filePath("settings"));
    QCoreApplication::setOrganizationName("ARTcamTest");
    QCoreApplication::setApplicationName("CalmWindow");
  }
  void init() { QSettings().clear(); }

  // Two shortcuts on one key make Qt report an ambiguous overload and trigger neither action.
  void everyKeyIsOneActions() {
    MainWindow window;
    window.session()->setInteractive(false);
    QStringList clashes;
    QList<QPair<QKeySequence, QString>> seen;
    for (QAction* a : window.findChildren<QAction*>()) {
      for (const QKeySequence& k : a->shortcuts()) {
        if (k.isEmpty()) continue;
        for (const auto& [other, name] : seen)
          if (other == k) clashes << QString("%1: %2 and %3").arg(k.toString(), name, a->text());
        seen.append({k, a->text()});
      }
    }
    QVERIFY2(clashes.isEmpty(), qPrintable(clashes.join("; ")));
    QVERIFY(seen.size() > 20);  // the window's actions were found

    // And the zoom keys do their work (they did nothing while ambiguous).
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    window.document()->reset(ui::test::syntheticPhoto(600, 400));
    window.canvas()->setFocus();
    QTest::keyClick(&window, Qt::Key_1, Qt::ControlModifier);
    QCOMPARE(window.canvas()->view().scale(), 1.0);
    QTest::keyClick(&window, Qt::Key_Minus, Qt::ControlModifier);
    QVERIFY2(window.canvas()->view().scale() < 1.0, "Ctrl+- zooms out");
    QTest::keyClick(&window, Qt::Key_1, Qt::ControlModifier);
    QTest::keyClick(&window, Qt::Key_Plus, Qt::ControlModifier);
    QVERIFY2(window.canvas()->view().scale() > 1.0, "Ctrl++ zooms in");
  }

  // At the default 1400 px the top toolbars sit side by side whole: no overflow arrow.
  void toolbarsFitTheDefaultWidth() {
    MainWindow window;
    window.session()->setInteractive(false);
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    int wanted = 0;
    for (QToolBar* bar : window.findChildren<QToolBar*>()) {
      if (window.toolBarArea(bar) != Qt::TopToolBarArea || bar->isHidden()) continue;
      wanted += bar->sizeHint().width();
    }
    QVERIFY(wanted > 0);
    QVERIFY2(wanted <= 1400, qPrintable(QString("the toolbars want %1 px").arg(wanted)));
    window.resize(1400, 900);
    QTest::qWait(50);
    if (window.width() == 1400)
      for (QToolBar* bar : window.findChildren<QToolBar*>()) {
        const auto* more = bar->findChild<QToolButton*>("qt_toolbar_ext_button");
        QVERIFY2(!more || !more->isVisible(), qPrintable(bar->objectName() + " overflows"));
      }
  }

  // The toolbar's buttons keep their place when the undo stack's text changes.
  void undoLabelMovesNothing() {
    MainWindow window;
    window.session()->setInteractive(false);
    window.resize(1400, 900);
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    window.document()->reset(ui::test::syntheticPhoto(600, 400));
    auto* bar = window.findChild<QToolBar*>("mainToolBar");
    QVERIFY(bar);
    QTest::qWait(20);
    // Every widget of the toolbar, right of Undo included.
    QList<QPair<QWidget*, QRect>> before;
    for (QAction* a : bar->actions())
      if (QWidget* w = bar->widgetForAction(a); w && w->isVisible())
        before.append({w, geometryIn(w, &window)});
    QVERIFY(before.size() > 6);
    Artcam camera = buildEffect("barrel", {}, window.document()->frame());
    window.document()->undoStack()->push(new SetCameraCommand(
        window.document(), std::move(camera),
        "Set camera: Canon EF 24-70mm f/2.8L II USM at 24 mm (lensfun, corrected)"));
    QTest::qWait(50);
    for (const auto& [w, rect] : before)
      QVERIFY2(geometryIn(w, &window) == rect,
               qPrintable(QString("a toolbar button moved from x %1 to %2")
                              .arg(rect.x())
                              .arg(geometryIn(w, &window).x())));
  }

  // The model buttons keep their place while the fit's explanation changes length.
  void modelRowHoldsStill() {
    MainWindow window;
    window.session()->setInteractive(false);
    window.resize(1400, 900);
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    Document* doc = window.document();
    doc->reset(ui::test::syntheticPhoto());
    PairsPanel* panel = window.pairsPanel();
    QTest::qWait(50);
    const QList<ModelClass> models = {ModelClass::Auto, ModelClass::Affine, ModelClass::Quadratic};
    auto place = [&] {
      QList<QRect> out;
      for (ModelClass m : models) out << geometryIn(panel->modelButton(m), &window);
      return out;
    };
    const QList<QRect> empty = place();
    const QString reason_empty = panel->reasonText();
    for (const Pair& p : ui::test::ninePairs()) doc->undoStack()->push(new AddPairCommand(doc, p));
    QTRY_VERIFY(!panel->reasonText().isEmpty());
    QVERIFY(panel->reasonText() != reason_empty);
    QTest::qWait(200);  // the explanation's throttle, then the layout
    QCOMPARE(place(), empty);
    doc->undoStack()->push(new SetModelCommand(doc, ModelClass::Translation));
    QTest::qWait(200);
    QCOMPARE(place(), empty);
  }

  // Size and export options come back in the next session.
  void windowAndExportOptionsAreRemembered() {
    ExportOptions chosen;
    chosen.fill = std::array<float, 4>{0.25f, 0.5f, 0.75f, 1.0f};
    chosen.write.jpeg_quality = 71;
    chosen.write.pixel_type = "uint16";
    chosen.edge = EdgeMode::Black;  // not the default (transparent)
    {
      MainWindow window;
      window.session()->setInteractive(false);
      window.show();
      QVERIFY(QTest::qWaitForWindowExposed(&window));
      window.resize(1234, 801);
      QTest::qWait(50);
      QCOMPARE(window.size(), QSize(1234, 801));
      window.session()->setExportOptions(chosen);
      QVERIFY(window.close());
    }
    MainWindow again;
    QCOMPARE(again.size(), QSize(1234, 801));
    const ExportOptions back = again.session()->exportOptions();
    QVERIFY(back.fill.has_value());
    QCOMPARE(*back.fill, *chosen.fill);
    QCOMPARE(back.write.jpeg_quality, std::optional<int>(71));
    QCOMPARE(back.write.pixel_type, std::string("uint16"));
    QVERIFY(back.edge == EdgeMode::Black);
    QVERIFY(!back.crop_to_valid);
  }

  // A photo that cannot be read: while its error is shown, no "Loading 0%" stays behind it.
  void refusedPhotoLeavesNoProgress() {
    const QString broken = dir_.filePath("broken.png");
    {
      QFile f(broken);
      QVERIFY(f.open(QIODevice::WriteOnly));
      f.write("\x89PNG\r\n\x1a\n this is not a picture");
    }
    MainWindow window;
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    auto* bar = window.fitStatus()->findChild<QProgressBar*>();
    QVERIFY(bar);
    bool looked = false, progress_shown = true;
    QString message;
    whenModal<QMessageBox>([&](QMessageBox* box) {
      looked = true;
      progress_shown = bar->isVisible();
      message = box->text();
    });
    window.session()->openPath(broken);
    QTRY_VERIFY_WITH_TIMEOUT(looked, 20000);
    QVERIFY2(message.contains("broken.png"), qPrintable(message));
    QVERIFY2(!progress_shown, "the load progress is shown behind the refusal");
    QVERIFY(!window.statusBar()->currentMessage().contains("Loading"));
    QTRY_VERIFY(!bar->isVisible());
    window.session()->setInteractive(false);
  }

  // The cursor's position is of the photo it was over.
  void newPhotoClearsTheCursorPosition() {
    MainWindow window;
    window.session()->setInteractive(false);
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    window.document()->reset(ui::test::syntheticPhoto(320, 240));
    window.fitStatus()->setCursorPosition(QPointF(100.4, 50.5));
    const QRegularExpression position("^\\d+\\.\\d, \\d+\\.\\d px$");
    auto shown = [&] {
      for (const QLabel* l : window.fitStatus()->findChildren<QLabel*>())
        if (position.match(l->text()).hasMatch()) return l->text();
      return QString();
    };
    QCOMPARE(shown(), QString("100.4, 50.5 px"));
    window.document()->reset(ui::test::syntheticPhoto(640, 480));
    QCOMPARE(shown(), QString());
  }

  // A camera whose pole line crosses part of the frame: w' = w·(w + 2.5 v) vanishes on
  // v = −0.4, inside the 3:2 frame (|v| ≤ 2/3), which `artcam` warns about on reading it.
  void importWarnsOfAPoleInTheFrame() {
    const FrameSize frame{600, 400};
    const Eigen::Vector3d u = Eigen::Vector3d::Unit(0), v = Eigen::Vector3d::Unit(1),
                          w = Eigen::Vector3d::Unit(2);
    Stage stage{{symmetricOuter(u, w), symmetricOuter(v, w), symmetricOuter(w + 2.5 * v, w)}};
    Artcam camera(Camera({Block{BlockKind::Position, 3}}, {stage}, frame, frame));
    const QString path = dir_.filePath("import-me.artcam");
    QVERIFY(writeArtcam(path.toStdString(), camera).ok);

    MainWindow window;
    window.session()->setInteractive(false);
    window.document()->reset(ui::test::syntheticPhoto(600, 400));
    QSignalSpy status(window.session(), &Session::statusMessage);
    QSignalSpy finished(window.session(), &Session::importFinished);
    window.session()->importArtcam(path);  // read off the GUI thread
    QVERIFY(finished.wait(10000));
    QVERIFY(finished.first().at(0).toBool());
    QVERIFY(window.document()->manualCamera().has_value());
    QStringList said;
    for (const QList<QVariant>& s : status) said << s.at(0).toString();
    QVERIFY2(said.join('\n').contains("pole"), qPrintable(said.join('\n')));
  }

  // Every save dialog proposes a name beside the photo: its base name and what is saved.
  void saveDialogsProposeAName() {
    MainWindow window;
    window.session()->setInteractive(false);
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    window.document()->reset(ui::test::syntheticPhoto(320, 240));
    auto proposal = [&](const std::function<void()>& open) {
      QStringList proposed;
      whenModal<QFileDialog>([&](QFileDialog* dialog) { proposed = dialog->selectedFiles(); });
      open();
      return proposed.isEmpty() ? QString() : QFileInfo(proposed.front()).fileName();
    };
    const QString camera = proposal([&] { window.session()->exportArtcamDialog(); });
    QVERIFY2(camera.startsWith("synthetic") && camera.endsWith(".artcam"), qPrintable(camera));
    const QString csv = proposal([&] { window.colourDock()->exportCsvDialog(); });
    QVERIFY2(csv.startsWith("synthetic") && csv.endsWith(".csv"), qPrintable(csv));
    const QString project = proposal([&] { window.session()->saveAs(); });
    QVERIFY2(project.startsWith("synthetic") && project.endsWith(".artcamproj"),
             qPrintable(project));
  }

 private:
  QTemporaryDir dir_;
};

QTEST_MAIN(TestCalmWindow)
#include "test_calm_window.moc"
