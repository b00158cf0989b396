// SPDX-License-Identifier: Apache-2.0
// The temporaries of atomic saves: removeLiveTemporaries (what the
// CLI's SIGINT handler calls) unlinks a save in flight and leaves the target as it was, stale
// temporaries of a process that is gone are removed by the next save to that name while a
// live process's are kept, and isAtomicTemporaryName recognises exactly the writer's names.
#include "core/io/atomic_file.h"

#include <QtTest/QtTest>

#include <QDir>
#include <QFile>
#include <QProcess>
#include <QTemporaryDir>

#include <signal.h>

#include <fstream>

using namespace artcam;

namespace {

std::string contents(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), {});
}

QStringList entries(const QString& folder) {
  return QDir(folder).entryList(QDir::Files | QDir::Hidden | QDir::NoDotAndDotDot, QDir::Name);
}

void touch(const QString& path) {
  QFile f(path);
  QVERIFY(f.open(QIODevice::WriteOnly));
  f.write("partial");
}

// The id of a process that has exited (and been reaped), so no process has it now — unless
// the system reuses it at once, which the caller checks with kill(pid, 0).
qint64 deadPid() {
  QProcess p;
  p.start("/bin/true", {});
  if (!p.waitForStarted(30000)) return 0;
  const qint64 pid = p.processId();  // 0 again once it has finished
  p.waitForFinished(30000);
  return pid;
}

}  // namespace

class TestAtomicTemporaries : public QObject {
  Q_OBJECT

 private slots:
  void interruptedSaveLeavesTargetAndNoTemporary() {
    QTemporaryDir dir;
    const std::string path = dir.filePath("notes.txt").toStdString();
    QVERIFY(writeTextAtomically(path, "old").ok);
    std::string seen_temp;
    const Status s = writeAtomically(path, [&](const std::string& temp) {
      std::ofstream(temp) << "half of the new";
      seen_temp = temp;
      removeLiveTemporaries();  // what a signal arriving here does
      return Status::success();
    });
    QVERIFY(!s.ok);
    QVERIFY(!seen_temp.empty());
    QVERIFY(!QFile::exists(QString::fromStdString(seen_temp)));
    QCOMPARE(contents(path), std::string("old"));
    QCOMPARE(entries(dir.path()), QStringList{"notes.txt"});
  }

  void finishedSavesAreNotTouchedByALaterSignal() {
    QTemporaryDir dir;
    const std::string path = dir.filePath("a.txt").toStdString();
    QVERIFY(writeTextAtomically(path, "kept").ok);
    removeLiveTemporaries();
    QCOMPARE(contents(path), std::string("kept"));
  }

  void staleTemporariesOfDeadWritersAreRemoved() {
    QTemporaryDir dir;
    const qint64 dead = deadPid();
    QVERIFY(dead > 0);
    QVERIFY(::kill(static_cast<pid_t>(dead), 0) != 0);  // gone (not reused meanwhile)
    const QString stale = dir.filePath(QStringLiteral(".photo.tmp-%1-3.png").arg(dead));
    const QString live =
        dir.filePath(QStringLiteral(".photo.tmp-%1-0.png").arg(QCoreApplication::applicationPid()));
    const QString other_target = dir.filePath(QStringLiteral(".other.tmp-%1-0.png").arg(dead));
    touch(stale);
    touch(live);
    touch(other_target);
    QCOMPARE(removeStaleTemporaries(dir.filePath("photo.png").toStdString()), 1);
    QVERIFY(!QFile::exists(stale));
    QVERIFY(QFile::exists(live));          // its writer (this process) is alive
    QVERIFY(QFile::exists(other_target));  // another target's: left to its own next save
    // A save to the other name cleans its own stale temporary.
    QVERIFY(writeTextAtomically(dir.filePath("other.png").toStdString(), "x").ok);
    QVERIFY(!QFile::exists(other_target));
  }

  void temporaryNames() {
    QVERIFY(isAtomicTemporaryName(".photo.tmp-123-0.png"));
    QVERIFY(isAtomicTemporaryName(".a.b.tmp-9-12.tiff"));
    QVERIFY(isAtomicTemporaryName(".notes.tmp-1-2"));
    QVERIFY(!isAtomicTemporaryName("photo.tmp-123-0.png"));  // not hidden
    QVERIFY(!isAtomicTemporaryName(".photo.png"));
    QVERIFY(!isAtomicTemporaryName(".photo.tmp-x-0.png"));
    QVERIFY(!isAtomicTemporaryName("photo.png"));
  }
};

QTEST_GUILESS_MAIN(TestAtomicTemporaries)
#include "test_atomic_temporaries.moc"
