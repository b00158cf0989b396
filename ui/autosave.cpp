// SPDX-License-Identifier: Apache-2.0
#include "ui/autosave.h"

#include "core/io/atomic_file.h"
#include "ui/background_job.h"

#include <QCoreApplication>
#include <QCryptographicHash>
#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QJsonDocument>
#include <QJsonObject>
#include <QLocale>
#include <QMessageBox>
#include <QRegularExpression>
#include <QStandardPaths>
#include <QUuid>

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

// Never stale by age: a studio may keep one recovery file for days. Stale only when the
// process that took it is gone (QLockFile checks its id and name on this host).
std::unique_ptr<QLockFile> lockFor(const QString& recovery_path) {
  auto lock = std::make_unique<QLockFile>(recovery_path + QStringLiteral(".lock"));
  lock->setStaleLockTime(0);
  return lock;
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
      dir_(QStandardPaths::writableLocation(QStandardPaths::AppLocalDataLocation) + "/recovery"),
      instance_(QString::number(QCoreApplication::applicationPid()) + "-" +
                QUuid::createUuid().toString(QUuid::Id128).left(8)) {
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
// at application exit the job helper waits for it. Otherwise nobody works on this instance's
// recoveries any more, so their locks go now: the finished job's functor may still hold the
// shared state for a moment on its pool thread, and another session must not see them taken.
Autosave::~Autosave() {
  const std::lock_guard<std::mutex> lock(stale_->mutex);
  if (!stale_->writing) stale_->locks.clear();
}

void Autosave::setProjectPath(const QString& path) {
  const QString abs = path.isEmpty() ? QString() : QFileInfo(path).absoluteFilePath();
  if (abs == project_path_) return;
  // The untitled session became a project (or another project opened): its old recovery is
  // superseded by the next autosave under the new name.
  project_path_ = abs;
}

namespace {

// A recovery file's name without the instance part: "untitled" or "<base>-<hash>".
QString recoveryStem(const QString& project_path) {
  if (project_path.isEmpty()) return QStringLiteral("untitled");
  const QString abs = QFileInfo(project_path).absoluteFilePath();
  const QString hash = QString::fromLatin1(
      QCryptographicHash::hash(abs.toUtf8(), QCryptographicHash::Sha1).toHex().left(12));
  return QFileInfo(abs).completeBaseName() + "-" + hash;
}

}  // namespace

QString Autosave::recoveryPathFor(const QString& project_path) const {
  return QDir(dir_).filePath(recoveryStem(project_path) + "-" + instance_ + "." +
                             kProjectExtension);
}

QStringList Autosave::recoveryFilesFor(const QString& project_path) const {
  const QString stem = recoveryStem(project_path);
  QStringList paths;
  // The instance part is "<pid>-<8 hex>"; the earlier naming had none.
  static const QRegularExpression instance(QStringLiteral("^-[0-9]+-[0-9a-f]{8}$"));
  const QDir dir(dir_);
  for (const QString& name :
       dir.entryList({stem + "*." + kProjectExtension}, QDir::Files, QDir::Name)) {
    const QString rest = QFileInfo(name).completeBaseName().mid(stem.size());
    if (rest.isEmpty() || instance.match(rest).hasMatch()) paths << dir.filePath(name);
  }
  return paths;
}

bool Autosave::ownedElsewhere(const QString& path) const {
  {
    const std::lock_guard<std::mutex> lock(stale_->mutex);
    if (stale_->locks.count(path)) return false;  // this instance's own (or adopted)
  }
  if (path == recoveryPathFor(project_path_) || path == recoveryPathFor(QString()))
    return false;  // about to be this instance's: never offered to itself below
  const std::unique_ptr<QLockFile> probe = lockFor(path);
  // Taken: nobody holds it (a stale lock of a dead owner is removed by tryLock). The probe is
  // released at once; adopt() takes it for good.
  return !probe->tryLock(0);
}

std::optional<RecoveryOffer> Autosave::findRecovery(const QString& project_path) const {
  std::optional<RecoveryOffer> newest;
  for (const QString& path : recoveryFilesFor(project_path)) {
    // This instance's own live file is not a recovery: it is the work in progress.
    if (path == recoveryPathFor(project_path_) || path == recoveryPathFor(QString())) continue;
    const QFileInfo recovery(path);
    if (!project_path.isEmpty()) {
      const QFileInfo project(project_path);
      if (project.isFile() && project.lastModified() >= recovery.lastModified()) continue;
    }
    if (newest && newest->saved_at >= recovery.lastModified()) continue;
    if (ownedElsewhere(path)) continue;  // a studio still working on it
    newest = RecoveryOffer{
        recovery.absoluteFilePath(),
        project_path.isEmpty() ? QString() : QFileInfo(project_path).absoluteFilePath(),
        recovery.lastModified()};
  }
  return newest;
}

std::vector<RecoveryOffer> Autosave::pendingRecoveries() const {
  std::vector<RecoveryOffer> offers;
  const QFileInfoList files =
      QDir(dir_).entryInfoList({QStringLiteral("*.") + kProjectExtension}, QDir::Files);
  QStringList seen;
  for (const QFileInfo& f : files) {
    const QString of = recoveryOf(f.absoluteFilePath());
    // Only files that are a project's recovery by name (not stray copies).
    if (!recoveryFilesFor(of).contains(f.absoluteFilePath()) || seen.contains(of)) continue;
    seen << of;
    if (auto offer = findRecovery(of)) offers.push_back(*offer);
  }
  std::sort(offers.begin(), offers.end(),
            [](const RecoveryOffer& a, const RecoveryOffer& b) { return a.saved_at > b.saved_at; });
  return offers;
}

void Autosave::adopt(const QString& recovery_path) {
  std::unique_ptr<QLockFile> lock = lockFor(recovery_path);
  if (!lock->tryLock(0)) return;  // another instance took it first: it stays theirs
  const std::lock_guard<std::mutex> guard(stale_->mutex);
  stale_->locks[recovery_path] = std::move(lock);
  stale_->adopted << recovery_path;
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
        {
          // Locked before the first write, so no other instance offers the file meanwhile.
          const std::lock_guard<std::mutex> lock(stale->mutex);
          if (!stale->locks.count(path)) {
            std::unique_ptr<QLockFile> file_lock = lockFor(path);
            QDir().mkpath(QFileInfo(path).absolutePath());
            if (file_lock->tryLock(0)) stale->locks[path] = std::move(file_lock);
          }
        }
        const QString error = writeFile(path, bytes);
        // Removed while this write was in flight: the write must not bring the file back, even
        // when the Autosave is gone by now (a clean close), so the worker removes it.
        const std::lock_guard<std::mutex> lock(stale->mutex);
        for (const QString& removed : stale->paths) {
          QFile::remove(removed);
          stale->locks.erase(removed);
        }
        stale->paths.clear();
        // An adopted recovery is superseded by this instance's own copy once one is written.
        if (error.isEmpty()) {
          for (const QString& adopted : stale->adopted) {
            if (adopted == path) continue;
            QFile::remove(adopted);
            stale->locks.erase(adopted);
          }
          stale->adopted.clear();
        }
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
  QStringList paths{recoveryPathFor(project_path), recoveryPathFor(QString())};
  paths += stale_->adopted;  // recovered from: saved or closed now
  stale_->adopted.clear();
  for (const QString& path : paths) {
    QFile::remove(path);
    if (stale_->writing)
      stale_->paths << path;  // the write in flight may re-create it
    else
      stale_->locks.erase(path);
  }
}

}  // namespace artcam::ui
