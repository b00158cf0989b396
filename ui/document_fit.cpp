// SPDX-License-Identifier: Apache-2.0
#include "ui/document_fit.h"

#include <QCoreApplication>
#include <QThread>

#include <atomic>

namespace artcam::ui {
namespace {

std::atomic<long> g_fits_on_gui{0};
std::atomic<long> g_fits_elsewhere{0};

void countFit() {
  const QCoreApplication* app = QCoreApplication::instance();
  if (app && QThread::currentThread() == app->thread())
    ++g_fits_on_gui;
  else
    ++g_fits_elsewhere;
}

}  // namespace

FitThreadCounts fitThreadCounts() { return {g_fits_on_gui.load(), g_fits_elsewhere.load()}; }

FittedCamera fitDocumentCamera(const FitInputs& inputs) {
  countFit();
  return fitDocumentGeometry(inputs);
}

}  // namespace artcam::ui
