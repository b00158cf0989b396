// SPDX-License-Identifier: Apache-2.0
// The tensor panel: every entry of every Q_i of the camera, one table per output element,
// rows and columns labelled by block element (Q_i is symmetric N×N over the
// blocks of x). Typing an entry sets Q_i(r, c) and Q_i(c, r) — storage is symmetric — and
// pushes one SetCameraCommand, which makes the camera "set by hand" until the user goes back
// to the fitted one. Presets: identity, barrel, pincushion.
#pragma once

#include "core/model/camera.h"

#include <QWidget>

#include <vector>

class QComboBox;
class QLabel;
class QTableWidget;
class QVBoxLayout;

namespace artcam::ui {

class Document;

// Radial distortion as an RTcam in the normalised frame: u' = u / (1 - k r²) (likewise v), so
// k > 0 pushes the corners out (pincushion) and k < 0 pulls them in (barrel). The denominator
// stays positive over the frame for |k| < 0.5 since r² ≤ 2 there.
Camera radialCamera(double k, FrameSize frame);

class TensorPanel : public QWidget {
  Q_OBJECT

 public:
  static constexpr double kPresetStrength = 0.15;

  explicit TensorPanel(Document* document, QWidget* parent = nullptr);

  // Tables in output-element order (stage 0); exposed for tests.
  const std::vector<QTableWidget*>& tables() const { return tables_; }
  // Sets entry (row, col) of Q_element in `stage` through an undo command.
  void setEntry(int stage, int element, int row, int col, double value);
  void applyPreset(const QString& name);  // "identity", "barrel", "pincushion"
  // One line on the whole camera: its kind, layers, blocks, depth output and effects; the
  // tables below edit the geometry (the first layer), every other part is kept as it is.
  QString summary() const;

 private:
  void rebuild();
  void refresh();

  Document* document_;
  QComboBox* stage_box_;
  QComboBox* preset_box_;
  QVBoxLayout* tables_layout_;
  QLabel* summary_label_;
  std::vector<QTableWidget*> tables_;
  int built_dimension_ = -1;
  int built_stages_ = -1;
  bool updating_ = false;
};

}  // namespace artcam::ui
