// SPDX-License-Identifier: Apache-2.0
// Autosave and crash recovery: an autosave writes a recovery file (atomically, off the GUI
// thread); a later session is offered it (the prompt is injected: no modal dialog) and
// accepting restores the exact state, marked modified; declining or an older recovery keeps
// the saved project; a clean save or close removes the recovery file.
#include "core/io/image_io.h"
#include "tests/ui/session_wait.h"
#include "tests/ui/ui_fixtures.h"
#include "ui/autosave.h"
#include "ui/commands.h"
#include "ui/depth_commands.h"
#include "ui/document.h"
#include "ui/session.h"

#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QLockFile>
#include <QProcess>
#include <QSignalSpy>
#include <QStandardPaths>
#include <QTemporaryDir>
#include <QtTest/QtTest>

#include <memory>

using namespace artcam;
using namespace artcam::ui;

namespace {

// Everything a recovery must bring back, compared exactly.
struct State {
  std::vector<Pair> pairs;
  ModelClass model;
  std::vector<DepthPlaneLayer> layers;
  QString photo;

  explicit State(const Document& d)
      : pairs(d.pairs()),
        model(d.model()),
        layers(d.depth()->layers()),
        photo(d.photo() ? QFileInfo(d.photo()->path).absoluteFilePath() : QString()) {}
  bool operator==(const State& o) const {
    return pairs == o.pairs && model == o.model && layers == o.layers && photo == o.photo;
  }
};

void editSomething(Document& doc, double shift) {
  for (Pair p : test::ninePairs()) {
    p.target.x() += shift;
    doc.undoStack()->push(new AddPairCommand(&doc, p));
  }
  doc.undoStack()->push(new SetModelCommand(&doc, ModelClass::Homography));
  DepthPlaneLayer layer = doc.depth()->makeLayer();
  layer.mask.stamp({60 + shift, 70}, BrushOptions{25, 0.4, false});
  layer.anchors = {{{50, 60}, 2.0 + shift}, {{90, 65}, 3}, {{70, 100}, 4}};
  doc.undoStack()->push(new AddDepthLayerCommand(doc.depth(), layer));
}

bool autosaveNow(Session& session) {
  QSignalSpy saved(session.autosave(), &Autosave::saved);
  session.autosave()->saveNow();
  if (!saved.wait(20000)) return false;
  return saved.front().at(0).toBool();
}

}  // namespace

class TestAutosave : public QObject {
  Q_OBJECT

  QTemporaryDir dir_;
  QString photo_;
  QString recovery_dir_;

  void configure(Session& session, std::vector<RecoveryOffer>* offers, bool accept) {
    session.setInteractive(false);
    session.autosave()->setRecoveryDir(recovery_dir_);
    session.autosave()->setPrompt([offers, accept](const RecoveryOffer& offer) {
      if (offers) offers->push_back(offer);
      return accept;
    });
  }

 private slots:
  void initTestCase() {
    QStandardPaths::setTestModeEnabled(true);
    QVERIFY(dir_.isValid());
    photo_ = dir_.filePath("photo.png");
    QVERIFY(writeImage(photo_.toStdString(), test::syntheticPhoto()->full.image).ok);
  }

  void init() {
    // Each case starts with an empty recovery folder of its own.
    recovery_dir_ = dir_.filePath(QString("recovery-%1").arg(QTest::currentTestFunction()));
    QDir(recovery_dir_).removeRecursively();
  }

  void untitledSessionIsRecoveredExactly() {
    std::optional<State> before;
    {
      Document doc;
      Session session(&doc, nullptr);
      configure(session, nullptr, false);
      QVERIFY(!session.offerRecovery());  // nothing to recover yet
      session.openPhoto(photo_);
      QTRY_VERIFY_WITH_TIMEOUT(doc.photo() != nullptr, 20000);
      session.autosave()->saveNow();  // unmodified: nothing written
      QVERIFY(!QFile::exists(session.autosave()->recoveryPathFor(QString())));
      editSomething(doc, 0.0);
      QVERIFY(autosaveNow(session));
      QVERIFY(QFile::exists(session.autosave()->recoveryPathFor(QString())));
      before.emplace(doc);
      // The process "dies" here: no save, no clean close.
    }
    Document doc;
    Session session(&doc, nullptr);
    std::vector<RecoveryOffer> offers;
    configure(session, &offers, true);
    QVERIFY(session.offerRecovery());
    QCOMPARE(offers.size(), size_t{1});
    QVERIFY(offers.front().project_path.isEmpty());
    QTRY_VERIFY_WITH_TIMEOUT(doc.photo() != nullptr, 20000);
    QVERIFY(State(doc) == *before);
    QVERIFY(doc.isModified());  // recovered work is not saved yet
    QVERIFY(session.projectPath().isEmpty());
    QCOMPARE(doc.fit().status.ok, true);
    // A clean close leaves nothing to recover.
    session.closedCleanly();
    QVERIFY(session.autosave()->pendingRecoveries().empty());
  }

  void projectRecoveryIsOfferedOnlyWhenNewer() {
    const QString project = dir_.filePath("recover-me.artcamproj");
    std::optional<State> saved_state, edited_state;
    QString recovery_lock;
    {
      Document doc;
      Session session(&doc, nullptr);
      configure(session, nullptr, false);
      session.openPhoto(photo_);
      QTRY_VERIFY_WITH_TIMEOUT(doc.photo() != nullptr, 20000);
      editSomething(doc, 0.0);
      QVERIFY(autosaveNow(session));  // an untitled recovery…
      QVERIFY(ui::test::saveAndWait(session, project));
      // …removed by the clean save, as is the project's own.
      QVERIFY(session.autosave()->pendingRecoveries().empty());
      saved_state.emplace(doc);
      doc.undoStack()->push(new SetModelCommand(&doc, ModelClass::Affine));
      editSomething(doc, 5.0);
      QVERIFY(autosaveNow(session));
      edited_state.emplace(doc);
      QVERIFY(!(*edited_state == *saved_state));
      const QString recovery = session.autosave()->recoveryPathFor(project);
      QVERIFY(QFile::exists(recovery));
      // The recovery must be newer than the project whatever the file system's clock grain.
      QFile f(recovery);
      QVERIFY(f.open(QIODevice::ReadWrite));
      QVERIFY(f.setFileTime(QFileInfo(project).lastModified().addSecs(5),
                            QFileDevice::FileModificationTime));
      recovery_lock = recovery + ".lock";
      QVERIFY(QFile::exists(recovery_lock));
    }
    // The session is gone: its lock goes with it at once, not when the finished write's job is
    // torn down on its pool thread (a race that hid the offer below under load).
    QVERIFY(!QFile::exists(recovery_lock));
    {
      // Declined: the saved project opens.
      Document doc;
      Session session(&doc, nullptr);
      std::vector<RecoveryOffer> offers;
      configure(session, &offers, false);
      session.openProject(project);
      QCOMPARE(offers.size(), size_t{1});
      QCOMPARE(offers.front().project_path, QFileInfo(project).absoluteFilePath());
      QTRY_VERIFY_WITH_TIMEOUT(doc.photo() != nullptr, 20000);
      QVERIFY(State(doc) == *saved_state);
      QVERIFY(!doc.isModified());
    }
    {
      // Accepted: the edited state, under the project's name, modified.
      Document doc;
      Session session(&doc, nullptr);
      std::vector<RecoveryOffer> offers;
      configure(session, &offers, true);
      session.openProject(project);
      QCOMPARE(offers.size(), size_t{1});
      QTRY_VERIFY_WITH_TIMEOUT(doc.photo() != nullptr, 20000);
      QVERIFY(State(doc) == *edited_state);
      QVERIFY(doc.isModified());
      QCOMPARE(session.projectPath(), QFileInfo(project).absoluteFilePath());
      // Saving it makes the project current: no offer any more.
      QVERIFY(ui::test::saveOwnAndWait(session));
      QVERIFY(!session.autosave()->findRecovery(project));
    }
    {
      // A recovery OLDER than the project is not offered.
      Document doc;
      Session session(&doc, nullptr);
      std::vector<RecoveryOffer> offers;
      configure(session, &offers, true);
      session.openProject(project);
      QTRY_VERIFY_WITH_TIMEOUT(doc.photo() != nullptr, 20000);
      editSomething(doc, 9.0);
      QVERIFY(autosaveNow(session));
      QFile f(session.autosave()->recoveryPathFor(project));
      QVERIFY(f.open(QIODevice::ReadWrite));
      QVERIFY(f.setFileTime(QFileInfo(project).lastModified().addSecs(-60),
                            QFileDevice::FileModificationTime));
      f.close();
      QVERIFY(!session.autosave()->findRecovery(project));
      QVERIFY(session.autosave()->pendingRecoveries().empty());
      QVERIFY(offers.empty());
    }
  }

  void timerAutosavesAndWritesAreAtomic() {
    Document doc;
    Session session(&doc, nullptr);
    configure(session, nullptr, false);
    doc.reset(test::syntheticPhoto());
    editSomething(doc, 1.0);
    QSignalSpy saved(session.autosave(), &Autosave::saved);
    session.autosave()->setInterval(50);
    session.autosave()->start();
    QVERIFY(saved.wait(20000));
    session.autosave()->stop();
    QVERIFY(saved.front().at(0).toBool());
    // Only the recovery file itself and its lock: no temporary left beside it.
    const QString name = QFileInfo(session.autosave()->recoveryPathFor(QString())).fileName();
    const QStringList files = QDir(recovery_dir_).entryList(QDir::Files | QDir::Hidden, QDir::Name);
    QCOMPARE(files, (QStringList{name, name + ".lock"}));
    const Result<Project> back = Autosave::readRecovery(QDir(recovery_dir_).filePath(name));
    QVERIFY2(back.ok(), back.status.message.c_str());
    QVERIFY(back->pairs == doc.pairs());
    QVERIFY(back->depth_layers == doc.depth()->layers());
  }

  // Two windows, both untitled: each writes its own recovery file, neither offers the other's
  // live one, and a third start offers a file only once its owner is gone.
  void instancesKeepTheirOwnRecoveries() {
    auto doc_a = std::make_unique<Document>();
    auto a = std::make_unique<Session>(doc_a.get(), nullptr);
    configure(*a, nullptr, false);
    a->openPhoto(photo_);
    QTRY_VERIFY_WITH_TIMEOUT(doc_a->photo() != nullptr, 20000);
    editSomething(*doc_a, 1.0);
    QVERIFY(autosaveNow(*a));
    Document doc_b;
    Session b(&doc_b, nullptr);
    std::vector<RecoveryOffer> offers_b;
    configure(b, &offers_b, false);
    QVERIFY(!b.offerRecovery());  // A is alive: its autosave is not B's to recover
    QVERIFY(offers_b.empty());
    b.openPhoto(photo_);
    QTRY_VERIFY_WITH_TIMEOUT(doc_b.photo() != nullptr, 20000);
    editSomething(doc_b, 2.0);
    QVERIFY(autosaveNow(b));
    const QString file_a = a->autosave()->recoveryPathFor(QString());
    const QString file_b = b.autosave()->recoveryPathFor(QString());
    QVERIFY(file_a != file_b);
    QVERIFY(QFile::exists(file_a) && QFile::exists(file_b));
    const Result<Project> read_a = Autosave::readRecovery(file_a);
    QVERIFY(read_a.ok() && read_a->pairs == doc_a->pairs());  // not overwritten by B
    QVERIFY(a->autosave()->pendingRecoveries().empty());
    QVERIFY(b.autosave()->pendingRecoveries().empty());
    // A "dies" (no clean close): its file is offered to a newcomer, B's live one is not.
    const std::vector<Pair> pairs_a = doc_a->pairs();
    a.reset();
    doc_a.reset();
    Document doc_c;
    Session c(&doc_c, nullptr);
    configure(c, nullptr, true);
    const std::vector<RecoveryOffer> offers = c.autosave()->pendingRecoveries();
    QCOMPARE(offers.size(), size_t{1});
    QCOMPARE(offers.front().recovery_path, QFileInfo(file_a).absoluteFilePath());
    QVERIFY(c.offerRecovery());
    QTRY_VERIFY_WITH_TIMEOUT(doc_c.photo() != nullptr, 20000);
    QVERIFY(doc_c.pairs() == pairs_a);
    // Recovered by C, it is C's now: B is not offered it either.
    QVERIFY(b.autosave()->pendingRecoveries().empty());
  }

  // A lock left by a process that is gone (a crash) does not hide its recovery file.
  void deadOwnersRecoveryIsOffered() {
    QString file;
    {
      Document doc;
      Session session(&doc, nullptr);
      configure(session, nullptr, false);
      doc.reset(test::syntheticPhoto());
      editSomething(doc, 3.0);
      QVERIFY(autosaveNow(session));
      file = session.autosave()->recoveryPathFor(QString());
    }
    // The lock as a crashed studio leaves it: QLockFile's own format, with a pid now unused.
    QProcess gone;
    gone.start("true", {});
    QVERIFY(gone.waitForStarted());
    const qint64 dead_pid = gone.processId();
    QVERIFY(gone.waitForFinished());
    QByteArray text;
    {
      QLockFile lock(file + ".lock");
      QVERIFY(lock.tryLock(0));
      QFile f(file + ".lock");
      QVERIFY(f.open(QIODevice::ReadOnly));
      text = f.readAll();
    }
    text = QByteArray::number(dead_pid) + text.mid(text.indexOf('\n'));
    {
      QFile f(file + ".lock");
      QVERIFY(f.open(QIODevice::WriteOnly));
      f.write(text);
    }
    Document doc;
    Session session(&doc, nullptr);
    configure(session, nullptr, false);
    const std::vector<RecoveryOffer> offers = session.autosave()->pendingRecoveries();
    QCOMPARE(offers.size(), size_t{1});
    QCOMPARE(offers.front().recovery_path, QFileInfo(file).absoluteFilePath());
  }
};

QTEST_MAIN(TestAutosave)
#include "test_autosave.moc"
