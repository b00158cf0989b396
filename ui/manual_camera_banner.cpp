// SPDX-License-Identifier: Apache-2.0
#include "ui/manual_camera_banner.h"

#include "ui/commands.h"
#include "ui/document.h"

#include <QEvent>
#include <QHBoxLayout>
#include <QLabel>
#include <QPushButton>

#include <optional>

namespace artcam::ui {

ManualCameraBanner::ManualCameraBanner(Document* document, QWidget* canvas)
    : QFrame(canvas),
      document_(document),
      label_(new QLabel(tr("Camera set by hand — pairs not fitted"), this)),
      fit_again_(new QPushButton(tr("Fit again"), this)) {
  setObjectName(QStringLiteral("manualCameraBanner"));
  setAutoFillBackground(true);
  setStyleSheet(QStringLiteral("#manualCameraBanner { background: rgba(70, 56, 20, 230); }"
                               "#manualCameraBanner QLabel { color: #ffe08a; }"));
  setToolTip(tr("The camera was edited by hand (tensor entries, a preset or an imported .artcam), "
                "so it is not fitted to the pairs: their markers are drawn neutral, as their "
                "residuals measure a camera nobody fitted to them. Fit again returns to the "
                "camera fitted to the pairs (undoable)."));
  fit_again_->setToolTip(tr("Use the camera fitted to the pairs again (Model ▸ Use Fitted Camera)"));
  auto* layout = new QHBoxLayout(this);
  layout->setContentsMargins(10, 4, 6, 4);
  layout->addWidget(label_, 1);
  layout->addWidget(fit_again_);
  connect(fit_again_, &QPushButton::clicked, this, [this] {
    if (document_->manualCamera())
      document_->undoStack()->push(
          new SetCameraCommand(document_, std::nullopt, tr("Fit camera to pairs again")));
  });
  connect(document_, &Document::cameraChanged, this, &ManualCameraBanner::sync);
  connect(document_, &Document::photoChanged, this, &ManualCameraBanner::sync);
  canvas->installEventFilter(this);
  place();
  sync();
}

QString ManualCameraBanner::text() const { return label_->text(); }

void ManualCameraBanner::sync() {
  const bool show = document_->photo() != nullptr && document_->manualCamera().has_value();
  setVisible(show);
  if (show) raise();
}

void ManualCameraBanner::place() {
  if (QWidget* p = parentWidget()) setGeometry(0, 0, p->width(), sizeHint().height());
}

bool ManualCameraBanner::eventFilter(QObject* watched, QEvent* event) {
  if (watched == parentWidget() && event->type() == QEvent::Resize) place();
  return QFrame::eventFilter(watched, event);
}

}  // namespace artcam::ui
