// SPDX-License-Identifier: Apache-2.0
// Undo commands for depth planes (every edit is a QUndoCommand storing old and new
// values). Mask edits store only the rectangle a stroke or polygon touched, before and after:
// a full mask is a byte per photo pixel, too much to copy per step.
#pragma once

#include "ui/depth_model.h"

#include <QUndoCommand>

#include <optional>
#include <vector>

namespace artcam::ui {

class AddDepthLayerCommand : public QUndoCommand {
 public:
  AddDepthLayerCommand(DepthModel* depth, DepthPlaneLayer layer, int index = -1);  // -1: append
  void redo() override;
  void undo() override;

 private:
  DepthModel* depth_;
  DepthPlaneLayer layer_;
  int index_;
};

class RemoveDepthLayerCommand : public QUndoCommand {
 public:
  RemoveDepthLayerCommand(DepthModel* depth, int index);
  void redo() override;
  void undo() override;

 private:
  DepthModel* depth_;
  DepthPlaneLayer layer_;
  int index_;
};

// A finished stroke or polygon: `before` and `after` are the bytes of `rect`. The first redo
// (on push) writes `after`, which a live stroke has already painted: harmless and exact.
class PaintDepthMaskCommand : public QUndoCommand {
 public:
  PaintDepthMaskCommand(DepthModel* depth, int layer, PixelRect rect, std::vector<uint8_t> before,
                        std::vector<uint8_t> after, const QString& text);
  void redo() override;
  void undo() override;

 private:
  DepthModel* depth_;
  int layer_;
  PixelRect rect_;
  std::vector<uint8_t> before_;
  std::vector<uint8_t> after_;
};

// Placing, moving or re-valuing the depth points of a layer (the whole list before and after).
class SetDepthAnchorsCommand : public QUndoCommand {
 public:
  SetDepthAnchorsCommand(DepthModel* depth, int layer, std::vector<DepthAnchor> anchors,
                         const QString& text);
  void redo() override;
  void undo() override;

 private:
  DepthModel* depth_;
  int layer_;
  std::vector<DepthAnchor> before_;
  std::vector<DepthAnchor> after_;
};

class RenameDepthLayerCommand : public QUndoCommand {
 public:
  RenameDepthLayerCommand(DepthModel* depth, int layer, QString name);
  void redo() override;
  void undo() override;

 private:
  DepthModel* depth_;
  int layer_;
  QString before_;
  QString after_;
};

// Loading (or clearing, with nullopt) the depth map file under the layers.
class SetDepthMapCommand : public QUndoCommand {
 public:
  SetDepthMapCommand(DepthModel* depth, std::optional<DepthMapSource> map);
  void redo() override;
  void undo() override;

 private:
  DepthModel* depth_;
  std::optional<DepthMapSource> before_;
  std::optional<DepthMapSource> after_;
};

}  // namespace artcam::ui
