// SPDX-License-Identifier: Apache-2.0
#include "ui/fit_status.h"

#include "core/model/structure.h"
#include "ui/document.h"
#include "ui/fit_explanation.h"
#include "ui/preview_controller.h"

#include <QHBoxLayout>
#include <QLabel>
#include <QPointF>
#include <QProgressBar>

#include <algorithm>

namespace artcam::ui {

FitStatus::FitStatus(Document* document, PreviewController* preview, QWidget* parent)
    : QWidget(parent),
      document_(document),
      preview_(preview),
      cursor_(new QLabel(this)),
      model_(new QLabel(this)),
      residual_(new QLabel(this)),
      render_(new QLabel(this)),
      progress_(new QProgressBar(this)) {
  progress_->setRange(0, 100);
  progress_->setMaximumWidth(160);
  progress_->setFormat(tr("Loading %p%"));
  progress_->hide();
  auto* layout = new QHBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  layout->addWidget(progress_);
  layout->addWidget(cursor_);
  layout->addWidget(model_);
  layout->addWidget(residual_);
  layout->addWidget(render_);
  connect(document_, &Document::cameraChanged, this, &FitStatus::updateFit);
  // A position in the old photo's pixels says nothing about the new one.
  connect(document_, &Document::photoChanged, cursor_, &QLabel::clear);
  connect(preview_, &PreviewController::previewChanged, this, &FitStatus::updateRender);
  updateFit();
  updateRender();
}

QString FitStatus::modelText() const { return model_->text(); }
QString FitStatus::residualText() const { return residual_->text(); }
QString FitStatus::renderText() const { return render_->text(); }
QString FitStatus::cursorText() const { return cursor_->text(); }
bool FitStatus::isLoadProgressShown() const { return !progress_->isHidden(); }

void FitStatus::setLoadProgress(int percent) {
  progress_->setVisible(percent >= 0);
  if (percent >= 0) progress_->setValue(percent);
}

void FitStatus::setCursorPosition(const QPointF& p) {
  const FrameSize f = document_->frame();
  const bool inside = p.x() >= 0 && p.y() >= 0 && p.x() < f.width && p.y() < f.height;
  cursor_->setText(inside ? tr("%1, %2 px").arg(p.x(), 0, 'f', 1).arg(p.y(), 0, 'f', 1)
                          : QString());
}

void FitStatus::updateFit() {
  const FitSummary& fit = document_->fit();
  if (!document_->photo()) {
    // Nothing is fitted before there is a photo: no model to name, no figures.
    model_->setText(QString());
    model_->setToolTip(QString());
    residual_->setText(QString());
    residual_->setToolTip(QString());
    return;
  }
  if (document_->manualCamera()) {
    model_->setText(
        tr("Camera: set by hand (%1)")
            .arg(QString::fromStdString(analyseStructure(document_->camera()).summary)));
  } else if (fit.status.ok) {
    // Under auto, say what the ladder chose; the reason is in the tooltip.
    const QString chosen = QString::fromStdString(fit.record.model);
    model_->setText(document_->model() == ModelClass::Auto ? tr("Model: auto → %1").arg(chosen)
                                                           : tr("Model: %1").arg(chosen));
    // The reason and every model's error, as in the Pairs panel.
    model_->setToolTip(QStringLiteral("<p>%1</p>%2").arg(fitReasonText(fit.record).toHtmlEscaped(),
                                                         modelScoresHtml(fit.record)));
  } else {
    model_->setText(tr("Model: none (identity)"));
  }
  if (fit.status.ok && !document_->manualCamera() && !document_->lineBows().empty()) {
    // A line fit: how straight the lines came out, then the pairs' residuals if there are any.
    double bow = 0.0;
    for (const LineBow& b : document_->lineBows()) bow = std::max(bow, b.max_px);
    QString text = tr("%n line(s): bow max %1 px", nullptr,
                      static_cast<int>(document_->lineBows().size()))
                       .arg(bow, 0, 'f', 2);
    if (fit.record.matches > 0)
      text += tr(" · pairs RMS %1 px · max %2 px")
                  .arg(fit.record.rms_px, 0, 'f', 2)
                  .arg(fit.record.max_px, 0, 'f', 2);
    residual_->setText(text);
  } else if (fit.status.ok && !document_->manualCamera())
    residual_->setText(tr("RMS %1 px · max %2 px")
                           .arg(fit.record.rms_px, 0, 'f', 2)
                           .arg(fit.record.max_px, 0, 'f', 2));
  else if (document_->manualCamera() && !document_->pairs().empty())
    residual_->setText(tr("Pairs not fitted (markers neutral)"));
  else
    residual_->setText(QString());
  if (document_->manualCamera())
    residual_->setToolTip(tr("The camera is set by hand, not fitted to the pairs, so their "
                             "markers are drawn neutral instead of by residual; Fit again "
                             "(over the canvas) or Model ▸ Use Fitted Camera fits them again"));
  else
    residual_->setToolTip(
        QString::fromStdString(fit.status.ok ? fit.report() : fit.status.message));
}

void FitStatus::updateRender() {
  if (preview_->image().isNull()) {
    render_->setText(QString());
    return;
  }
  render_->setText(tr("Preview %1 ms%2")
                       .arg(preview_->lastRenderMs(), 0, 'f', 0)
                       .arg(preview_->imageIsFinal() ? QString() : tr(" (coarse)")));
}

}  // namespace artcam::ui
