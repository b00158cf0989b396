// SPDX-License-Identifier: Apache-2.0
// Session: Lens ▸ From Database… (ui/lens_dialog.h). Loading the database and fitting the
// camera are one-shot background jobs (the database is a few hundred XML files; a piecewise
// fit of a 24 Mpix frame takes about half a second), so the GUI thread never waits on either.
#include "core/io/photo_metadata.h"
#include "ui/background_job.h"
#include "ui/commands.h"
#include "ui/document.h"
#include "ui/lens_dialog.h"
#include "ui/session.h"

#include <stdexcept>

namespace artcam::ui {

void Session::lensFromDatabaseDialog() {
  const PhotoPtr photo = document_->photo();
  if (!photo) {
    showError(tr("Lens from database"),
              tr("Open a photo first: the lens camera is made for the photo's size."));
    return;
  }
  LensHint hint;
  if (photo->full.info.metadata) hint = photoLensTags(*photo->full.info.metadata);
  emit statusMessage(tr("Reading the lensfun database…"));
  runInBackground(
      this,
      [](JobContext&) {
        auto db = LensDatabase::load();
        if (!db) throw std::runtime_error(db.status.message);
        return *db.value;
      },
      [this, photo, hint](JobOutcome<std::shared_ptr<const LensDatabase>> outcome) {
        if (!outcome.value) {
          if (!outcome.cancelled) showError(tr("Lens from database"), outcome.error);
          return;
        }
        if (document_->photo() != photo) return;  // another photo was opened meanwhile
        LensDialog dialog(*outcome.value, photo->size(), hint, dialog_parent_);
        if (dialog.exec() != QDialog::Accepted || dialog.options().lens.empty()) return;
        applyLensCamera(dialog.options(), *outcome.value);
      });
}

void Session::applyLensCamera(const LensCameraOptions& options,
                              std::shared_ptr<const LensDatabase> database) {
  const PhotoPtr photo = document_->photo();
  if (!photo) {
    emit lensCameraApplied(false, tr("no photo is open"));
    return;
  }
  LensCameraOptions o = options;
  o.size = photo->size();
  runInBackground(
      this, [o, database](JobContext&) { return lensCamera(*database, o); },
      [this, photo](JobOutcome<LensCameraSummary> outcome) {
        const QString title = tr("Lens from database");
        if (!outcome.value || !outcome.value->status.ok) {
          const QString why = outcome.value
                                  ? QString::fromStdString(outcome.value->status.message)
                                  : outcome.error;
          if (!outcome.cancelled) showError(title, why);
          emit lensCameraApplied(false, why);
          return;
        }
        if (document_->photo() != photo) {
          emit lensCameraApplied(false, tr("the photo changed while the lens camera was made"));
          return;
        }
        LensCameraSummary& s = *outcome.value;
        // The lensfun samples are the camera's own data, not the user's pairs: they stay out of
        // the document, which takes the camera as one set by hand (like an imported one).
        Artcam camera = std::move(s.camera);
        camera.matches.clear();
        camera.fit.reset();
        document_->undoStack()->push(new SetCameraCommand(
            document_, std::move(camera),
            tr("Lens %1 at %2 mm").arg(QString::fromStdString(s.lens.model)).arg(s.focal_mm)));
        QString summary =
            tr("%1 at %2 mm: %3 camera, max %4 px against lensfun%5")
                .arg(QString::fromStdString(s.lens.model))
                .arg(s.focal_mm)
                .arg(s.piecewise ? tr("piecewise (%1 patches)").arg(s.patches) : tr("single"))
                .arg(s.max_px, 0, 'g', 3)
                .arg(s.within_tolerance ? QString() : tr(" (above the threshold)"));
        if (s.vignetting)
          summary += tr("; vignetting at f/%1, max %2 % against lensfun")
                         .arg(s.aperture)
                         .arg(s.vignetting_fit.max_percent, 0, 'g', 2);
        for (const std::string& note : s.notes)
          if (note.find("vignetting") != std::string::npos)
            summary += "; " + QString::fromStdString(note);
        emit statusMessage(summary);
        emit lensCameraApplied(true, summary);
      });
}

}  // namespace artcam::ui
