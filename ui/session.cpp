// SPDX-License-Identifier: Apache-2.0
#include "ui/session.h"

#include "core/io/artcam_file.h"
#include "core/io/depth_file.h"
#include "ui/autosave.h"
#include "ui/background_job.h"
#include "ui/commands.h"
#include "ui/depth_commands.h"
#include "ui/document.h"
#include "ui/export_job.h"
#include "ui/export_options_dialog.h"
#include "ui/export_settings.h"
#include "ui/image_loader.h"
#include "ui/save_names.h"
#include "ui/studio_wording.h"

#include <QCoreApplication>
#include <QFileDialog>
#include <QFileInfo>
#include <QMessageBox>
#include <QProgressDialog>
#include <QSettings>

#include <cmath>

namespace artcam::ui {
namespace {

const char kRecentKey[] = "recentFiles";

QString photoFilter() {
  return QCoreApplication::translate(
      "Session", "Images (*.png *.jpg *.jpeg *.tif *.tiff *.exr *.bmp *.webp);;All files (*)");
}

QString projectFilter() {
  return QCoreApplication::translate("Session", "ARTcam Studio projects (*.%1)")
      .arg(kProjectExtension);
}

}  // namespace

Session::Session(Document* document, QWidget* dialog_parent, QObject* parent)
    : QObject(parent),
      document_(document),
      dialog_parent_(dialog_parent),
      autosave_(new Autosave(
          [this]() -> std::optional<Project> {
            if (!document_->isModified()) return std::nullopt;
            return currentProject();
          },
          this)) {
  export_options_ = loadExportOptions(QSettings());
  connect(document_->undoStack(), &QUndoStack::cleanChanged, this, &Session::titleChanged);
  connect(autosave_, &Autosave::saved, this, [this](bool ok, const QString& message) {
    if (!ok) emit statusMessage(tr("Autosave failed: %1").arg(message));
  });
  autosave_->setPrompt([this](const RecoveryOffer& offer) {
    return interactive_ && Autosave::dialogPrompt(dialog_parent_)(offer);
  });
  autosave_->start();
}

Session::~Session() {
  if (export_job_) export_job_->cancel();
  delete export_job_.data();
  delete loader_.data();
}

QString Session::displayName() const {
  if (!project_path_.isEmpty()) return QFileInfo(project_path_).fileName();
  if (document_->photo()) return QFileInfo(document_->photo()->path).fileName();
  return tr("Untitled");
}

QStringList Session::recentFiles() const { return QSettings().value(kRecentKey).toStringList(); }

void Session::addRecent(const QString& path) {
  QStringList list = recentFiles();
  const QString abs = QFileInfo(path).absoluteFilePath();
  list.removeAll(abs);
  list.prepend(abs);
  while (list.size() > kMaxRecentFiles) list.removeLast();
  QSettings().setValue(kRecentKey, list);
  emit recentFilesChanged();
}

void Session::showError(const QString& title, const QString& message) {
  emit errorOccurred(message);
  emit statusMessage(message);
  if (interactive_) QMessageBox::critical(dialog_parent_, title, message);
}

void Session::openPath(const QString& path) {
  const QString suffix = QFileInfo(path).suffix().toLower();
  if (suffix == kProjectExtension)
    openProject(path);
  else if (suffix == "ply")
    openCloud(path);
  else if (suffix == "artcam")
    importArtcam(path);
  else
    openPhoto(path);
}

void Session::openPhoto(const QString& path) {
  if (!maybeSave()) return;
  project_path_.clear();
  autosave_->setProjectPath(QString());
  startLoading(path, std::nullopt);
}

void Session::openProject(const QString& path) {
  if (!maybeSave()) return;
  if (const auto offer = autosave_->findRecovery(QFileInfo(path).absoluteFilePath());
      offer && autosave_->ask(*offer)) {
    recover(*offer);
    return;
  }
  Result<Project> project = readProject(path);
  if (!project) {
    showError(tr("Open project"), QString::fromStdString(project.status.message));
    return;
  }
  pending_project_path_ = QFileInfo(path).absoluteFilePath();
  const QString photo_path = project->photo_path;  // copied: the project is moved below
  startLoading(photo_path, std::move(*project.value));
}

bool Session::offerRecovery() {
  const std::vector<RecoveryOffer> offers = autosave_->pendingRecoveries();
  if (offers.empty() || !autosave_->ask(offers.front())) return false;
  recover(offers.front());
  return true;
}

void Session::recover(const RecoveryOffer& offer) {
  Result<Project> project = Autosave::readRecovery(offer.recovery_path);
  if (!project) {
    showError(tr("Recover work"), QString::fromStdString(project.status.message));
    return;
  }
  pending_project_path_ = offer.project_path;
  const QString photo_path = project->photo_path;
  startLoading(photo_path, std::move(*project.value), /*recovered=*/true);
}

void Session::closedCleanly() { autosave_->removeRecovery(project_path_); }

std::optional<Project> Session::currentProject() const {
  if (!document_->photo()) return std::nullopt;
  Project p;
  p.photo_path = QFileInfo(document_->photo()->path).absoluteFilePath();
  p.pairs = document_->pairs();
  p.lines = document_->lines();
  p.model = document_->model();
  p.manual_camera = document_->manualCamera();
  p.effects = document_->effects();
  if (view_state_) p.view = view_state_();
  p.depth_layers = document_->depth()->layers();
  if (const auto& map = document_->depth()->map()) p.depth_map = DepthMapRef{map->path, map->options};
  for (const ProjectPart& part : parts_)
    if (const QJsonObject o = part.save(); !o.isEmpty()) p.parts[part.name] = o;
  return p;
}

void Session::startLoading(const QString& photo_path, std::optional<Project> project,
                           bool recovered) {
  if (loader_) {
    // A newer open replaces the one in flight; its result is never applied.
    disconnect(loader_, nullptr, this, nullptr);
    loader_->cancel();
    connect(loader_, &ImageLoader::finished, loader_, &QObject::deleteLater);
  }
  pending_project_ = std::move(project);
  pending_recovered_ = recovered;
  auto* loader = new ImageLoader(photo_path, this);
  // A JPEG shows its first look at once and its full photo a moment later (image_loader.h).
  loader->setFirstLook(true);
  loader->setHoldWholeRead(hold_whole_read_);
  loader_ = loader;
  connect(loader, &ImageLoader::progressChanged, this, &Session::loadProgress);
  connect(loader, &ImageLoader::loaded, this, [this, loader](const PhotoPtr& photo) {
    if (loader != loader_) return;
    ++photo_serial_;
    if (pending_project_) {
      Project p = std::move(*pending_project_);
      pending_project_.reset();
      std::optional<Artcam> manual = p.manual_camera;
      if (manual) manual->setFrames(photo->size(), photo->size());
      document_->reset(photo, std::move(p.pairs), p.model, std::move(manual),
                       std::move(p.effects), std::move(p.lines));
      // Masks are the photo's size; a photo that changed size since the save cannot take them.
      QStringList dropped;
      for (size_t i = 0; i < p.depth_layers.size(); ++i) {
        const RegionMask& m = p.depth_layers[i].mask;
        if (m.width() != photo->size().width || m.height() != photo->size().height)
          dropped << tr("%1: /depth/layers/%2: the mask is %3×%4 but the photo is %5×%6")
                         .arg(QFileInfo(pending_project_path_).fileName())
                         .arg(i)
                         .arg(m.width())
                         .arg(m.height())
                         .arg(photo->size().width)
                         .arg(photo->size().height);
      }
      document_->depth()->reset(photo->size(), std::move(p.depth_layers));
      if (!dropped.isEmpty())
        showError(tr("Open project"),
                  tr("Depth planes left out (the photo changed size):\n%1").arg(dropped.join('\n')));
      if (p.depth_map) {
        // Loaded like any depth map, but as part of opening: not an undoable edit.
        readDepthMapAsync(p.depth_map->path, p.depth_map->options, /*undoable=*/false);
      }
      project_path_ = pending_project_path_;
      if (pending_recovered_) {
        document_->undoStack()->resetClean();  // recovered work is not saved yet
      } else {
        addRecent(project_path_);
      }
      for (const ProjectPart& part : parts_) part.load(p.parts.value(part.name).toObject());
      emit viewStateLoaded(p.view);
    } else {
      document_->reset(photo);
      addRecent(photo->path);
    }
    pending_recovered_ = false;
    autosave_->setProjectPath(project_path_);
    emit titleChanged();
    QString loaded = tr("Loaded %1 (%2×%3)")
                         .arg(QFileInfo(photo->path).fileName())
                         .arg(photo->size().width)
                         .arg(photo->size().height);
    // The studio shows and exports colour and alpha (image_io.h, "Channels"): the rest are named,
    // never dropped silently. `artcam warp` carries them into an EXR.
    QStringList dropped;
    for (const std::string& c : photo->full.info.dropped_channels) dropped << QString::fromStdString(c);
    if (!dropped.isEmpty())
      loaded += tr("; channels beyond colour and alpha (%1) are not shown or exported here "
                   "(artcam warp carries them into an EXR)")
                    .arg(dropped.join(", "));
    emit statusMessage(loaded);
  });
  connect(loader, &ImageLoader::refined, this, [this, loader](const PhotoPtr& photo) {
    if (loader != loader_) return;
    document_->refinePhoto(photo);
  });
  connect(loader, &ImageLoader::refineFailed, this, [this, loader](const QString& message) {
    if (loader != loader_) return;
    document_->failRefine(message);
    showError(tr("Open photo"),
              tr("%1\nThe photo is shown from a reduced decode; it cannot be exported.").arg(message));
  });
  connect(loader, &ImageLoader::failed, this, [this, loader](const QString& message) {
    if (loader != loader_) return;
    pending_project_.reset();
    emit loadProgress(-1);  // the load is over: no "Loading 0%" behind the error's dialog
    showError(tr("Open photo"), message);
  });
  connect(loader, &ImageLoader::finished, this, [this, loader] {
    if (loader == loader_) loader_ = nullptr;
    loader->deleteLater();
    emit loadProgress(-1);
  });
  emit loadProgress(0);
  loader->start();
}

bool Session::saveProjectTo(const QString& path) {
  const std::optional<Project> p = currentProject();
  if (!p) {
    showError(tr("Save project"), tr("Nothing to save: open a photo first."));
    return false;
  }
  const Status status = writeProject(path, *p);
  if (!status) {
    showError(tr("Save project"), QString::fromStdString(status.message));
    return false;
  }
  autosave_->removeRecovery(project_path_);  // the old name's (or the untitled) recovery
  project_path_ = QFileInfo(path).absoluteFilePath();
  autosave_->removeRecovery(project_path_);
  autosave_->setProjectPath(project_path_);
  document_->undoStack()->setClean();
  addRecent(project_path_);
  emit titleChanged();
  emit statusMessage(tr("Saved %1").arg(path));
  return true;
}

void Session::importArtcam(const QString& path) {
  const PhotoPtr& photo = document_->photo();
  if (!photo) {
    showError(tr("Import camera"), tr("Open a photo before importing a camera onto it."));
    return;
  }
  Result<Artcam> doc = readArtcam(path.toStdString());
  if (!doc) {
    showError(tr("Import camera"), QString::fromStdString(doc.status.message));
    return;
  }
  // Every kind is taken: the geometry (the first layer) becomes editable in the Tensors panel,
  // every other part (colour and depth blocks, layers, patches, depth output) is kept as it is.
  // What cannot warp a photo at all is refused with the reason.
  const Camera& cam = doc->main();
  if (cam.layout().find(BlockKind::Position) < 0 || cam.blocks()[0] != Block{BlockKind::Position, 3}) {
    showError(tr("Import camera"),
              tr("%1: this camera does not take image positions (its first block is not an "
                 "image position (u, v, w)), so it cannot warp a photo; render it with artcam "
                 "render instead.")
                  .arg(path));
    return;
  }
  if (doc->isPiecewise() && (cam.sourceSize().width != photo->size().width ||
                             cam.sourceSize().height != photo->size().height)) {
    showError(tr("Import camera"),
              tr("%1: its patches were cut for a %2×%3 photo; this photo is %4×%5.")
                  .arg(path)
                  .arg(cam.sourceSize().width)
                  .arg(cam.sourceSize().height)
                  .arg(photo->size().width)
                  .arg(photo->size().height));
    return;
  }
  QUndoStack* stack = document_->undoStack();
  stack->beginMacro(tr("Import %1").arg(QFileInfo(path).fileName()));
  const bool geometry_only = doc->kind() == ArtcamKind::Single || doc->kind() == ArtcamKind::Chained;
  if (geometry_only && !doc->matches.empty() && cam.sourceSize().isImage()) {
    // Matches are pixels of the camera's frames: rescale to this photo's pixels.
    const double sx = static_cast<double>(photo->size().width) / cam.sourceSize().width;
    const double sy = static_cast<double>(photo->size().height) / cam.sourceSize().height;
    const FrameSize t = cam.targetSize().isImage() ? cam.targetSize() : cam.sourceSize();
    const double tx = static_cast<double>(photo->size().width) / t.width;
    const double ty = static_cast<double>(photo->size().height) / t.height;
    for (const PointMatch& m : doc->matches) {
      if (m.source.size() != 2 || m.target.size() != 2) continue;
      Pair p;
      p.source = {m.source[0] * sx, m.source[1] * sy};
      p.target = {m.target[0] * tx, m.target[1] * ty};
      p.enabled = m.enabled;
      stack->push(new AddPairCommand(document_, p));
    }
    stack->push(new SetCameraCommand(document_, std::nullopt, tr("Use fitted camera")));
  } else {
    Artcam c = std::move(*doc.value);
    c.matches.clear();
    c.fit.reset();
    c.setFrames(photo->size(), photo->size());
    stack->push(new SetCameraCommand(document_, std::move(c), tr("Set camera")));
  }
  stack->endMacro();
  QString imported =
      tr("Imported %1 (%2 camera)")
          .arg(path,
               QString::fromUtf8(std::string(artcamKindName(document_->artcam().kind())).c_str()));
  // What `artcam` prints on reading such a camera: a pole in the frame leaves part of the
  // picture empty, which the user should hear before looking for a bug in the photo.
  QStringList warnings;
  for (const std::string& w : cameraWarnings(document_->artcam()))
    warnings << QString::fromStdString(w);
  if (warnings.isEmpty()) {
    emit statusMessage(imported);
    return;
  }
  imported += tr(". Warning: %1").arg(warnings.join("; "));
  emit statusMessage(imported);
  if (interactive_) QMessageBox::warning(dialog_parent_, tr("Import camera"), imported);
}

bool Session::exportArtcam(const QString& path) {
  // The whole camera the preview and the export render: geometry, colour block and effects.
  Artcam doc = document_->artcam();
  doc.matches = document_->matches();
  // The fit record describes the camera only when the camera is the fitted one.
  if (!document_->manualCamera() && document_->fit().status.ok && document_->effects().empty())
    doc.fit = document_->fit().record;
  const Status status = writeArtcam(path.toStdString(), doc);
  if (!status) {
    showError(tr("Export camera"), QString::fromStdString(status.message));
    return false;
  }
  emit statusMessage(tr("Exported camera to %1").arg(path));
  return true;
}

void Session::exportImage(const QString& path) {
  if (!document_->photo()) {
    showError(tr("Export image"), tr("Nothing to export: open a photo first."));
    return;
  }
  if (export_job_ || export_waits_) {
    showError(tr("Export image"), tr("An export is already running."));
    return;
  }
  if (!document_->photo()->hasFullImage()) {
    // A first look (image_loader.h): the export renders the full photo, so it waits for it.
    export_waits_ = true;
    emit statusMessage(tr("Export of %1 waits for the full photo (decoding)…").arg(path));
    document_->whenFullImage(this, [this, path](bool ready) {
      export_waits_ = false;
      if (ready) {
        exportImage(path);
        return;
      }
      const QString message =
          tr("Export of %1 not made: the full photo was not decoded (another photo was opened, "
             "or its decode failed).")
              .arg(path);
      showError(tr("Export image"), message);
      emit exportFinished(false, message);
    });
    return;
  }
  auto* job = new ExportJob(document_->photo(), document_->artcam(), path,
                            exportOptionsForFile(export_options_, path), this);
  // A camera with a depth block reads the painted depth (rasterised here: the depth model lives
  // on the GUI thread; only such cameras pay for it).
  if (readsDepth(document_->artcam()))
    job->setDepth(std::make_shared<const ImageF>(document_->depth()->rasterise()));
  export_job_ = job;
  QProgressDialog* dialog = nullptr;
  if (interactive_) {
    dialog = new QProgressDialog(tr("Exporting %1…").arg(QFileInfo(path).fileName()), tr("Cancel"),
                                 0, 100, dialog_parent_);
    dialog->setWindowModality(Qt::WindowModal);
    dialog->setMinimumDuration(300);
    dialog->setAttribute(Qt::WA_DeleteOnClose);
    connect(job, &ExportJob::progressChanged, dialog, &QProgressDialog::setValue);
    connect(dialog, &QProgressDialog::canceled, job, &ExportJob::cancel, Qt::DirectConnection);
  }
  connect(job, &ExportJob::done, this, [this, dialog](bool ok, const QString& message) {
    if (dialog) dialog->close();
    if (ok)
      emit statusMessage(message);
    else if (!message.isEmpty())
      showError(tr("Export image"), studioWording(message));
    emit exportFinished(ok, ok ? message : studioWording(message));
  });
  connect(job, &ExportJob::finished, job, &QObject::deleteLater);
  job->start();
}

bool Session::exportDepthMap(const QString& path) {
  if (!document_->photo() || !document_->depth()->hasDepth()) {
    showError(tr("Export depth map"),
              tr("No depth to export: paint a depth plane and give it three depths, or load a "
                 "depth map."));
    return false;
  }
  WriteImageOptions options;
  options.pixel_type = "float";
  const ImageF depth = depthMapImage(document_->depth()->rasterise());
  const Status status = writeImage(path.toStdString(), depth, nullptr, options);
  if (!status) {
    showError(tr("Export depth map"), QString::fromStdString(status.message));
    return false;
  }
  emit statusMessage(tr("Exported the depth map to %1").arg(path));
  return true;
}

void Session::exportDepthMapDialog() {
  if (!document_->photo()) return;
  const QFileInfo info(document_->photo()->path);
  const QString suggestion = info.absoluteDir().filePath(info.completeBaseName() + "_depth.exr");
  const QString path = QFileDialog::getSaveFileName(dialog_parent_, tr("Export depth map"),
                                                    suggestion, tr("OpenEXR (*.exr)"));
  if (!path.isEmpty()) exportDepthMap(path);
}

void Session::setExportOptions(const ExportOptions& options) {
  export_options_ = options;
  QSettings settings;
  saveExportOptions(settings, options);
}

void Session::cancelExport() {
  if (export_job_) export_job_->cancel();
}

void Session::loadDepthMap(const QString& path, const DepthFileOptions& options) {
  if (!document_->photo()) {
    showError(tr("Load depth map"), tr("Open a photo before loading its depth map."));
    return;
  }
  const QString abs = QFileInfo(path).absoluteFilePath();
  emit statusMessage(tr("Loading depth map %1…").arg(QFileInfo(abs).fileName()));
  readDepthMapAsync(abs, options, /*undoable=*/true);
}

void Session::readDepthMapAsync(const QString& path, const DepthFileOptions& options,
                                bool undoable) {
  const quint64 serial = photo_serial_;
  runInBackground(
      this, [path, options](JobContext&) { return readDepthFile(path.toStdString(), options); },
      [this, path, options, serial, undoable](JobOutcome<Result<ImageF>> outcome) {
        if (serial != photo_serial_) return;  // another photo opened meanwhile
        if (!outcome.value || !*outcome.value) {
          const QString message = outcome.value
                                      ? QString::fromStdString(outcome.value->status.message)
                                      : tr("%1: %2").arg(path, outcome.error);
          showError(tr("Load depth map"), message);
          emit depthMapLoaded(false, message);
          return;
        }
        applyDepthMap(path, options,
                      std::make_shared<const ImageF>(std::move(*outcome.value->value)), undoable);
      });
}

void Session::applyDepthMap(const QString& path, const DepthFileOptions& options,
                            std::shared_ptr<const ImageF> map, bool undoable) {
  const FrameSize f = document_->frame();
  // Sampled nearest at the photo's scale, so any size works; a different aspect would put depth
  // on the wrong pixels.
  const double photo_aspect = static_cast<double>(f.width) / f.height;
  const double map_aspect = static_cast<double>(map->width) / map->height;
  if (std::abs(map_aspect / photo_aspect - 1.0) > 0.01) {
    const QString message = tr("%1: the depth map is %2×%3 but the photo is %4×%5 (aspects differ)")
                                .arg(path)
                                .arg(map->width)
                                .arg(map->height)
                                .arg(f.width)
                                .arg(f.height);
    showError(tr("Load depth map"), message);
    emit depthMapLoaded(false, message);
    return;
  }
  DepthMapSource source{path, options, std::move(map)};
  if (undoable)
    document_->undoStack()->push(new SetDepthMapCommand(document_->depth(), std::move(source)));
  else
    document_->depth()->setMap(std::move(source));
  const QString message = tr("Loaded depth map %1").arg(QFileInfo(path).fileName());
  emit statusMessage(message);
  emit depthMapLoaded(true, message);
}

void Session::openCloud(const QString& path) {
  emit statusMessage(tr("Loading %1…").arg(QFileInfo(path).fileName()));
  runInBackground(
      this, [path](JobContext&) { return CloudView::load(path); },
      [this, path](JobOutcome<Result<LoadedCloud>> outcome) {
        if (!outcome.value || !*outcome.value) {
          showError(tr("Open point cloud"),
                    outcome.value ? QString::fromStdString(outcome.value->status.message)
                                  : tr("%1: %2").arg(path, outcome.error));
          return;
        }
        const LoadedCloud& cloud = *outcome.value->value;
        emit statusMessage(tr("Loaded %1 (%2 points)")
                               .arg(QFileInfo(cloud.path).fileName())
                               .arg(cloud.cloud->size()));
        emit cloudLoaded(cloud);
      });
}

void Session::openCloudDialog() {
  const QString path = QFileDialog::getOpenFileName(dialog_parent_, tr("Open point cloud"),
                                                    QString(), tr("Point clouds (*.ply)"));
  if (!path.isEmpty()) openCloud(path);
}

void Session::loadDepthMapDialog(double scale, bool inverse) {
  if (!document_->photo()) return;
  const QString path = QFileDialog::getOpenFileName(
      dialog_parent_, tr("Load depth map"), QFileInfo(document_->photo()->path).absolutePath(),
      tr("Depth maps (*.exr *.tif *.tiff *.png *.pgm *.pfm);;All files (*)"));
  if (path.isEmpty()) return;
  DepthFileOptions options;
  options.scale = scale;
  options.inverse = inverse;
  loadDepthMap(path, options);
}

void Session::openDialog() {
  const QString path = QFileDialog::getOpenFileName(
      dialog_parent_, tr("Open photo or project"), QString(),
      tr("Photos and projects (*.png *.jpg *.jpeg *.tif *.tiff *.exr *.bmp *.webp *.%1);;")
              .arg(kProjectExtension) +
          projectFilter() + ";;" + photoFilter());
  if (!path.isEmpty()) openPath(path);
}

bool Session::save() {
  if (project_path_.isEmpty()) return saveAs();
  return saveProjectTo(project_path_);
}

bool Session::saveAs() {
  if (!document_->photo()) return false;
  QString suggestion = project_path_;
  if (suggestion.isEmpty()) {
    const QFileInfo info(document_->photo()->path);
    suggestion = info.absoluteDir().filePath(info.completeBaseName() + "." + kProjectExtension);
  }
  QString path =
      QFileDialog::getSaveFileName(dialog_parent_, tr("Save project"), suggestion, projectFilter());
  if (path.isEmpty()) return false;
  if (QFileInfo(path).suffix().isEmpty()) path += QString(".") + kProjectExtension;
  return saveProjectTo(path);
}

void Session::importArtcamDialog() {
  const QString path = QFileDialog::getOpenFileName(dialog_parent_, tr("Import camera"), QString(),
                                                    tr("ARTcam cameras (*.artcam)"));
  if (!path.isEmpty()) importArtcam(path);
}

void Session::exportArtcamDialog() {
  const QString photo = document_->photo() ? document_->photo()->path : QString();
  QString path = QFileDialog::getSaveFileName(dialog_parent_, tr("Export camera"),
                                              proposedSavePath(photo, "_camera.artcam"),
                                              tr("ARTcam cameras (*.artcam)"));
  if (path.isEmpty()) return;
  if (QFileInfo(path).suffix().isEmpty()) path += ".artcam";
  exportArtcam(path);
}

void Session::exportImageDialog() {
  if (!document_->photo()) return;
  const QFileInfo info(document_->photo()->path);
  const QString suggestion =
      info.absoluteDir().filePath(info.completeBaseName() + "_warped." + info.suffix());
  const QString path = QFileDialog::getSaveFileName(dialog_parent_, tr("Export warped image"),
                                                    suggestion, photoFilter());
  if (path.isEmpty()) return;
  // The dialog offers the photo's own JPEG quality until the user picks one (as a write does).
  ExportOptions current = export_options_;
  if (!current.write.jpeg_quality && document_->photo()->full.info.jpeg_quality > 0)
    current.write.jpeg_quality = document_->photo()->full.info.jpeg_quality;
  const std::optional<ExportOptions> options =
      ExportOptionsDialog::ask(current, path, dialog_parent_);
  if (!options) return;
  setExportOptions(*options);
  exportImage(path);
}

bool Session::maybeSave() {
  if (!document_->isModified() || !interactive_) return true;
  const auto answer = QMessageBox::warning(
      dialog_parent_, tr("Unsaved changes"),
      tr("%1 has unsaved changes. Save them?").arg(displayName()),
      QMessageBox::Save | QMessageBox::Discard | QMessageBox::Cancel, QMessageBox::Save);
  if (answer == QMessageBox::Save) return save();
  return answer == QMessageBox::Discard;
}

}  // namespace artcam::ui
