// SPDX-License-Identifier: Apache-2.0
#include "ui/autosave.h"

#include "core/io/atomic_file.h"
#include "ui/background_job.h"

#include <QCryptographicHash>
#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QJsonDocument>
#include <QJsonObject>
#include <QLocale>
#include <QMessageBox>
#include <QStandardPaths>

#include <algorithm>
#include <memory>
#include <mutex>

namespace artcam::ui {
namespace {

const char kRecoveryOf[] = "recovery_of";

// Written on the worker thread by core's atomic writer (write aside, fsync, rename): a studio
// killed mid-write leaves the previous recovery file whole, and its hidden temporary
// (".name.tmp-<pid>-<n>.artcamproj", never listed as a recovery) is removed by the next
// autosave once that process is gone (core/io/atomic_file.h).
QString writeFile(const QString& path, const QByteArray& bytes) {
  QDir().mkpath(QFileInfo(path).absolutePath());
  const Status s = writeTextAtomically(QFile::encodeName(path).toStdString(), bytes.toStdString());
  return s ? QString() : QString::fromStdString(s.message);
}

// Tests (a short interval to kill the studio after its autosave) and users who want another
// rhythm: ARTCAM_AUTOSAVE_INTERVAL_MS, at least 100 ms.
int intervalFromEnvironment() {
  bool ok = false;
  const int ms = qEnvironmentVariableIntValue("ARTCAM_AUTOSAVE_INTERVAL_MS", &ok);
  return ok && ms >= 100 ? ms : Autosave::kDefaultIntervalMs;
}

QString recoveryOf(const QString& recovery_path) {
  QFile file(recovery_path);
  if (!file.open(QIODevice::ReadOnly)) return {};
  return QJsonDocument::fromJson(file.readAll()).object()[kRecoveryOf].toString();
}

}  // namespace

Autosave::Autosave(Snapshot snapshot, QObject* parent)
    : QObject(parent),
      snapshot_(std::move(snapshot)),
      dir_(QStandardPaths::writableLocation(QStandardPaths::AppLocalDataLocation) + "/recovery") {
  timer_.setInterval(intervalFromEnvironment());
  connect(&timer_, &QTimer::timeout, this, &Autosave::saveNow);
}

Autosave::Prompt Autosave::dialogPrompt(QWidget* parent) {
  return [parent](const RecoveryOffer& offer) {
    const QString what = offer.project_path.isEmpty()
                             ? tr("an unsaved session")
                             : QFileInfo(offer.project_path).fileName();
    return QMessageBox::question(
               parent, tr("Recover work"),
               tr("ARTcam Studio did not close cleanly. A recovery copy of %1 from %2 is newer "
                  "than the saved project. Recover it?")
                   .arg(what, QLocale().toString(offer.saved_at, QLocale::ShortFormat)),
               QMessageBox::Yes | QMessageBox::No, QMessageBox::Yes) == QMessageBox::Yes;
  };
}

// A write in flight finishes on its own (atomic, and it removes what was removed meanwhile);
// at application exit the job helper waits for it.
Autosave::~Autosave() = default;

void Autosave::setProjectPath(const QString& path) {
  const QString abs = path.isEmpty() ? QString() : QFileInfo(path).absoluteFilePath();
  if (abs == project_path_) return;
  // The untitled session became a project (or another project opened): its old recovery is
  // superseded by the next autosave under the new name.
  project_path_ = abs;
}

QString Autosave::recoveryPathFor(const QString& project_path) const {
  if (project_path.isEmpty()) return QDir(dir_).filePath(QStringLiteral("untitled.artcamproj"));
  const QString abs = QFileInfo(project_path).absoluteFilePath();
  const QString hash = QString::fromLatin1(
      QCryptographicHash::hash(abs.toUtf8(), QCryptographicHash::Sha1).toHex().left(12));
  return QDir(dir_).filePath(QFileInfo(abs).completeBaseName() + "-" + hash + "." +
                             kProjectExtension);
}

std::optional<RecoveryOffer> Autosave::findRecovery(const QString& project_path) const {
  const QFileInfo recovery(recoveryPathFor(project_path));
  if (!recovery.isFile()) return std::nullopt;
  if (!project_path.isEmpty()) {
    const QFileInfo project(project_path);
    if (project.isFile() && project.lastModified() >= recovery.lastModified()) return std::nullopt;
  }
  return RecoveryOffer{recovery.absoluteFilePath(),
                       project_path.isEmpty() ? QString() : QFileInfo(project_path).absoluteFilePath(),
                       recovery.lastModified()};
}

std::vector<RecoveryOffer> Autosave::pendingRecoveries() const {
  std::vector<RecoveryOffer> offers;
  const QFileInfoList files =
      QDir(dir_).entryInfoList({QStringLiteral("*.") + kProjectExtension}, QDir::Files);
  for (const QFileInfo& f : files) {
    const QString of = recoveryOf(f.absoluteFilePath());
    // Only files that are this project's recovery by name (not stray copies).
    if (recoveryPathFor(of) != f.absoluteFilePath()) continue;
    if (auto offer = findRecovery(of)) offers.push_back(*offer);
  }
  std::sort(offers.begin(), offers.end(),
            [](const RecoveryOffer& a, const RecoveryOffer& b) { return a.saved_at > b.saved_at; });
  return offers;
}

Result<Project> Autosave::readRecovery(const QString& recovery_path) {
  return readProject(recovery_path);
}

void Autosave::saveNow() {
  if (writing_) {
    again_ = true;  // one more after the write in flight, with the newest state
    return;
  }
  const std::optional<Project> project = snapshot_();
  if (!project) return;
  const QString path = recoveryPathFor(project_path_);
  // Serialised here (the document lives on this thread); written on the worker.
  QJsonObject root = QJsonDocument::fromJson(projectToJson(*project, path)).object();
  root[kRecoveryOf] = project_path_;
  const QByteArray bytes = QJsonDocument(root).toJson(QJsonDocument::Compact);
  writing_ = true;
  {
    const std::lock_guard<std::mutex> lock(stale_->mutex);
    stale_->writing = true;
  }
  runInBackground(
      this,
      [path, bytes, stale = stale_](JobContext&) {
        const QString error = writeFile(path, bytes);
        // Removed while this write was in flight: the write must not bring the file back, even
        // when the Autosave is gone by now (a clean close), so the worker removes it.
        const std::lock_guard<std::mutex> lock(stale->mutex);
        for (const QString& removed : stale->paths) QFile::remove(removed);
        stale->paths.clear();
        stale->writing = false;
        return error;
      },
      [this](JobOutcome<QString> outcome) {
        writing_ = false;
        const QString error = outcome.value ? *outcome.value : outcome.error;
        emit saved(error.isEmpty(), error);
        if (again_) {
          again_ = false;
          saveNow();
        }
      });
}

void Autosave::removeRecovery(const QString& project_path) {
  again_ = false;
  const std::lock_guard<std::mutex> lock(stale_->mutex);
  for (const QString& path : {recoveryPathFor(project_path), recoveryPathFor(QString())}) {
    QFile::remove(path);
    if (stale_->writing) stale_->paths << path;  // the write in flight may re-create it
  }
}

}  // namespace artcam::ui
