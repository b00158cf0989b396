// SPDX-License-Identifier: Apache-2.0
// Atomic saves: the target is replaced whole or not at all, and no temporary is left behind.
#include "core/io/atomic_file.h"

#include <QtTest/QtTest>

#include <fstream>
#include <stdexcept>

using namespace artcam;

namespace {

std::string contents(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), {});
}

QStringList entries(const QTemporaryDir& dir) {
  return QDir(dir.path())
      .entryList(QDir::AllEntries | QDir::Hidden | QDir::NoDotAndDotDot, QDir::Name);
}

}  // namespace

class TestAtomicFile : public QObject {
  Q_OBJECT

 private slots:
  void writesAndReplaces() {
    QTemporaryDir dir;
    const std::string path = dir.filePath("notes.txt").toStdString();
    QVERIFY(writeTextAtomically(path, "first").ok);
    QCOMPARE(contents(path), std::string("first"));
    QVERIFY(writeTextAtomically(path, "second, longer").ok);
    QCOMPARE(contents(path), std::string("second, longer"));
    QCOMPARE(entries(dir), QStringList{"notes.txt"});
  }

  void temporaryIsHiddenBesideTheTargetWithItsExtension() {
    QTemporaryDir dir;
    const std::string path = dir.filePath("out.png").toStdString();
    std::string seen;
    const Status status = writeAtomically(path, [&](const std::string& temp) {
      seen = temp;
      std::ofstream(temp) << "x";
      return Status::success();
    });
    QVERIFY(status.ok);
    const QFileInfo info(QString::fromStdString(seen));
    QCOMPARE(info.absolutePath(), QDir(dir.path()).absolutePath());
    QVERIFY2(info.fileName().startsWith(".out.tmp-") && info.fileName().endsWith(".png"),
             seen.c_str());
  }

  void failedWriteLeavesThePreviousFileUntouched() {
    QTemporaryDir dir;
    const std::string path = dir.filePath("cam.artcam").toStdString();
    QVERIFY(writeTextAtomically(path, "precious").ok);
    const Status status = writeAtomically(path, [&](const std::string& temp) {
      std::ofstream(temp) << "half a fi";  // a partial write, then the writer gives up
      return Status::failure(path + ": cannot write: disk on fire");
    });
    QVERIFY(!status.ok);
    QCOMPARE(status.message, path + ": cannot write: disk on fire");
    QCOMPARE(contents(path), std::string("precious"));
    QCOMPARE(entries(dir), QStringList{"cam.artcam"});
  }

  void throwingWriterCleansUp() {
    QTemporaryDir dir;
    const std::string path = dir.filePath("a.txt").toStdString();
    QVERIFY_THROWS_EXCEPTION(std::runtime_error,
                             writeAtomically(path, [](const std::string& temp) -> Status {
                               std::ofstream(temp) << "partial";
                               throw std::runtime_error("boom");
                             }));
    QVERIFY(entries(dir).isEmpty());
  }

  void missingFolderIsReported() {
    QTemporaryDir dir;
    const std::string path = dir.filePath("no/such/folder/x.txt").toStdString();
    const Status status = writeTextAtomically(path, "x");
    QVERIFY(!status.ok);
    QVERIFY2(status.message.rfind(path + ": cannot write: ", 0) == 0, status.message.c_str());
  }

  void keepsPermissionsOfTheReplacedFile() {
    QTemporaryDir dir;
    const QString path = dir.filePath("script.sh");
    QVERIFY(writeTextAtomically(path.toStdString(), "#!/bin/sh\n").ok);
    QVERIFY(QFile::setPermissions(path, QFile::ReadOwner | QFile::WriteOwner | QFile::ExeOwner));
    QVERIFY(writeTextAtomically(path.toStdString(), "#!/bin/sh\necho hi\n").ok);
    QVERIFY(QFile::permissions(path) & QFile::ExeOwner);
  }
};

QTEST_GUILESS_MAIN(TestAtomicFile)
#include "test_atomic_file.moc"
