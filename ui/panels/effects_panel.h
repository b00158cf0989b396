// SPDX-License-Identifier: Apache-2.0
// The effects panel: pick one of the image effects (core/effects/
// effect_table.h), set its parameters, and see it live on the photo's preview copy. The
// parameter rows are made from the effect's row of the table: one spin box per number (a row of
// N for a vector parameter), its range, default and unit (as the suffix) from the table.
//
// Rendering runs off the GUI thread and nothing here waits for it: every change stamps a new
// generation, a trailing 80 ms timer coalesces slider drags, and the EffectsRenderWorker (the
// newest-request worker) renders the newest request; an older one is cancelled between bands
// and a result of an older generation is dropped. Results come back by queued signal.
//
// Depth: the image given to setDepth (1 channel, or the 2-channel form of core/depth/
// depth_raster.h, any size) — e.g. the studio's painted planes rasterised; otherwise a stand-in
// ramp, far at the top (1 … 100 log-spaced), which the status line says. The panel previews an
// effect on its own and does not change the document (the main preview renders the document's
// camera, colour and depth blocks included, through core's attributed renderer).
#pragma once

#include "core/effects/effect_table.h"
#include "core/model/image.h"
#include "ui/panels/effects_render_worker.h"

#include <QImage>
#include <QWidget>

#include <map>
#include <memory>
#include <string>

class QComboBox;
class QFormLayout;
class QLabel;
class QDoubleSpinBox;
class QTimer;

namespace artcam::ui {

class Document;

class EffectsPanel : public QWidget {
  Q_OBJECT

 public:
  explicit EffectsPanel(Document* document, QWidget* parent = nullptr);
  ~EffectsPanel() override;

  QString effect() const;
  void setEffect(const QString& name);
  // Sets a parameter's spin boxes (as if typed); false for an unknown name or a vector of the
  // wrong size. The spin boxes are named NAME, or NAME[i] for a vector's component i.
  bool setParameter(const QString& name, double value);
  bool setParameter(const QString& name, const std::vector<double>& value);
  EffectValues parameters() const;
  // The depth the effects read; null: the stand-in ramp.
  void setDepth(std::shared_ptr<const ImageF> depth);

  // The last rendered preview and the generation it belongs to.
  const QImage& preview() const { return preview_; }
  quint64 previewGeneration() const { return shown_generation_; }
  quint64 requestedGeneration() const { return generation_; }
  QString status() const;
  // The renderer thread (tests replace its render function before the first request).
  EffectsRenderWorker* renderWorker() { return &worker_; }

 signals:
  void previewReady(quint64 generation);

 private:
  void rebuildParameters();
  void schedule();
  void startRender();
  void deliver(quint64 generation, const QImage& image, const QString& message);

  Document* document_;
  QComboBox* effect_box_;
  QFormLayout* form_;
  QLabel* image_label_;
  QLabel* status_label_;
  QTimer* throttle_;
  std::map<std::string, std::vector<QDoubleSpinBox*>> spins_;
  QImage preview_;
  std::shared_ptr<const ImageF> depth_;
  quint64 generation_ = 0;  // GUI thread only
  quint64 shown_generation_ = 0;
  EffectsRenderWorker worker_;
};

}  // namespace artcam::ui
