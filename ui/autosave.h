// SPDX-License-Identifier: Apache-2.0
// Autosave and crash recovery. Every `interval` the modified document is
// written as a project to a RECOVERY file (atomically, on a worker thread: the GUI thread never
// blocks on file I/O); a clean save or close removes it. A recovery file left behind means the
// studio did not close cleanly: on the next start (or when its project is opened) the user is
// offered to recover it when it is newer than the saved project (or the project was never
// saved). The prompt is injectable so tests run without modal dialogs. The interval is one
// minute, or ARTCAM_AUTOSAVE_INTERVAL_MS (≥ 100) from the environment.
//
// Recovery files live in one folder (default: <AppLocalDataLocation>/recovery), one per project
// and studio instance: "<project base name>-<12 hex of SHA-1 of its absolute path>-<instance>
// .artcamproj", or "untitled-<instance>.artcamproj" for a session not yet saved, where
// <instance> is unique to this Autosave (process id and a random part). Each is an ordinary
// project file (paths absolute) plus "recovery_of": the project it stands for ("" when
// untitled). Two windows thus never write each other's safety copy.
//
// Each recovery file is locked by its writer while it lives (QLockFile "<file>.lock", taken by
// the first write, never stale by age): a file whose lock is held belongs to a studio that is
// still running and is never offered. Only a file whose owner is gone (its lock left by a dead
// process, or no lock) is offered; recovering it adopts it (its lock taken), and it goes with
// this instance's next recovery write or clean save. Files of the earlier naming (no instance
// part) are offered the same way.
#pragma once

#include "ui/project_file.h"

#include <QDateTime>
#include <QLockFile>
#include <QObject>
#include <QString>
#include <QStringList>
#include <QTimer>

class QWidget;

#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <vector>

namespace artcam::ui {

struct RecoveryOffer {
  QString recovery_path;  // the recovery file
  QString project_path;   // the project it stands for; empty: never saved
  QDateTime saved_at;     // the recovery file's modification time
};

class Autosave : public QObject {
  Q_OBJECT

 public:
  static constexpr int kDefaultIntervalMs = 60 * 1000;

  // `snapshot` returns the current state as a project, or nothing when there is nothing to
  // keep (no photo, or no unsaved change).
  using Snapshot = std::function<std::optional<Project>()>;
  // Returns true to recover. None set: never (the Session installs dialogPrompt when it is
  // interactive).
  using Prompt = std::function<bool(const RecoveryOffer&)>;
  static Prompt dialogPrompt(QWidget* parent);

  explicit Autosave(Snapshot snapshot, QObject* parent = nullptr);
  ~Autosave() override;  // releases its locks (a write in flight keeps its own to the end)

  void setRecoveryDir(const QString& dir) { dir_ = dir; }
  const QString& recoveryDir() const { return dir_; }
  void setInterval(int ms) { timer_.setInterval(ms); }
  void setPrompt(Prompt prompt) { prompt_ = std::move(prompt); }
  // The project whose recovery file autosaves write to ("" while untitled).
  void setProjectPath(const QString& path);
  // This instance's recovery file for `project_path` ("" for untitled).
  QString recoveryPathFor(const QString& project_path) const;

  // The newest recovery for `project_path` whose owner is gone, when it is newer than the
  // project (or it was never saved).
  std::optional<RecoveryOffer> findRecovery(const QString& project_path) const;
  // All such recoveries in the folder, newest first (at start-up).
  std::vector<RecoveryOffer> pendingRecoveries() const;
  // Takes over a recovery whose owner is gone (its lock), so no other instance offers it while
  // this one works on it; it is removed by this instance's next write or clean save.
  void adopt(const QString& recovery_path);
  bool ask(const RecoveryOffer& offer) const { return prompt_ && prompt_(offer); }

  // Reads a recovery file as a project (recovery_of is not part of Project).
  static Result<Project> readRecovery(const QString& recovery_path);

 public slots:
  void start() { timer_.start(); }
  void stop() { timer_.stop(); }
  // Writes a recovery file now if the snapshot has something (the timer calls this).
  void saveNow();
  // After a clean save or close: the recovery of `project_path` (and of the untitled session)
  // is no longer needed.
  void removeRecovery(const QString& project_path);

 signals:
  // From the GUI thread after each write: ok, and the message naming the cause when not.
  void saved(bool ok, const QString& message);

 private:
  Snapshot snapshot_;
  Prompt prompt_;
  QString dir_;
  QString project_path_;
  QTimer timer_;
  bool writing_ = false;  // a write in flight (background_job.h)
  // Whether `path`'s lock is held by a live studio other than this instance.
  bool ownedElsewhere(const QString& path) const;
  // The recovery files for `project_path` by any instance (its name with any instance part).
  QStringList recoveryFilesFor(const QString& project_path) const;

  QString instance_;  // this Autosave's part of its recovery files' names
  // Recovery files removed while a write was in flight; that write removes them again. The
  // locks of this instance's recovery files (and of adopted ones), taken by the writes.
  struct StaleRecoveries {
    std::mutex mutex;
    bool writing = false;
    QStringList paths;
    std::map<QString, std::unique_ptr<QLockFile>> locks;
    QStringList adopted;
  };
  std::shared_ptr<StaleRecoveries> stale_ = std::make_shared<StaleRecoveries>();
  bool again_ = false;         // a save was asked for while one was in flight
};

}  // namespace artcam::ui
