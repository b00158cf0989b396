// SPDX-License-Identifier: Apache-2.0
// The depth panel: the list of depth planes (add, remove, rename, choose the
// active one), the brush settings (radius, hardness) and the depth given to the next clicked
// point, the active plane's three depth points (depth typed here), the plane's status, the
// overlay switch and opacity, and the depth map file (load with scale / inverse, clear).
// Every edit goes through depth_commands.h; loading a file is the session's (off-thread).
#pragma once

#include <QWidget>

class QCheckBox;
class QDoubleSpinBox;
class QLabel;
class QListWidget;
class QSlider;
class QTableWidget;

namespace artcam::ui {

class DepthOverlay;
class DepthToolSettings;
class Document;

class DepthPanel : public QWidget {
  Q_OBJECT

 public:
  DepthPanel(Document* document, DepthToolSettings* settings, DepthOverlay* overlay,
             QWidget* parent = nullptr);

  QListWidget* layerList() const { return layers_; }
  QTableWidget* anchorTable() const { return anchors_; }
  QString statusText() const;
  double mapScale() const;
  bool mapInverse() const;

 public slots:
  void addLayer();
  void removeActiveLayer();

 signals:
  // The user asked to load a depth map file (the session shows the dialog and loads it).
  void loadDepthMapRequested();

 private:
  void rebuildLayers();
  void rebuildAnchors();
  void onAnchorEdited(int row, int column);

  Document* document_;
  DepthToolSettings* settings_;
  DepthOverlay* overlay_;
  QListWidget* layers_;
  QTableWidget* anchors_;
  QLabel* status_;
  QLabel* map_label_;
  QDoubleSpinBox* radius_;
  QSlider* hardness_;
  QDoubleSpinBox* next_depth_;
  QDoubleSpinBox* map_scale_;
  QCheckBox* map_inverse_;
  bool syncing_ = false;
};

}  // namespace artcam::ui
