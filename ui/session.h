// SPDX-License-Identifier: Apache-2.0
// File operations of one editing session: open photo (off the GUI thread, with progress),
// open/save project (atomic), import/export .artcam, export the warped image (worker with a
// cancellable progress dialog), recent files, and the save prompt on close. Errors are shown
// as dialogs naming the file and the cause. MainWindow only wires actions to these slots.
//
// Every read and write runs as a one-shot job (background_job.h): the GUI thread only
// serialises the document before a write and applies what a read brought. So a save, an
// .artcam import or export and a depth map export have finished only when their signal comes
// (projectSaved, fileWritten, importFinished), not when the call returns.
//
// A project whose photo is missing (it moved) is not refused: the locate prompt names the
// project and the photo and returns the photo's new place (a file dialog when interactive);
// a photo of another size than the project's pixels were made on is refused naming both, and
// the located one opens the project with everything in it, marked modified, so the next save
// stores the new place.
#pragma once

#include "core/lens/lens_camera.h"
#include "core/lens/lens_database.h"
#include "ui/cloud_view.h"
#include "ui/export_job.h"
#include "ui/image_loader.h"
#include "ui/project_file.h"

#include <QObject>
#include <QPointer>
#include <QString>
#include <QStringList>

#include <functional>
#include <memory>
#include <optional>
#include <vector>

class QWidget;

namespace artcam::ui {

class Autosave;
class Document;
struct RecoveryOffer;

class Session : public QObject {
  Q_OBJECT

 public:
  static constexpr int kMaxRecentFiles = 10;

  Session(Document* document, QWidget* dialog_parent, QObject* parent = nullptr);
  ~Session() override;

  // Supplies the view state to save; MainWindow sets it from the canvas and preview.
  void setViewStateProvider(std::function<ViewState()> provider) {
    view_state_ = std::move(provider);
  }
  // A studio mode's own state in the project (Project::parts[name]): `save` returns it (empty:
  // nothing to keep), `load` restores it after the photo of an opened or recovered project is
  // in the document (an empty object when the project has none). Not undoable steps.
  struct ProjectPart {
    QString name;
    std::function<QJsonObject()> save;
    std::function<void(const QJsonObject&)> load;
  };
  void addProjectPart(ProjectPart part) { parts_.push_back(std::move(part)); }
  // When false, errors are only emitted (errorOccurred) rather than shown modally (tests).
  void setInteractive(bool interactive) { interactive_ = interactive; }
  // Asked when an opened project's photo is missing: (project path, photo path) → the photo's
  // new place, or empty to give up. Default: a Locate… dialog when interactive, else give up.
  using LocatePrompt = std::function<QString(const QString&, const QString&)>;
  void setLocatePrompt(LocatePrompt prompt) { locate_prompt_ = std::move(prompt); }
  // A project save is being written (saveProjectTo until projectSaved).
  bool isSaving() const { return saving_; }

  const QString& projectPath() const { return project_path_; }
  QString displayName() const;
  bool isLoading() const { return loader_ != nullptr; }
  // Opening a JPEG: its whole read waits for releaseWholeRead() after the first look
  // (ImageLoader::setHoldWholeRead); MainWindow releases it when the first look's preview is in.
  void setHoldWholeRead(bool on) { hold_whole_read_ = on; }
  void releaseWholeRead() {
    if (loader_) loader_->releaseWholeRead();
  }
  QStringList recentFiles() const;
  Autosave* autosave() const { return autosave_; }
  // The state a save would write (no view state when no provider is set).
  std::optional<Project> currentProject() const;

 public slots:
  // Decides by extension: project, .artcam (import) or photo.
  void openPath(const QString& path);
  void openPhoto(const QString& path);
  void openProject(const QString& path);
  // Starts the save (false when there is nothing to save or a save is running); projectSaved
  // says how it ended.
  bool saveProjectTo(const QString& path);
  // Read off the GUI thread, applied as one undo step; importFinished says how it ended.
  void importArtcam(const QString& path);
  // Starts the write (false when refused at once); fileWritten says how it ended.
  bool exportArtcam(const QString& path);
  void exportImage(const QString& path);
  // Writes the document's depth (painted planes over the map) at the photo's size as a float
  // EXR of depth in channel Z, 0 where there is none (what Load Depth Map and artcam --depth
  // read back). Rasterised here, written off the GUI thread; fileWritten says how it ended.
  bool exportDepthMap(const QString& path);
  // Crop or fill, JPEG quality, bit depth and size of the next exports (the export dialog's).
  const ExportOptions& exportOptions() const { return export_options_; }
  // Remembered across sessions (QSettings, export_settings.h).
  void setExportOptions(const ExportOptions& options);
  // Stops a running export at its next tile (the progress dialog's Cancel does the same).
  void cancelExport();
  // Loads a depth map file on a worker thread; when it arrives it becomes an undoable edit.
  void loadDepthMap(const QString& path, const artcam::DepthFileOptions& options);
  // Depth from a rectified stereo pair (core/depth/stereo_depth.h, OpenCV's semi-global
  // matcher): the photo is the left view, `right_path` the right one, `baseline_focal` the
  // baseline times the focal length in px. The depth is written to `depth_path` (float EXR,
  // channel Z, atomically) and loaded as the document's depth map (undoable), so the project
  // keeps it as any depth map. depthMapLoaded reports the outcome.
  void depthFromStereo(const QString& right_path, double baseline_focal, const QString& depth_path);
  // The second image the compositing effects read (read off the GUI thread; undoable).
  void loadSecondImage(const QString& path);
  void removeSecondImage();
  // Reads a point cloud (.ply) on a worker thread for the 3D view; cloudLoaded on success.
  void openCloud(const QString& path);
  // At start-up: offers the newest recovery left by a session that did not close cleanly.
  // Returns whether one was accepted (it is then loading).
  bool offerRecovery();
  // Loads a recovery file: the state it holds, under its project's path, marked modified.
  void recover(const artcam::ui::RecoveryOffer& offer);
  // After a clean close: nothing to recover.
  void closedCleanly();

  // Dialog-driven versions for the menus.
  void openDialog();
  bool save();
  bool saveAs();
  void importArtcamDialog();
  void exportArtcamDialog();
  void exportImageDialog();
  void exportDepthMapDialog();
  void loadDepthMapDialog(double scale, bool inverse);
  void loadSecondImageDialog();
  void depthFromStereoDialog();
  void openCloudDialog();
  // Lens ▸ From Database… (session_lens.cpp): the lensfun database loaded off the GUI thread,
  // the lens dialog with the photo's EXIF suggestions, then applyLensCamera.
  void lensFromDatabaseDialog();
  // Makes `artcam lens camera`'s camera for the open photo off the GUI thread and sets it as
  // the document's camera (undoable); lensCameraApplied reports the outcome either way.
  void applyLensCamera(const LensCameraOptions& options,
                       std::shared_ptr<const LensDatabase> database);
  // Asks to save unsaved changes, then runs `proceed` (at once when nothing needs saving or
  // the user discards, after a successful save when they save; never when they cancel or the
  // save fails).
  void maybeSaveThen(std::function<void()> proceed);

 signals:
  void loadProgress(int percent);  // -1: finished or failed
  void statusMessage(const QString& message);
  void errorOccurred(const QString& message);
  void titleChanged();
  void recentFilesChanged();
  void viewStateLoaded(const artcam::ui::ViewState& view);
  void exportFinished(bool ok, const QString& message);
  void projectSaved(bool ok, const QString& message);
  void fileWritten(bool ok, const QString& message);  // .artcam and depth map exports
  void importFinished(bool ok, const QString& message);
  // A project is in the document (ok), or could not be opened (the message says why).
  void projectOpened(bool ok, const QString& message);
  void depthMapLoaded(bool ok, const QString& message);
  void secondImageLoaded(bool ok, const QString& message);
  void cloudLoaded(const artcam::ui::LoadedCloud& cloud);
  void lensCameraApplied(bool ok, const QString& message);

 private:
  void startLoading(const QString& photo_path, std::optional<Project> project,
                    bool recovered = false, bool located = false);
  void openProjectNow(const QString& path);
  // After the read: the photo is there, or it is asked for (locate_prompt_).
  void openReadProject(const QString& path, Project project, bool photo_found, bool recovered);
  void locatePhoto(const QString& path, Project project, bool recovered);
  void importReadArtcam(const QString& path, Artcam doc);
  void failOpen(const QString& message);
  void readDepthMapAsync(const QString& path, const DepthFileOptions& options, bool undoable);
  void readSecondImageAsync(const QString& path, bool undoable);
  void applyDepthMap(const QString& path, const DepthFileOptions& options,
                     std::shared_ptr<const ImageF> map, bool undoable);
  void showError(const QString& title, const QString& message);
  // The end of a background export (.artcam, depth map): the error shown under `action`, or
  // `written` on the status line; fileWritten either way.
  void finishWrite(const JobOutcome<Status>& outcome, const QString& action,
                   const QString& written);
  void addRecent(const QString& path);

  Document* document_;
  QWidget* dialog_parent_;
  std::function<ViewState()> view_state_;
  std::vector<ProjectPart> parts_;
  bool interactive_ = true;
  LocatePrompt locate_prompt_;
  bool saving_ = false;
  quint64 open_serial_ = 0;  // bumps per open; a stale project read is dropped
  ExportOptions export_options_;
  QString project_path_;
  QPointer<ImageLoader> loader_;
  bool hold_whole_read_ = false;
  bool export_waits_ = false;  // an export waits for the full photo (exportImage)
  std::optional<Project> pending_project_;
  QString pending_project_path_;
  QPointer<ExportJob> export_job_;
  Autosave* autosave_;
  bool pending_recovered_ = false;
  bool pending_located_ = false;
  QString pending_recovery_file_;  // the recovery file being recovered (recover)
  quint64 photo_serial_ = 0;  // bumps per loaded photo; stale depth map loads are dropped
};

}  // namespace artcam::ui
