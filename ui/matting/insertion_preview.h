// SPDX-License-Identifier: Apache-2.0
// Keeps the Insertion fit and preview current: after every change of the insertion state or
// the photo it stamps a request with a new generation and hands it to the InsertionWorker
// (newest wins); results older than what is shown are dropped. The GUI thread never waits
// for a fit or a render.
#pragma once

#include "ui/matting/insertion_worker.h"

#include <QImage>
#include <QObject>

namespace artcam::ui {

class Document;
class InsertionModel;

class InsertionPreview : public QObject {
  Q_OBJECT

 public:
  InsertionPreview(InsertionModel* model, QObject* parent = nullptr);
  ~InsertionPreview() override;

  const InsertionFit& fit() const { return fit_; }
  // The graphic composited over the photo (photo pixels); null when there is nothing to show.
  const QImage& composite() const { return composite_; }
  quint64 requestedGeneration() const { return requested_; }
  quint64 fitGeneration() const { return fit_generation_; }
  quint64 compositeGeneration() const { return composite_generation_; }
  // The newest request's fit has arrived (and its preview, when it will have one).
  bool isCurrent() const;
  // Stops the worker (waits for a fit in flight); later edits are ignored.
  void shutdown();

 public slots:
  void refresh();

 signals:
  void requested();  // a new fit/preview is on its way (isCurrent() is false until it arrives)
  void fitChanged();
  void compositeChanged();
  void failed(const QString& message);

 private:
  void onFitted(const InsertionFit& fit, quint64 generation);
  void onRendered(const QImage& image, quint64 generation);

  InsertionModel* model_;
  InsertionWorker* worker_;
  bool stopped_ = false;
  quint64 requested_ = 0;
  bool requested_renders_ = false;  // the newest request will produce a composite
  InsertionFit fit_;
  quint64 fit_generation_ = 0;
  QImage composite_;
  quint64 composite_generation_ = 0;
};

}  // namespace artcam::ui
