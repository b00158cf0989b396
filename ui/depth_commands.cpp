// SPDX-License-Identifier: Apache-2.0
#include "ui/depth_commands.h"

#include <QCoreApplication>

namespace artcam::ui {
namespace {

QString tr(const char* text) { return QCoreApplication::translate("depth_commands", text); }

}  // namespace

AddDepthLayerCommand::AddDepthLayerCommand(DepthModel* depth, DepthPlaneLayer layer, int index)
    : depth_(depth), layer_(std::move(layer)), index_(index < 0 ? depth->layerCount() : index) {
  setText(tr("Add depth plane"));
}
void AddDepthLayerCommand::redo() { depth_->insertLayer(index_, layer_); }
void AddDepthLayerCommand::undo() { depth_->removeLayer(index_); }

RemoveDepthLayerCommand::RemoveDepthLayerCommand(DepthModel* depth, int index)
    : depth_(depth), layer_(depth->layer(index)), index_(index) {
  setText(tr("Remove depth plane"));
}
void RemoveDepthLayerCommand::redo() { depth_->removeLayer(index_); }
void RemoveDepthLayerCommand::undo() { depth_->insertLayer(index_, layer_); }

PaintDepthMaskCommand::PaintDepthMaskCommand(DepthModel* depth, int layer, PixelRect rect,
                                             std::vector<uint8_t> before,
                                             std::vector<uint8_t> after, const QString& text)
    : depth_(depth),
      layer_(layer),
      rect_(rect),
      before_(std::move(before)),
      after_(std::move(after)) {
  setText(text);
}
void PaintDepthMaskCommand::redo() { depth_->pasteMask(layer_, rect_, after_); }
void PaintDepthMaskCommand::undo() { depth_->pasteMask(layer_, rect_, before_); }

SetDepthAnchorsCommand::SetDepthAnchorsCommand(DepthModel* depth, int layer,
                                               std::vector<DepthAnchor> anchors,
                                               const QString& text)
    : depth_(depth), layer_(layer), before_(depth->layer(layer).anchors), after_(std::move(anchors)) {
  setText(text);
}
void SetDepthAnchorsCommand::redo() { depth_->setAnchors(layer_, after_); }
void SetDepthAnchorsCommand::undo() { depth_->setAnchors(layer_, before_); }

RenameDepthLayerCommand::RenameDepthLayerCommand(DepthModel* depth, int layer, QString name)
    : depth_(depth), layer_(layer), before_(depth->layer(layer).name), after_(std::move(name)) {
  setText(tr("Rename depth plane"));
}
void RenameDepthLayerCommand::redo() { depth_->setName(layer_, after_); }
void RenameDepthLayerCommand::undo() { depth_->setName(layer_, before_); }

SetDepthMapCommand::SetDepthMapCommand(DepthModel* depth, std::optional<DepthMapSource> map)
    : depth_(depth), before_(depth->map()), after_(std::move(map)) {
  setText(after_ ? tr("Load depth map") : tr("Clear depth map"));
}
void SetDepthMapCommand::redo() { depth_->setMap(after_); }
void SetDepthMapCommand::undo() { depth_->setMap(before_); }

}  // namespace artcam::ui
