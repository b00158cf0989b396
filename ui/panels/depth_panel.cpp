// SPDX-License-Identifier: Apache-2.0
#include "ui/panels/depth_panel.h"

#include "ui/depth_commands.h"
#include "ui/depth_overlay.h"
#include "ui/document.h"
#include "ui/tools/depth_tool_settings.h"

#include <QCheckBox>
#include <QDoubleSpinBox>
#include <QFileInfo>
#include <QFormLayout>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QListWidget>
#include <QPushButton>
#include <QSignalBlocker>
#include <QSlider>
#include <QTableWidget>
#include <QVBoxLayout>

#include <cmath>

namespace artcam::ui {

namespace {

// Shows a setting in its box only when the box shows another value: setValue re-formats the
// text, so the settings' echo of a box's own keystroke would turn a typed "1" into "1.000" with
// the cursor after the 1, and the ".5" typed next would be refused (typing 1.5 gave 1).
void showInBox(QDoubleSpinBox* box, double value) {
  if (box->valueFromText(box->textFromValue(value)) != box->value()) box->setValue(value);
}

}  // namespace

DepthPanel::DepthPanel(Document* document, DepthToolSettings* settings, DepthOverlay* overlay,
                       QWidget* parent)
    : QWidget(parent),
      document_(document),
      settings_(settings),
      overlay_(overlay),
      layers_(new QListWidget(this)),
      anchors_(new QTableWidget(DepthModel::kAnchorCount, 3, this)),
      status_(new QLabel(this)),
      map_label_(new QLabel(this)),
      radius_(new QDoubleSpinBox(this)),
      hardness_(new QSlider(Qt::Horizontal, this)),
      next_depth_(new QDoubleSpinBox(this)),
      map_scale_(new QDoubleSpinBox(this)),
      map_inverse_(new QCheckBox(tr("Inverse depth"), this)) {
  auto* layout = new QVBoxLayout(this);

  // Planes.
  layers_->setToolTip(tr("Depth planes: later ones lie on top. Double-click to rename."));
  layers_->setMaximumHeight(110);
  auto* add = new QPushButton(tr("Add plane"), this);
  add->setToolTip(tr("A new empty region to paint (then give it depth at three points)"));
  auto* remove = new QPushButton(tr("Remove"), this);
  remove->setToolTip(tr("Remove the selected depth plane"));
  auto* buttons = new QHBoxLayout;
  buttons->addWidget(add);
  buttons->addWidget(remove);
  layout->addWidget(layers_);
  layout->addLayout(buttons);

  // Brush and depth point settings.
  auto* form = new QFormLayout;
  radius_->setRange(DepthToolSettings::kMinRadius, DepthToolSettings::kMaxRadius);
  radius_->setDecimals(1);
  radius_->setSuffix(tr(" px"));
  radius_->setValue(settings_->radius());
  radius_->setToolTip(tr("Brush radius in photo pixels ([ and ] change it)"));
  hardness_->setRange(0, 100);
  hardness_->setValue(static_cast<int>(std::lround(settings_->hardness() * 100)));
  hardness_->setToolTip(tr("Share of the brush that is fully opaque; the rest fades out"));
  next_depth_->setRange(1e-4, 1e7);
  next_depth_->setDecimals(3);
  next_depth_->setValue(settings_->nextDepth());
  next_depth_->setToolTip(tr("Depth given to the next depth point you click (any unit)"));
  next_depth_->setObjectName(QStringLiteral("nextDepth"));
  form->addRow(tr("Radius"), radius_);
  form->addRow(tr("Hardness"), hardness_);
  auto* edges = new QCheckBox(tr("Stop at colour edges"), this);
  edges->setObjectName(QStringLiteral("edgeAwareBrush"));
  edges->setChecked(settings_->edgeAware());
  edges->setToolTip(tr("Edge-aware brush: a stroke paints only pixels of the brush connected to "
                       "where it began through similar colours, so it does not spill over edges"));
  auto* tolerance = new QDoubleSpinBox(this);
  tolerance->setObjectName(QStringLiteral("edgeTolerance"));
  tolerance->setRange(0.0, 2.0);
  tolerance->setDecimals(2);
  tolerance->setSingleStep(0.02);
  tolerance->setValue(settings_->edgeTolerance());
  tolerance->setToolTip(tr("How far a colour may be from the stroke's first pixel (linear RGB "
                           "distance) and still be painted"));
  form->addRow(edges);
  form->addRow(tr("Edge tolerance"), tolerance);
  connect(edges, &QCheckBox::toggled, settings_, &DepthToolSettings::setEdgeAware);
  connect(tolerance, &QDoubleSpinBox::valueChanged, settings_,
          &DepthToolSettings::setEdgeTolerance);
  connect(settings_, &DepthToolSettings::changed, this, [this, edges, tolerance] {
    const QSignalBlocker b1(edges), b2(tolerance);
    edges->setChecked(settings_->edgeAware());
    showInBox(tolerance, settings_->edgeTolerance());
  });
  // Alt+N reaches the field from anywhere in the window while the panel shows: a depth is typed
  // before each clicked point, between clicks on the canvas.
  form->addRow(tr("&Next depth"), next_depth_);
  layout->addLayout(form);

  // The active plane's depth points.
  anchors_->setHorizontalHeaderLabels({tr("x"), tr("y"), tr("depth")});
  anchors_->horizontalHeader()->setSectionResizeMode(QHeaderView::Stretch);
  anchors_->verticalHeader()->setVisible(true);
  anchors_->setMaximumHeight(120);
  anchors_->setToolTip(tr("Depth points of the selected plane: type a depth to change it"));
  layout->addWidget(anchors_);
  status_->setWordWrap(true);
  layout->addWidget(status_);

  // Overlay.
  auto* show = new QCheckBox(tr("Show depth overlay"), this);
  show->setChecked(overlay_->isVisible());
  show->setToolTip(tr("Colour the photo by depth: red near, blue far"));
  auto* opacity = new QSlider(Qt::Horizontal, this);
  opacity->setRange(0, 100);
  opacity->setValue(static_cast<int>(std::lround(overlay_->opacity() * 100)));
  opacity->setToolTip(tr("Opacity of the depth overlay"));
  layout->addWidget(show);
  layout->addWidget(opacity);

  // Depth map file.
  auto* map_box = new QGroupBox(tr("Depth map file"), this);
  auto* map_layout = new QFormLayout(map_box);
  map_scale_->setRange(1e-9, 1e9);
  map_scale_->setDecimals(6);
  map_scale_->setValue(1.0);
  map_scale_->setToolTip(
      tr("Depth per stored count of an integer (16-bit PNG/TIFF) file, e.g. 0.001 for "
         "millimetres read as metres; float EXR/TIFF files are read as stored"));
  map_inverse_->setToolTip(tr("The file stores inverse depth (disparity-like)"));
  auto* load = new QPushButton(tr("Load…"), map_box);
  load->setToolTip(tr("Load a float EXR/TIFF or 16-bit PNG depth map under the planes"));
  auto* clear = new QPushButton(tr("Clear"), map_box);
  map_layout->addRow(tr("Scale"), map_scale_);
  map_layout->addRow(map_inverse_);
  auto* map_buttons = new QHBoxLayout;
  map_buttons->addWidget(load);
  map_buttons->addWidget(clear);
  map_layout->addRow(map_buttons);
  map_layout->addRow(map_label_);
  layout->addWidget(map_box);
  layout->addStretch(1);

  DepthModel* depth = document_->depth();
  connect(add, &QPushButton::clicked, this, &DepthPanel::addLayer);
  connect(remove, &QPushButton::clicked, this, &DepthPanel::removeActiveLayer);
  connect(layers_, &QListWidget::currentRowChanged, this, [this](int row) {
    if (!syncing_) document_->depth()->setActiveLayer(row);
  });
  connect(layers_, &QListWidget::itemChanged, this, [this](QListWidgetItem* item) {
    if (syncing_) return;
    const int row = layers_->row(item);
    if (row >= 0 && row < document_->depth()->layerCount() &&
        item->text() != document_->depth()->layer(row).name && !item->text().isEmpty())
      document_->undoStack()->push(
          new RenameDepthLayerCommand(document_->depth(), row, item->text()));
  });
  connect(radius_, &QDoubleSpinBox::valueChanged, settings_, &DepthToolSettings::setRadius);
  connect(hardness_, &QSlider::valueChanged, this,
          [this](int v) { settings_->setHardness(v / 100.0); });
  connect(next_depth_, &QDoubleSpinBox::valueChanged, settings_,
          &DepthToolSettings::setNextDepth);
  connect(settings_, &DepthToolSettings::changed, this, [this] {
    // Shown, not fed back: the boxes round (one decimal) and must not round the settings.
    const QSignalBlocker b1(radius_), b2(hardness_), b3(next_depth_);
    showInBox(radius_, settings_->radius());
    hardness_->setValue(static_cast<int>(std::lround(settings_->hardness() * 100)));
    showInBox(next_depth_, settings_->nextDepth());
  });
  connect(anchors_, &QTableWidget::cellChanged, this, &DepthPanel::onAnchorEdited);
  connect(show, &QCheckBox::toggled, overlay_, &DepthOverlay::setVisible);
  connect(overlay_, &DepthOverlay::changed, show,
          [this, show] { show->setChecked(overlay_->isVisible()); });
  connect(opacity, &QSlider::valueChanged, this,
          [this](int v) { overlay_->setOpacity(v / 100.0); });
  connect(load, &QPushButton::clicked, this, &DepthPanel::loadDepthMapRequested);
  connect(clear, &QPushButton::clicked, this, [this] {
    if (document_->depth()->map())
      document_->undoStack()->push(new SetDepthMapCommand(document_->depth(), std::nullopt));
  });
  connect(depth, &DepthModel::layersChanged, this, &DepthPanel::rebuildLayers);
  connect(depth, &DepthModel::activeLayerChanged, this, [this] {
    rebuildLayers();
  });
  connect(depth, &DepthModel::depthChanged, this, &DepthPanel::rebuildAnchors);
  rebuildLayers();
}

QString DepthPanel::statusText() const { return status_->text(); }
double DepthPanel::mapScale() const { return map_scale_->value(); }
bool DepthPanel::mapInverse() const { return map_inverse_->isChecked(); }

void DepthPanel::addLayer() {
  if (!document_->photo()) return;
  DepthModel* depth = document_->depth();
  document_->undoStack()->push(new AddDepthLayerCommand(depth, depth->makeLayer()));
}

void DepthPanel::removeActiveLayer() {
  DepthModel* depth = document_->depth();
  if (depth->activeLayer() >= 0)
    document_->undoStack()->push(new RemoveDepthLayerCommand(depth, depth->activeLayer()));
}

void DepthPanel::rebuildLayers() {
  const DepthModel* depth = document_->depth();
  syncing_ = true;
  layers_->clear();
  for (const DepthPlaneLayer& l : depth->layers()) {
    auto* item = new QListWidgetItem(l.name, layers_);
    item->setFlags(item->flags() | Qt::ItemIsEditable);
  }
  layers_->setCurrentRow(depth->activeLayer());
  syncing_ = false;
  if (const auto& map = depth->map())
    map_label_->setText(tr("%1 (scale %2%3)")
                            .arg(QFileInfo(map->path).fileName())
                            .arg(map->options.scale)
                            .arg(map->options.inverse ? tr(", inverse") : QString()));
  else
    map_label_->setText(tr("No depth map loaded"));
  rebuildAnchors();
}

void DepthPanel::rebuildAnchors() {
  const DepthModel* depth = document_->depth();
  const int layer = depth->activeLayer();
  syncing_ = true;
  anchors_->blockSignals(true);
  for (int row = 0; row < DepthModel::kAnchorCount; ++row)
    for (int col = 0; col < 3; ++col) {
      auto* item = new QTableWidgetItem;
      const bool has = layer >= 0 && row < static_cast<int>(depth->layer(layer).anchors.size());
      if (has) {
        const DepthAnchor& a = depth->layer(layer).anchors[static_cast<size_t>(row)];
        const double v = col == 0 ? a.pixel.x() : col == 1 ? a.pixel.y() : a.depth;
        item->setText(QString::number(v, 'g', col == 2 ? 8 : 6));
      }
      Qt::ItemFlags flags = Qt::ItemIsEnabled | Qt::ItemIsSelectable;
      if (has && col == 2) flags |= Qt::ItemIsEditable;
      item->setFlags(flags);
      anchors_->setItem(row, col, item);
    }
  anchors_->blockSignals(false);
  syncing_ = false;
  if (layer < 0)
    status_->setText(document_->photo() ? tr("Paint a region (B), then click three depth points (D).")
                                        : QString());
  else
    status_->setText(depth->planeStatus(layer));
}

void DepthPanel::onAnchorEdited(int row, int column) {
  if (syncing_ || column != 2) return;
  DepthModel* depth = document_->depth();
  const int layer = depth->activeLayer();
  if (layer < 0 || row >= static_cast<int>(depth->layer(layer).anchors.size())) return;
  bool ok = false;
  const double value = anchors_->item(row, column)->text().toDouble(&ok);
  std::vector<DepthAnchor> anchors = depth->layer(layer).anchors;
  if (!ok || !(value > 0.0) || !std::isfinite(value) ||
      value == anchors[static_cast<size_t>(row)].depth) {
    rebuildAnchors();  // refused: show the old value again
    return;
  }
  anchors[static_cast<size_t>(row)].depth = value;
  document_->undoStack()->push(
      new SetDepthAnchorsCommand(depth, layer, std::move(anchors), tr("Set point depth")));
}

}  // namespace artcam::ui
