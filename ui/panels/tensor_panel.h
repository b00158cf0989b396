// SPDX-License-Identifier: Apache-2.0
// The tensor panel: every entry of every Q_i of the camera, one table per output element,
// rows and columns labelled by block element (Q_i is symmetric N×N over the
// blocks of x). Typing an entry sets Q_i(r, c) and Q_i(c, r) — storage is symmetric — and
// pushes one SetCameraCommand, which makes the camera "set by hand" until the user goes back
// to the fitted one. Presets: the identity, and every image effect of core's effects table
// (core/effects/effect_table.h) that needs neither depth nor a second image, under its human
// name: applied, a preset is the table's builder at its defaults in the photo's frame, the
// camera `artcam preset NAME --size W×H` writes (its pole check and refusals included), set by
// hand as the whole camera in one SetCameraCommand. A cell shows its entry rounded (tiny
// round-off as 0); its tooltip names the term the entry weighs, its blocks and the exact value.
#pragma once

#include "core/effects/effect_table.h"
#include "core/model/camera.h"

#include <QString>
#include <QWidget>

#include <utility>
#include <vector>

class QComboBox;
class QLabel;
class QTableWidget;
class QVBoxLayout;

namespace artcam::ui {

class Document;

class TensorPanel : public QWidget {
  Q_OBJECT

 public:
  explicit TensorPanel(Document* document, QWidget* parent = nullptr);

  // Tables in output-element order (stage 0); exposed for tests.
  const std::vector<QTableWidget*>& tables() const { return tables_; }
  // Sets entry (row, col) of Q_element in `stage` through an undo command.
  void setEntry(int stage, int element, int row, int col, double value);
  // "identity" or an effect's name ("barrel"), at the table's defaults overridden by `values`.
  // Returns "" when applied, else why nothing was (no photo, unknown name, the table's or the
  // camera's refusal), which the panel also shows beneath its presets.
  QString applyPreset(const QString& name, const EffectValues& values = {});
  // The presets offered, in order: (name, human name).
  std::vector<std::pair<QString, QString>> presets() const;
  // One line on the whole camera: its kind, layers, blocks, depth output and effects; the
  // tables below edit the geometry (the first layer), every other part is kept as it is.
  QString summary() const;
  // A cell's text: |value| < kZeroBelow is "0", else six significant digits ("0.123457").
  static constexpr double kZeroBelow = 1e-12;
  static QString entryText(double value);

 private:
  void rebuild();
  void refresh();

  Document* document_;
  QComboBox* stage_box_;
  QComboBox* preset_box_;
  QLabel* preset_message_;
  QVBoxLayout* tables_layout_;
  QLabel* summary_label_;
  std::vector<QTableWidget*> tables_;
  int built_dimension_ = -1;
  int built_stages_ = -1;
  bool updating_ = false;
};

}  // namespace artcam::ui
