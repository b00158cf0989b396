// SPDX-License-Identifier: Apache-2.0
#include "ui/fit_worker.h"

#include <QMetaObject>

#include <memory>

namespace artcam::ui {

FitWorker::FitWorker(Delivery deliver, QObject* parent)
    : NewestRequestWorker(QStringLiteral("the fit worker"), parent), deliver_(std::move(deliver)) {}

FitWorker::~FitWorker() { shutdown(); }

void FitWorker::serve(FitRequest& request) {
  auto fitted = std::make_shared<FittedCamera>(fitDocumentCamera(request.inputs));
  const quint64 revision = request.generation;
  if (!keepGoing()) return;  // a newer request is waiting: it supersedes this one
  // Queued to this object, which lives on the GUI thread; dropped if it is destroyed first.
  QMetaObject::invokeMethod(
      this, [this, fitted, revision] { deliver_(std::move(*fitted), revision); },
      Qt::QueuedConnection);
}

}  // namespace artcam::ui
