// SPDX-License-Identifier: Apache-2.0
// The studio killed mid-edit loses no work: artcam-studio opens a photo, an
// undoable edit imports a camera with 20 matches (hidden test hook in app/studio_main.cpp),
// the autosave runs on a short interval (ARTCAM_AUTOSAVE_INTERVAL_MS), and the process is
// SIGKILLed. The recovery file must be there, load as a project with the photo and the 20
// pairs read independently from the .artcam file, not be offered to another studio while the
// first one runs, and be offered at the next start once it is gone.
#include "ui/autosave.h"
#include "ui/project_file.h"

#include <QtTest/QtTest>

#include <QDirIterator>
#include <QFile>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QProcess>
#include <QTemporaryDir>

#include "core/io/image_io.h"

using namespace artcam;

class TestKillRecovery : public QObject {
  Q_OBJECT

  QTemporaryDir dir_;

  QString findRecovery() const {
    QDirIterator it(dir_.filePath("data"), {"*.artcamproj"}, QDir::Files,
                    QDirIterator::Subdirectories);
    return it.hasNext() ? it.next() : QString();
  }

 private slots:
  void killedStudioLeavesALoadableRecovery() {
    QVERIFY(dir_.isValid());
    // A 600x400 photo: the sample camera's frames, so its matches are these pixels as stored.
    ImageF photo(600, 400, 3);
    for (size_t k = 0; k < photo.data.size(); ++k)
      photo.data[k] = static_cast<float>(k % 97) / 97.0f;
    const QString photo_path = dir_.filePath("photo.png");
    QVERIFY(writeImage(photo_path.toStdString(), photo).ok);
    const QString camera = QStringLiteral(ARTCAM_RESOURCES_DIR "/sample.artcam");

    QProcess studio;
    QProcessEnvironment env = QProcessEnvironment::systemEnvironment();
    env.insert("QT_QPA_PLATFORM", "offscreen");
    env.insert("XDG_DATA_HOME", dir_.filePath("data"));      // the recovery folder lives here
    env.insert("XDG_CONFIG_HOME", dir_.filePath("config"));  // recent files
    env.insert("ARTCAM_AUTOSAVE_INTERVAL_MS", "200");
    env.insert("ARTCAM_STUDIO_TEST_IMPORT", camera);
    studio.setProcessEnvironment(env);
    studio.start(QStringLiteral(ARTCAM_STUDIO_PATH), {photo_path});
    QVERIFY(studio.waitForStarted());
    QElapsedTimer clock;
    clock.start();  // a guard against hanging, not a timing check
    while (findRecovery().isEmpty() && studio.state() == QProcess::Running &&
           clock.elapsed() < 120000)
      QThread::msleep(10);
    QCOMPARE(studio.state(), QProcess::Running);
    const QString recovery = findRecovery();
    QVERIFY2(!recovery.isEmpty(), qPrintable(QString::fromUtf8(studio.readAllStandardError())));
    {
      // While that studio runs its recovery file is its own: another studio is not offered it.
      ui::Autosave other([] { return std::optional<ui::Project>(); });
      other.setRecoveryDir(QFileInfo(recovery).absolutePath());
      QVERIFY(other.pendingRecoveries().empty());
      QCOMPARE(studio.state(), QProcess::Running);
    }
    studio.kill();  // SIGKILL mid-edit: no clean close, no save prompt
    QVERIFY(studio.waitForFinished(30000));
    QCOMPARE(studio.exitStatus(), QProcess::CrashExit);

    // The matches as the .artcam file states them, read here with Qt's JSON reader.
    QFile file(camera);
    QVERIFY(file.open(QIODevice::ReadOnly));
    const QJsonArray matches =
        QJsonDocument::fromJson(file.readAll()).object()["matches"].toArray();
    QCOMPARE(matches.size(), 20);

    const Result<ui::Project> project = ui::Autosave::readRecovery(recovery);
    QVERIFY2(project.ok(), project.status.message.c_str());
    QCOMPARE(QFileInfo(project->photo_path).canonicalFilePath(),
             QFileInfo(photo_path).canonicalFilePath());
    QCOMPARE(static_cast<int>(project->pairs.size()), 20);
    for (int k = 0; k < 20; ++k) {
      const QJsonObject m = matches[k].toObject();
      const QJsonArray s = m["source"].toArray(), t = m["target"].toArray();
      QVERIFY(!s.isEmpty() && !t.isEmpty());
      QCOMPARE(project->pairs[static_cast<size_t>(k)].source.x(), s[0].toDouble());
      QCOMPARE(project->pairs[static_cast<size_t>(k)].source.y(), s[1].toDouble());
      QCOMPARE(project->pairs[static_cast<size_t>(k)].target.x(), t[0].toDouble());
      QCOMPARE(project->pairs[static_cast<size_t>(k)].target.y(), t[1].toDouble());
    }

    // The next start offers it (the studio's own recovery logic, pointed at the same folder).
    ui::Autosave autosave([] { return std::optional<ui::Project>(); });
    autosave.setRecoveryDir(QFileInfo(recovery).absolutePath());
    const auto offers = autosave.pendingRecoveries();
    QCOMPARE(static_cast<int>(offers.size()), 1);
    QCOMPARE(offers.front().recovery_path, QFileInfo(recovery).absoluteFilePath());
    QVERIFY(offers.front().project_path.isEmpty());  // an untitled session
  }
};

QTEST_MAIN(TestKillRecovery)
#include "test_kill_recovery.moc"
