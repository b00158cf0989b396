// SPDX-License-Identifier: Apache-2.0
#include "ui/fit_worker.h"

#include <QMetaObject>

#include <memory>

namespace artcam::ui {

FitWorker::FitWorker(Delivery deliver, QObject* parent)
    : QThread(parent), deliver_(std::move(deliver)) {}

FitWorker::~FitWorker() { slot_.shutdown(*this); }

void FitWorker::run() {
  for (;;) {
    std::optional<FitRequest> next = slot_.take();
    if (!next) return;
    auto fitted = std::make_shared<FittedCamera>(fitDocumentCamera(next->inputs));
    const quint64 revision = next->revision;
    if (!slot_.keepGoing()) continue;  // a newer request is waiting: it supersedes this one
    // Queued to this object, which lives on the GUI thread; dropped if it is destroyed first.
    QMetaObject::invokeMethod(
        this, [this, fitted, revision] { deliver_(std::move(*fitted), revision); },
        Qt::QueuedConnection);
  }
}

}  // namespace artcam::ui
