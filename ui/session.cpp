// SPDX-License-Identifier: Apache-2.0
#include "ui/session.h"

#include "core/depth/stereo_depth.h"
#include "core/io/artcam_file.h"
#include "core/io/depth_file.h"
#include "core/io/image_io.h"
#include "core/io/stored_image.h"
#include "core/project/project_render.h"
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
#include <QFile>
#include <QFileDialog>
#include <QFileInfo>
#include <QInputDialog>
#include <QMessageBox>
#include <QProgressDialog>
#include <QPushButton>
#include <QSettings>

#include <cmath>

namespace artcam::ui {
namespace {

const char kRecentKey[] = "recentFiles";

// The photo formats the studio's Open dialogs offer. packaging/check-desktop-files.sh reads this
// line: the desktop entry's MimeType must name each of these extensions' MIME types.
const char kPhotoPatterns[] =
    "*.png *.jpg *.jpeg *.tif *.tiff *.exr *.bmp *.webp *.heic *.heif *.avif *.dpx *.hdr *.tga "
    "*.ppm *.pgm *.pnm";

QString photoFilter() {
  return QCoreApplication::translate("Session", "Images (%1);;All files (*)")
      .arg(QLatin1String(kPhotoPatterns));
}

QString projectFilter() {
  return QCoreApplication::translate("Session", "ARTcam Studio projects (*.%1)")
      .arg(kProjectExtension);
}

// The default locate prompt: says what is missing, then a file dialog in the project's folder.
QString locateDialog(QWidget* parent, const QString& project, const QString& photo) {
  QMessageBox box(QMessageBox::Warning, QCoreApplication::translate("Session", "Open project"),
                  QCoreApplication::translate("Session",
                                              "The photo of %1 is missing:\n%2\n\nLocate it to "
                                              "open the project with its pairs, depth and effects.")
                      .arg(QFileInfo(project).fileName(), photo),
                  QMessageBox::Cancel, parent);
  QPushButton* locate =
      box.addButton(QCoreApplication::translate("Session", "Locate…"), QMessageBox::AcceptRole);
  box.setDefaultButton(locate);
  box.exec();
  if (box.clickedButton() != locate) return {};
  return QFileDialog::getOpenFileName(
      parent, QCoreApplication::translate("Session", "Locate %1").arg(QFileInfo(photo).fileName()),
      QFileInfo(project).absolutePath(), photoFilter());
}

// A project read off the GUI thread, and whether its photo is where it says.
struct ReadProject {
  Result<Project> project;
  bool photo_found = false;
};

ReadProject readProjectAndLook(const QString& path, bool recovery) {
  ReadProject read;
  read.project = recovery ? Autosave::readRecovery(path) : readProject(path);
  if (read.project) read.photo_found = QFileInfo(read.project->photo_path).isFile();
  return read;
}

// A job's Status (or what it threw) as one line; empty when it succeeded.
QString errorOf(const JobOutcome<Status>& outcome) {
  if (!outcome.value) return outcome.error;
  return outcome.value->ok ? QString() : QString::fromStdString(outcome.value->message);
}

}  // namespace

void Session::finishWrite(const JobOutcome<Status>& outcome, const QString& action,
                          const QString& written) {
  if (const QString error = errorOf(outcome); !error.isEmpty()) {
    showError(action, error);
    emit fileWritten(false, error);
    return;
  }
  emit statusMessage(written);
  emit fileWritten(true, written);
}

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
  locate_prompt_ = [this](const QString& project, const QString& photo) {
    return interactive_ ? locateDialog(dialog_parent_, project, photo) : QString();
  };
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
  maybeSaveThen([this, path] {
    ++open_serial_;  // a project read in flight is superseded
    project_path_.clear();
    autosave_->setProjectPath(QString());
    startLoading(path, std::nullopt);
  });
}

void Session::openProject(const QString& path) {
  maybeSaveThen([this, path] { openProjectNow(path); });
}

void Session::openProjectNow(const QString& path) {
  const QString abs = QFileInfo(path).absoluteFilePath();
  if (const auto offer = autosave_->findRecovery(abs); offer && autosave_->ask(*offer)) {
    recover(*offer);
    return;
  }
  const quint64 serial = ++open_serial_;
  emit statusMessage(tr("Opening %1…").arg(QFileInfo(abs).fileName()));
  runInBackground(
      this, [abs](JobContext&) { return readProjectAndLook(abs, /*recovery=*/false); },
      [this, abs, serial](JobOutcome<ReadProject> outcome) {
        if (serial != open_serial_) return;  // another open came after this one
        if (!outcome.value) return failOpen(tr("%1: %2").arg(abs, outcome.error));
        ReadProject& read = *outcome.value;
        if (!read.project) return failOpen(QString::fromStdString(read.project.status.message));
        openReadProject(abs, std::move(*read.project.value), read.photo_found, false);
      });
}

void Session::failOpen(const QString& message) {
  showError(tr("Open project"), message);
  emit projectOpened(false, message);
}

void Session::openReadProject(const QString& path, Project project, bool photo_found,
                              bool recovered) {
  if (!photo_found) {
    locatePhoto(path, std::move(project), recovered);
    return;
  }
  pending_project_path_ = path;
  const QString photo_path = project.photo_path;  // copied: the project is moved below
  startLoading(photo_path, std::move(project), recovered);
}

void Session::locatePhoto(const QString& path, Project project, bool recovered) {
  const QString name = path.isEmpty() ? tr("The recovered session") : QFileInfo(path).fileName();
  const QString missing = project.photo_path;
  const QString located = locate_prompt_ ? locate_prompt_(path, missing) : QString();
  if (located.isEmpty()) {
    failOpen(tr("%1: its photo %2 is missing (moved or renamed?); open the project again and "
                "Locate it.")
                 .arg(name, missing));
    return;
  }
  const QString photo = QFileInfo(located).absoluteFilePath();
  const quint64 serial = open_serial_;
  auto held = std::make_shared<Project>(std::move(project));
  // The header only: a photo of another size is refused before anything is decoded.
  runInBackground(
      this,
      [photo](JobContext&) { return readStoredShape(QFile::encodeName(photo).toStdString()); },
      [this, path, name, photo, held, recovered, serial](JobOutcome<Result<StoredShape>> outcome) {
        if (serial != open_serial_) return;
        if (!outcome.value || !*outcome.value)
          return failOpen(tr("%1: %2").arg(
              name, outcome.value ? QString::fromStdString(outcome.value->status.message)
                                  : tr("%1: %2").arg(photo, outcome.error)));
        const StoredShape& shape = **outcome.value;
        if (const Status fits = checkPhotoSize(*held, {shape.width, shape.height}, photo,
                                               path.isEmpty() ? name : path);
            !fits)
          return failOpen(QString::fromStdString(fits.message));
        Project p = std::move(*held);
        p.photo_path = photo;
        pending_project_path_ = path;
        startLoading(photo, std::move(p), recovered, /*located=*/true);
      });
}

bool Session::offerRecovery() {
  const std::vector<RecoveryOffer> offers = autosave_->pendingRecoveries();
  if (offers.empty() || !autosave_->ask(offers.front())) return false;
  recover(offers.front());
  return true;
}

void Session::recover(const RecoveryOffer& offer) {
  const quint64 serial = ++open_serial_;
  pending_recovery_file_ = offer.recovery_path;
  const QString recovery = offer.recovery_path, project = offer.project_path;
  runInBackground(
      this, [recovery](JobContext&) { return readProjectAndLook(recovery, /*recovery=*/true); },
      [this, project, serial](JobOutcome<ReadProject> outcome) {
        if (serial != open_serial_) return;
        if (!outcome.value) return failOpen(outcome.error);
        ReadProject& read = *outcome.value;
        if (!read.project) return failOpen(QString::fromStdString(read.project.status.message));
        openReadProject(project, std::move(*read.project.value), read.photo_found, true);
      });
}

void Session::closedCleanly() { autosave_->removeRecovery(project_path_); }

std::optional<Project> Session::currentProject() const {
  if (!document_->photo()) return std::nullopt;
  Project p;
  p.photo_path = QFileInfo(document_->photo()->path).absoluteFilePath();
  p.photo_size = document_->photo()->size();
  p.pairs = document_->pairs();
  p.lines = document_->lines();
  p.model = document_->model();
  p.line_model = document_->lineModel();
  p.manual_camera = document_->manualCamera();
  p.effects = document_->effects();
  if (view_state_) p.view = view_state_();
  p.depth_layers = document_->depth()->layers();
  if (const auto& map = document_->depth()->map()) p.depth_map = DepthMapRef{map->path, map->options};
  if (const auto& second = document_->secondImage()) p.second_path = second->path;
  p.finish = document_->finish();
  for (const ProjectPart& part : parts_)
    if (const QJsonObject o = part.save(); !o.isEmpty()) p.parts[part.name] = o;
  return p;
}

void Session::startLoading(const QString& photo_path, std::optional<Project> project,
                           bool recovered, bool located) {
  if (loader_) {
    // A newer open replaces the one in flight; its result is never applied.
    disconnect(loader_, nullptr, this, nullptr);
    loader_->cancel();
    connect(loader_, &ImageLoader::finished, loader_, &QObject::deleteLater);
  }
  pending_project_ = std::move(project);
  pending_recovered_ = recovered;
  pending_located_ = located;
  auto* loader = new ImageLoader(photo_path, this);
  // A JPEG shows its first look at once and its full photo a moment later (image_loader.h).
  loader->setFirstLook(true);
  loader->setHoldWholeRead(hold_whole_read_);
  loader_ = loader;
  connect(loader, &ImageLoader::progressChanged, this, &Session::loadProgress);
  connect(loader, &ImageLoader::loaded, this, [this, loader](const PhotoPtr& photo) {
    if (loader != loader_) return;
    ++photo_serial_;
    const bool opened_project = pending_project_.has_value();
    if (pending_project_) {
      Project p = std::move(*pending_project_);
      pending_project_.reset();
      std::optional<Artcam> manual = p.manual_camera;
      if (manual) manual->setFrames(photo->size(), photo->size());
      document_->reset(photo, std::move(p.pairs), p.model, std::move(manual), std::move(p.effects),
                       std::move(p.lines), p.line_model);
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
      if (p.second_path) readSecondImageAsync(*p.second_path, /*undoable=*/false);
      document_->setFinish(p.finish);
      project_path_ = pending_project_path_;
      // Recovered: the file is this window's now, so no other offers it; it goes with this
      // window's next recovery write or clean save (not before the work is in the document).
      if (pending_recovered_) autosave_->adopt(pending_recovery_file_);
      if (pending_recovered_ || pending_located_) {
        // Recovered work is not saved yet; a located photo's new place is not either.
        document_->undoStack()->resetClean();
      } else {
        addRecent(project_path_);
      }
      for (const ProjectPart& part : parts_) part.load(p.parts.value(part.name).toObject());
      emit viewStateLoaded(p.view);
    } else {
      document_->reset(photo);
      addRecent(photo->path);
    }
    const bool was_located = pending_located_;
    pending_recovered_ = false;
    pending_located_ = false;
    autosave_->setProjectPath(project_path_);
    emit titleChanged();
    // A project is named by its own file, its photo after it.
    QString loaded =
        opened_project && !project_path_.isEmpty()
            ? tr("Opened %1 (photo %2, %3×%4)")
                  .arg(QFileInfo(project_path_).fileName(), QFileInfo(photo->path).fileName())
                  .arg(photo->size().width)
                  .arg(photo->size().height)
            : tr("Loaded %1 (%2×%3)")
                  .arg(QFileInfo(photo->path).fileName())
                  .arg(photo->size().width)
                  .arg(photo->size().height);
    if (was_located)
      loaded += tr("; its photo is now %1: save to keep the new place").arg(photo->path);
    // The studio shows and exports colour and alpha (image_io.h, "Channels"): the rest are named,
    // never dropped silently. `artcam warp` carries them into an EXR.
    QStringList dropped;
    for (const std::string& c : photo->full.info.dropped_channels) dropped << QString::fromStdString(c);
    if (!dropped.isEmpty())
      loaded += tr("; channels beyond colour and alpha (%1) are not shown or exported here "
                   "(artcam warp carries them into an EXR)")
                    .arg(dropped.join(", "));
    emit statusMessage(loaded);
    if (opened_project) emit projectOpened(true, loaded);
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
    emit loadProgress(-1);  // the load is over: no "Loading 0%" behind the error's dialog
    if (pending_project_) {
      // Opening a project: the project is what failed to open, because of its photo.
      pending_project_.reset();
      failOpen(tr("%1: photo: %2").arg(QFileInfo(pending_project_path_).fileName(), message));
      return;
    }
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
  std::optional<Project> p = currentProject();
  if (!p) {
    showError(tr("Save project"), tr("Nothing to save: open a photo first."));
    return false;
  }
  if (saving_) {
    showError(tr("Save project"), tr("A save is already running."));
    return false;
  }
  const QString abs = QFileInfo(path).absoluteFilePath();
  // The state is taken here (the document lives on this thread); serialised and written on the
  // job's. Edits made meanwhile are not in the file, so they keep the document modified.
  auto project = std::make_shared<const Project>(std::move(*p));
  const int index = document_->undoStack()->index();
  const quint64 serial = photo_serial_;
  saving_ = true;
  emit statusMessage(tr("Saving %1…").arg(QFileInfo(abs).fileName()));
  runInBackground(
      this, [abs, project](JobContext&) { return writeProject(abs, *project); },
      [this, abs, index, serial](JobOutcome<Status> outcome) {
        saving_ = false;
        if (const QString error = errorOf(outcome); !error.isEmpty()) {
          showError(tr("Save project"), error);
          emit projectSaved(false, error);
          return;
        }
        const QString message = tr("Saved %1").arg(abs);
        if (serial == photo_serial_) {               // still the document that was saved
          autosave_->removeRecovery(project_path_);  // the old name's (or the untitled) recovery
          project_path_ = abs;
          autosave_->removeRecovery(project_path_);
          autosave_->setProjectPath(project_path_);
          if (document_->undoStack()->index() == index) document_->undoStack()->setClean();
          addRecent(project_path_);
          emit titleChanged();
        }
        emit statusMessage(message);
        emit projectSaved(true, message);
      });
  return true;
}

void Session::importArtcam(const QString& path) {
  const PhotoPtr& photo = document_->photo();
  if (!photo) {
    showError(tr("Import camera"), tr("Open a photo before importing a camera onto it."));
    return;
  }
  const quint64 serial = photo_serial_;
  runInBackground(
      this, [path](JobContext&) { return readArtcam(path.toStdString()); },
      [this, path, serial](JobOutcome<Result<Artcam>> outcome) {
        if (serial != photo_serial_) return;  // another photo opened meanwhile
        if (!outcome.value || !*outcome.value) {
          const QString message = outcome.value
                                      ? QString::fromStdString(outcome.value->status.message)
                                      : tr("%1: %2").arg(path, outcome.error);
          showError(tr("Import camera"), message);
          emit importFinished(false, message);
          return;
        }
        importReadArtcam(path, std::move(*outcome.value->value));
      });
}

void Session::importReadArtcam(const QString& path, Artcam read) {
  const PhotoPtr& photo = document_->photo();
  if (!photo) return;
  std::optional<Artcam> doc(std::move(read));
  const auto refuse = [this](const QString& message) {
    showError(tr("Import camera"), message);
    emit importFinished(false, message);
  };
  // Every kind is taken: the geometry (the first layer) becomes editable in the Tensors panel,
  // every other part (colour and depth blocks, layers, patches, depth output) is kept as it is.
  // What cannot warp a photo at all is refused with the reason.
  const Camera& cam = doc->main();
  if (cam.layout().find(BlockKind::Position) < 0 || cam.blocks()[0] != Block{BlockKind::Position, 3}) {
    refuse(tr("%1: this camera does not take image positions (its first block is not an "
              "image position (u, v, w)), so it cannot warp a photo; render it with artcam "
              "render instead.")
               .arg(path));
    return;
  }
  if (doc->isPiecewise() && (cam.sourceSize().width != photo->size().width ||
                             cam.sourceSize().height != photo->size().height)) {
    refuse(tr("%1: its patches were cut for a %2×%3 photo; this photo is %4×%5.")
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
    Artcam c = std::move(*doc);
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
  if (!warnings.isEmpty()) imported += tr(". Warning: %1").arg(warnings.join("; "));
  emit statusMessage(imported);
  if (!warnings.isEmpty() && interactive_)
    QMessageBox::warning(dialog_parent_, tr("Import camera"), imported);
  emit importFinished(true, imported);
}

bool Session::exportArtcam(const QString& path) {
  // The whole camera the preview and the export render: geometry, colour block and effects.
  Artcam doc = document_->artcam();
  doc.matches = document_->matches();
  // The fit record describes the camera only when the camera is the fitted one.
  if (!document_->manualCamera() && document_->fit().status.ok && document_->effects().empty())
    doc.fit = document_->fit().record;
  auto held = std::make_shared<const Artcam>(std::move(doc));
  runInBackground(
      this, [path, held](JobContext&) { return writeArtcam(path.toStdString(), *held); },
      [this, path](JobOutcome<Status> outcome) {
        finishWrite(outcome, tr("Export camera"), tr("Exported camera to %1").arg(path));
      });
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
  ExportOptions options = exportOptionsForFile(export_options_, path);
  options.finish = document_->finish();  // the document's, not a remembered export setting
  auto* job =
      new ExportJob(document_->photo(), document_->artcam(), path, std::move(options), this);
  // A camera with a depth block reads the painted depth (rasterised here: the depth model lives
  // on the GUI thread; only such cameras pay for it).
  if (readsDepth(document_->artcam()))
    job->setDepth(std::make_shared<const ImageF>(document_->depth()->rasterise()));
  if (const auto& second = document_->secondImage()) job->setSecond(second->image);
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
  // Rasterised here (the depth model lives on this thread), written on the job's.
  auto raster = std::make_shared<const ImageF>(document_->depth()->rasterise());
  emit statusMessage(tr("Exporting the depth map to %1…").arg(path));
  runInBackground(
      this,
      [path, raster](JobContext& job) {
        return writeDepthMapFile(QFile::encodeName(path).toStdString(), *raster,
                                 [&job](double f) { return job.progress(f); });
      },
      [this, path](JobOutcome<Status> outcome) {
        finishWrite(outcome, tr("Export depth map"), tr("Exported the depth map to %1").arg(path));
      });
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

void Session::depthFromStereo(const QString& right_path, double baseline_focal,
                              const QString& depth_path) {
  const PhotoPtr photo = document_->photo();
  if (!photo || !photo->hasFullImage()) {
    showError(tr("Depth from stereo pair"), tr("Open the left view (whole) first."));
    return;
  }
  emit statusMessage(tr("Matching %1 against %2…")
                         .arg(QFileInfo(photo->path).fileName(), QFileInfo(right_path).fileName()));
  const quint64 serial = photo_serial_;
  const QString out = QFileInfo(depth_path).absoluteFilePath();
  // The depth is never written over the pair it is measured from.
  for (const QString& input : {photo->path, right_path})
    if (QFileInfo(out) == QFileInfo(input) ||
        (QFileInfo::exists(out) &&
         QFileInfo(out).canonicalFilePath() == QFileInfo(input).canonicalFilePath())) {
      const QString message =
          tr("%1: refusing to write the depth over an input of the pair").arg(out);
      showError(tr("Depth from stereo pair"), message);
      emit depthMapLoaded(false, message);
      return;
    }
  runInBackground(
      this,
      [photo, right_path, baseline_focal, out](JobContext&) -> Status {
        const Result<LoadedImage> right = readImage(QFile::encodeName(right_path).toStdString());
        if (!right) return Status::failure(right.status.message);
        StereoOptions options;
        options.baseline_focal = baseline_focal;
        if (const Status s = checkStereoOptions(options, right->image.width, right->image.height);
            !s)
          return s;
        const Result<ImageF> depth =
            artcam::depthFromStereo(photo->full.image, right->image, options);
        if (!depth)
          return Status::failure(photo->path.toStdString() + ", " + right_path.toStdString() +
                                 ": " + depth.status.message);
        WriteImageOptions write;
        write.pixel_type = "float";
        write.channel_names = {"Z"};
        return writeImage(QFile::encodeName(out).toStdString(), *depth, nullptr, write);
      },
      [this, serial, out](JobOutcome<Status> outcome) {
        if (serial != photo_serial_) return;
        if (!outcome.value || !*outcome.value) {
          const QString message =
              outcome.value ? QString::fromStdString(outcome.value->message) : outcome.error;
          showError(tr("Depth from stereo pair"), message);
          emit depthMapLoaded(false, message);
          return;
        }
        readDepthMapAsync(out, DepthFileOptions{}, /*undoable=*/true);
      });
}

void Session::depthFromStereoDialog() {
  const PhotoPtr photo = document_->photo();
  if (!photo) return;
  const QString right = QFileDialog::getOpenFileName(
      dialog_parent_, tr("The right view of the stereo pair (the photo is the left)"),
      QFileInfo(photo->path).absolutePath(), photoFilter());
  if (right.isEmpty()) return;
  bool ok = false;
  const double baseline_focal = QInputDialog::getDouble(
      dialog_parent_, tr("Depth from stereo pair"),
      tr("Baseline × focal length (depth units × px): depth = this / disparity"), 100.0, 1e-6, 1e12,
      4, &ok);
  if (!ok) return;
  const QFileInfo left(photo->path);
  const QString out = QFileDialog::getSaveFileName(
      dialog_parent_, tr("Save the depth map"),
      left.absolutePath() + "/" + left.completeBaseName() + "-depth.exr", tr("OpenEXR (*.exr)"));
  if (!out.isEmpty()) depthFromStereo(right, baseline_focal, out);
}

void Session::loadSecondImage(const QString& path) {
  if (!document_->photo()) {
    showError(tr("Second image"), tr("Open a photo before the image to composite with it."));
    return;
  }
  const QString abs = QFileInfo(path).absoluteFilePath();
  emit statusMessage(tr("Loading second image %1…").arg(QFileInfo(abs).fileName()));
  readSecondImageAsync(abs, /*undoable=*/true);
}

void Session::readSecondImageAsync(const QString& path, bool undoable) {
  const quint64 serial = photo_serial_;
  runInBackground(
      this, [path](JobContext&) { return readImage(QFile::encodeName(path).toStdString()); },
      [this, path, serial, undoable](JobOutcome<Result<LoadedImage>> outcome) {
        if (serial != photo_serial_) return;  // another photo opened meanwhile
        if (!outcome.value || !*outcome.value) {
          const QString message = outcome.value
                                      ? QString::fromStdString(outcome.value->status.message)
                                      : tr("%1: %2").arg(path, outcome.error);
          showError(tr("Second image"), message);
          emit secondImageLoaded(false, message);
          return;
        }
        auto image = std::make_shared<const ImageF>(std::move(outcome.value->value->image));
        // It lies over the photo's frame, as `artcam warp --second` and `artcam export` take it:
        // another size is stretched to the photo, and said.
        const FrameSize f = document_->frame();
        QString message = tr("Second image %1").arg(QFileInfo(path).fileName());
        if (const std::string stretched = secondImageSizeNote({image->width, image->height}, f);
            !stretched.empty())
          message += ": " + QString::fromStdString(stretched);
        Document::SecondImage second{path, std::move(image)};
        if (undoable)
          document_->undoStack()->push(new SetSecondImageCommand(document_, std::move(second)));
        else
          document_->setSecondImage(std::move(second));
        emit statusMessage(message);
        emit secondImageLoaded(true, message);
      });
}

void Session::removeSecondImage() {
  if (document_->secondImage())
    document_->undoStack()->push(new SetSecondImageCommand(document_, std::nullopt));
}

void Session::loadSecondImageDialog() {
  if (!document_->photo()) return;
  const QString path = QFileDialog::getOpenFileName(
      dialog_parent_, tr("Second image (composited by the colour effects)"),
      QFileInfo(document_->photo()->path).absolutePath(), photoFilter());
  if (!path.isEmpty()) loadSecondImage(path);
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
      tr("Photos and projects (%1 *.%2);;")
              .arg(QLatin1String(kPhotoPatterns), QLatin1String(kProjectExtension)) +
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

void Session::maybeSaveThen(std::function<void()> proceed) {
  if (!document_->isModified() || !interactive_) {
    proceed();
    return;
  }
  const auto answer = QMessageBox::warning(
      dialog_parent_, tr("Unsaved changes"),
      tr("%1 has unsaved changes. Save them?").arg(displayName()),
      QMessageBox::Save | QMessageBox::Discard | QMessageBox::Cancel, QMessageBox::Save);
  if (answer == QMessageBox::Discard) {
    proceed();
    return;
  }
  if (answer != QMessageBox::Save) return;
  // The save runs off the GUI thread: continue on its outcome, once.
  auto connection = std::make_shared<QMetaObject::Connection>();
  *connection = connect(this, &Session::projectSaved, this,
                        [connection, proceed = std::move(proceed)](bool ok, const QString&) {
                          QObject::disconnect(*connection);
                          if (ok) proceed();
                        });
  if (!save()) QObject::disconnect(*connection);
}

}  // namespace artcam::ui
