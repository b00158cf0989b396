// SPDX-License-Identifier: Apache-2.0
// The main window assembles only: it creates the document, canvas, panels, preview
// and session, lays them out in docks, makes the menus, toolbars and shortcuts, and wires
// signals. Editing logic lives in the tools, commands and document; file logic in Session.
#pragma once

#include "core/model/image.h"

#include <QMainWindow>

#include <memory>

class QMenu;

namespace artcam::ui {

class Canvas;
class CloudView;
class ColourDock;
class DepthOverlay;
class DepthPanel;
class DepthToolSettings;
class Document;
class FitStatus;
class PairsPanel;
class PreviewController;
class PreviewView;
class Session;
class ToolSwitcher;

class MainWindow : public QMainWindow {
  Q_OBJECT

 public:
  explicit MainWindow(QWidget* parent = nullptr);
  ~MainWindow() override;

  Document* document() const { return document_; }
  Canvas* canvas() const { return canvas_; }
  Session* session() const { return session_; }
  PreviewController* preview() const { return preview_; }
  PreviewView* previewView() const { return preview_view_; }
  PairsPanel* pairsPanel() const { return pairs_panel_; }
  FitStatus* fitStatus() const { return fit_status_; }
  DepthPanel* depthPanel() const { return depth_panel_; }
  CloudView* cloudView() const { return cloud_view_; }
  ColourDock* colourDock() const { return colour_dock_; }
  DepthOverlay* depthOverlay() const { return depth_overlay_; }
  DepthToolSettings* depthToolSettings() const { return depth_settings_; }
  ToolSwitcher* toolSwitcher() const { return tool_switcher_; }

 protected:
  void closeEvent(QCloseEvent* event) override;
  void dragEnterEvent(QDragEnterEvent* event) override;
  void dropEvent(QDropEvent* event) override;

 private:
  void createMenus();
  void createToolActions(QMenu* menu, class QToolBar* bar);
  void rebuildRecentMenu();
  void updateTitle();

  Document* document_;
  PreviewController* preview_;
  Canvas* canvas_;
  PreviewView* preview_view_;
  PairsPanel* pairs_panel_;
  FitStatus* fit_status_;
  Session* session_;
  DepthToolSettings* depth_settings_;
  DepthOverlay* depth_overlay_;
  DepthPanel* depth_panel_;
  CloudView* cloud_view_;
  ColourDock* colour_dock_ = nullptr;
  QMenu* recent_menu_ = nullptr;
  ToolSwitcher* tool_switcher_ = nullptr;
  bool close_accepted_ = false;  // the save prompt let the window close (closeEvent)
};

}  // namespace artcam::ui
