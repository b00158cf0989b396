// SPDX-License-Identifier: Apache-2.0
#include "ui/main_window.h"

#include "ui/canvas.h"
#include "ui/canvas_view_actions.h"
#include "ui/cloud_view.h"
#include "ui/colour/colour_dock.h"
#include "ui/commands.h"
#include "ui/depth_overlay.h"
#include "ui/document.h"
#include "ui/fit_status.h"
#include "ui/help_dialogs.h"
#include "ui/line_commands.h"
#include "ui/manual_camera_banner.h"
#include "ui/matting/insertion_studio.h"
#include "ui/panels/depth_panel.h"
#include "ui/panels/effects_panel.h"
#include "ui/panels/lines_panel.h"
#include "ui/panels/pairs_panel.h"
#include "ui/panels/tensor_panel.h"
#include "ui/preview_controller.h"
#include "ui/preview_view.h"
#include "ui/session.h"
#include "ui/space_pan.h"
#include "ui/studio_wording.h"
#include "ui/tool_switcher.h"
#include "ui/tools/depth_tool.h"
#include "ui/tools/depth_tool_settings.h"
#include "ui/tools/line_tool.h"
#include "ui/tools/pair_tool.h"
#include "ui/unfold/unfold_studio.h"

#include <QAction>
#include <QActionGroup>
#include <QApplication>
#include <QCloseEvent>
#include <QDockWidget>
#include <QDragEnterEvent>
#include <QDropEvent>
#include <QFileInfo>
#include <QKeySequence>
#include <QLabel>
#include <QMenu>
#include <QMenuBar>
#include <QMessageBox>
#include <QMimeData>
#include <QSettings>
#include <QStatusBar>
#include <QToolBar>
#include <QUrl>

#include <functional>
#include <memory>
#include <optional>

namespace artcam::ui {
namespace {

const char kGeometryKey[] = "window/geometry";
const char kStateKey[] = "window/state";

}  // namespace

MainWindow::MainWindow(QWidget* parent)
    : QMainWindow(parent),
      document_(new Document(this)),
      preview_(new PreviewController(document_, this)),
      canvas_(new Canvas(document_, this)),
      preview_view_(new PreviewView(document_, preview_, this)),
      pairs_panel_(new PairsPanel(document_, this)),
      fit_status_(new FitStatus(document_, preview_, this)),
      session_(new Session(document_, this, this)),
      depth_settings_(new DepthToolSettings(this)),
      depth_overlay_(new DepthOverlay(document_, this)),
      depth_panel_(new DepthPanel(document_, depth_settings_, depth_overlay_, this)),
      cloud_view_(new CloudView(document_, this)) {
  canvas_->setTool(std::make_unique<PairTool>(canvas_, document_));
  canvas_->setDepthOverlay(depth_overlay_);
  canvas_->setPreview(preview_);  // the canvas shows the result of the same worker
  // A JPEG's whole read starts once its first look's preview is in (image_loader.h).
  session_->setHoldWholeRead(true);
  connect(preview_, &PreviewController::previewChanged, this, [this] {
    if (preview_->imageIsFinal()) session_->releaseWholeRead();
  });
  setCentralWidget(canvas_);
  setAcceptDrops(true);

  auto* preview_dock = new QDockWidget(tr("Preview"), this);
  preview_dock->setObjectName("previewDock");
  preview_dock->setWidget(preview_view_);
  addDockWidget(Qt::RightDockWidgetArea, preview_dock);
  auto* cloud_dock = new QDockWidget(tr("3D View"), this);
  cloud_dock->setObjectName("cloudDock");
  cloud_dock->setWidget(cloud_view_);
  tabifyDockWidget(preview_dock, cloud_dock);
  // The canvas shows the result (Result, Split, Onion), so the thumbnail dock is optional: hidden
  // by default, in View ▸ docks. Its tab-mate, the 3D view, would then fill the place while empty:
  // it is hidden too until a cloud is opened (below) or it is asked for in the View menu.
  preview_dock->hide();
  cloud_dock->hide();
  connect(session_, &Session::cloudLoaded, this, [this, cloud_dock](const LoadedCloud& cloud) {
    cloud_view_->setCloud(cloud);
    cloud_dock->show();
    cloud_dock->raise();
  });
  connect(cloud_view_, &CloudView::renderFailed, this, [this](const QString& m) {
    statusBar()->showMessage(tr("3D view failed: %1").arg(m), 8000);
  });
  auto* pairs_dock = new QDockWidget(tr("Pairs"), this);
  pairs_dock->setObjectName("pairsDock");
  pairs_dock->setWidget(pairs_panel_);
  addDockWidget(Qt::RightDockWidgetArea, pairs_dock);
  auto* lines_dock = new QDockWidget(tr("Lines"), this);  // beside the pairs: both feed the fit
  lines_dock->setObjectName("linesDock");
  lines_dock->setWidget(new LinesPanel(document_, this));
  tabifyDockWidget(pairs_dock, lines_dock);
  auto* tensor_dock = new QDockWidget(tr("Tensors"), this);
  tensor_dock->setObjectName("tensorDock");
  tensor_dock->setWidget(new TensorPanel(document_, this));
  tabifyDockWidget(pairs_dock, tensor_dock);
  auto* depth_dock = new QDockWidget(tr("Depth"), this);
  depth_dock->setObjectName("depthDock");
  depth_dock->setWidget(depth_panel_);
  tabifyDockWidget(tensor_dock, depth_dock);
  auto* effects_dock = new QDockWidget(tr("Effects"), this);
  effects_dock->setObjectName("effectsDock");
  auto* effects_panel = new EffectsPanel(document_, this);
  effects_dock->setWidget(effects_panel);
  tabifyDockWidget(depth_dock, effects_dock);
  auto* colour_dock = new QDockWidget(tr("Colour"), this);
  colour_dock->setObjectName("colourDock");
  colour_dock_ = new ColourDock(document_, this);
  colour_dock->setWidget(colour_dock_);
  tabifyDockWidget(effects_dock, colour_dock);
  connect(colour_dock_, &ColourDock::statusMessage, this,
          [this](const QString& m) { statusBar()->showMessage(m, 8000); });
  connect(colour_dock_, &ColourDock::samplesRestored, colour_dock, &QDockWidget::raise);
  // Cameras with a depth block read the painted depth in the preview too (same raster).
  connect(depth_overlay_, &DepthOverlay::changed, preview_,
          [this] { preview_->setDepth(depth_overlay_->raster()); });
  pairs_dock->raise();
  connect(depth_panel_, &DepthPanel::loadDepthMapRequested, this, [this] {
    session_->loadDepthMapDialog(depth_panel_->mapScale(), depth_panel_->mapInverse());
  });

  statusBar()->addPermanentWidget(fit_status_);
  connect(session_, &Session::statusMessage, this,
          [this](const QString& m) { statusBar()->showMessage(m, 8000); });
  connect(session_, &Session::loadProgress, fit_status_, &FitStatus::setLoadProgress);
  connect(canvas_, &Canvas::cursorMoved, fit_status_, &FitStatus::setCursorPosition);
  connect(canvas_, &Canvas::toolMessage, this,
          [this](const QString& m) { statusBar()->showMessage(m, 8000); });
  connect(session_, &Session::titleChanged, this, &MainWindow::updateTitle);
  connect(session_, &Session::recentFilesChanged, this, &MainWindow::rebuildRecentMenu);
  connect(preview_, &PreviewController::renderFailed, this, [this](const QString& m) {
    statusBar()->showMessage(tr("Preview failed: %1").arg(studioWording(m)), 8000);
  });
  connect(document_->undoStack(), &QUndoStack::cleanChanged, this, &MainWindow::updateTitle);
  connect(document_, &Document::photoChanged, this, &MainWindow::updateTitle);
  session_->setViewStateProvider([this] {
    ViewState v;
    v.scale = canvas_->view().scale();
    v.centre = canvas_->view().centre(QSizeF(canvas_->size()));
    v.preview_mode = static_cast<int>(preview_view_->area()->mode());
    v.opacity = preview_view_->area()->opacity();
    v.canvas = canvas_->viewState();
    return v;
  });
  connect(session_, &Session::viewStateLoaded, this, [this](const ViewState& v) {
    // A reopened project fits the picture to the window: the saved scale and centre were for
    // the window of the last session (another screen, another dock layout) and often showed a
    // corner of the photo. They stay in the file (ViewState) for readers that want them.
    canvas_->zoomToFit();
    preview_view_->setMode(static_cast<PreviewMode>(v.preview_mode));
    preview_view_->setOpacity(v.opacity);
    canvas_->setViewState(v.canvas);
  });

  colour_dock_->attachToSession(session_);
  createMenus();
  auto* insertion = new InsertionStudio(this, canvas_, document_);  // Insertion dock, menu and tools
  insertion->attachToSession(session_);
  // The Insertion tools are canvas tools like the others: one exclusive group, on the toolbar.
  for (QAction* a : {insertion->gridToolAction(), insertion->regionToolAction()}) {
    tool_switcher_->addAction(a);
    if (auto* bar = findChild<QToolBar*>(QStringLiteral("mainToolBar"))) bar->addAction(a);
  }
  auto* unfold = new UnfoldStudio(this, canvas_, document_);  // Unfold menu and wall tool
  unfold->attachToSession(session_);
  tool_switcher_->addAction(unfold->wallToolAction());
  // The wall tool shows the photo it marks; once unfolded, the canvas shows the result.
  connect(unfold, &UnfoldStudio::unfolded, this, [this](bool ok) {
    if (ok && tool_switcher_->defaultAction()) tool_switcher_->defaultAction()->trigger();
  });
  if (auto* bar = findChild<QToolBar*>(QStringLiteral("mainToolBar")))
    bar->addAction(unfold->wallToolAction());
  updateTitle();
  resize(1400, 900);
  // The last session's window: size, place, docks and toolbars (saved on a clean close).
  const QSettings settings;
  restoreGeometry(settings.value(kGeometryKey).toByteArray());
  restoreState(settings.value(kStateKey).toByteArray());
}

MainWindow::~MainWindow() = default;

void MainWindow::createMenus() {
  QMenu* file = menuBar()->addMenu(tr("&File"));
  QToolBar* bar = addToolBar(tr("Main"));
  bar->setObjectName("mainToolBar");
  QAction* open = file->addAction(tr("&Open…"), QKeySequence::Open, session_, &Session::openDialog);
  file->addAction(tr("Open &Point Cloud…"), QKeySequence(tr("Ctrl+Shift+O")), session_,
                  &Session::openCloudDialog)
      ->setToolTip(tr("A .ply cloud for the 3D view (orbit by drag, zoom by wheel)"));
  recent_menu_ = file->addMenu(tr("Open &Recent"));
  rebuildRecentMenu();
  file->addSeparator();
  QAction* save =
      file->addAction(tr("&Save Project"), QKeySequence::Save, session_, &Session::save);
  file->addAction(tr("Save Project &As…"), QKeySequence::SaveAs, session_, &Session::saveAs);
  file->addSeparator();
  file->addAction(tr("&Import Camera (.artcam)…"), session_, &Session::importArtcamDialog);
  file->addAction(tr("Export &Camera (.artcam)…"), session_, &Session::exportArtcamDialog);
  QAction* export_image = file->addAction(tr("&Export Warped Image…"), QKeySequence(tr("Ctrl+E")),
                                          session_, &Session::exportImageDialog);
  file->addSeparator();
  file->addAction(tr("Export Dep&th Map (EXR)…"), session_, &Session::exportDepthMapDialog)
      ->setToolTip(tr("The painted depth planes over the depth map, as float depth (0: none)"));
  file->addAction(tr("Load &Depth Map…"), QKeySequence(tr("Ctrl+Shift+L")), this, [this] {
    session_->loadDepthMapDialog(depth_panel_->mapScale(), depth_panel_->mapInverse());
  })->setToolTip(tr("A float EXR/TIFF or 16-bit PNG depth map under the painted planes"));
  file->addAction(tr("Depth from Stereo &Pair…"), session_, &Session::depthFromStereoDialog)
      ->setToolTip(tr("The photo is the left view of a rectified pair: choose the right one; "
                      "the depth (OpenCV's semi-global matcher) becomes the depth map"));
  file->addAction(tr("Second &Image…"), session_, &Session::loadSecondImageDialog)
      ->setToolTip(tr("The image the compositing effects (over, in, atop, xor, multiply, screen, "
                      "…) combine with the photo"));
  file->addAction(tr("Remove Second Image"), session_, &Session::removeSecondImage);
  file->addSeparator();
  file->addAction(tr("&Quit"), QKeySequence::Quit, this, &QWidget::close);
  // The toolbar's labels are short (the menu's say more), so both toolbars fit 1400 px.
  open->setIconText(tr("Open"));
  save->setIconText(tr("Save"));
  export_image->setIconText(tr("Export"));
  open->setToolTip(tr("Open a photo or project (Ctrl+O)"));
  save->setToolTip(tr("Save the project (Ctrl+S)"));
  export_image->setToolTip(tr("Export the warped image (Ctrl+E)"));
  bar->addAction(open);
  bar->addAction(save);
  bar->addAction(export_image);
  bar->addSeparator();

  QMenu* edit = menuBar()->addMenu(tr("&Edit"));
  QAction* undo = document_->undoStack()->createUndoAction(this, tr("&Undo"));
  undo->setShortcut(QKeySequence::Undo);
  QAction* redo = document_->undoStack()->createRedoAction(this, tr("&Redo"));
  // Ctrl+Y redoes on every platform too (the standard binding is Ctrl+Shift+Z off Windows).
  QList<QKeySequence> redo_keys = QKeySequence::keyBindings(QKeySequence::Redo);
  if (!redo_keys.contains(QKeySequence(tr("Ctrl+Y")))) redo_keys << QKeySequence(tr("Ctrl+Y"));
  redo->setShortcuts(redo_keys);
  edit->addAction(undo);
  edit->addAction(redo);
  edit->addSeparator();
  edit->addAction(tr("Select &All Pairs"), QKeySequence::SelectAll, this, [this] {
    std::vector<int> all(document_->pairs().size());
    for (size_t i = 0; i < all.size(); ++i) all[i] = static_cast<int>(i);
    document_->setSelection(all);
  });
  edit->addAction(tr("&Enable/Disable Selected Pairs"), this,
                  [this] { pushTogglePairsEnabled(document_, document_->selection()); });
  // The toolbar's Undo and Redo keep one label: the stack's actions name the command ("Undo Set
  // camera: Canon EF 24-70mm …"), and a label that changes width moves every button right of
  // it. The command's name is in the tooltip; the shortcuts stay on the menu's actions.
  for (QAction* stack_action : {undo, redo}) {
    auto* a = new QAction(stack_action == undo ? tr("Undo") : tr("Redo"), bar);
    a->setObjectName(stack_action == undo ? "toolbarUndo" : "toolbarRedo");
    auto follow = [a, stack_action] {
      a->setEnabled(stack_action->isEnabled());
      a->setToolTip(stack_action->text().remove('&'));
    };
    follow();
    connect(stack_action, &QAction::changed, a, follow);
    connect(a, &QAction::triggered, stack_action, &QAction::trigger);
    bar->addAction(a);
  }
  bar->addSeparator();

  QMenu* view = menuBar()->addMenu(tr("&View"));
  view->addAction(tr("Zoom to &Fit"), QKeySequence(tr("Ctrl+0")), canvas_, &Canvas::zoomToFit);
  view->addAction(tr("&Actual Pixels"), QKeySequence(tr("Ctrl+1")), canvas_, &Canvas::zoomActual);
  // Each key once: the platform's ZoomIn/ZoomOut are Ctrl++ and Ctrl+- here, and a key listed
  // twice is two shortcuts for one key, which Qt reports as ambiguous and never triggers.
  auto keys = [](QList<QKeySequence> own, QKeySequence::StandardKey standard) {
    for (const QKeySequence& k : QKeySequence::keyBindings(standard))
      if (!own.contains(k)) own << k;
    return own;
  };
  QAction* zoom_in = view->addAction(tr("Zoom &In"), canvas_, &Canvas::zoomIn);
  zoom_in->setShortcuts(
      keys({QKeySequence(tr("Ctrl+=")), QKeySequence(tr("Ctrl++"))}, QKeySequence::ZoomIn));
  QAction* zoom_out = view->addAction(tr("Zoom &Out"), canvas_, &Canvas::zoomOut);
  zoom_out->setShortcuts(keys({QKeySequence(tr("Ctrl+-"))}, QKeySequence::ZoomOut));
  view->addSeparator();
  addCanvasViewActions(this, canvas_, view);
  view->addSeparator();
  for (QDockWidget* dock : findChildren<QDockWidget*>()) view->addAction(dock->toggleViewAction());

  QMenu* tools = menuBar()->addMenu(tr("&Tools"));
  createToolActions(tools, bar);
  view->addSeparator();
  QAction* loupe = view->addAction(tr("&Loupe While Placing Points"));
  loupe->setCheckable(true);
  loupe->setChecked(canvas_->isLoupeEnabled());
  loupe->setShortcut(QKeySequence(tr("L")));
  loupe->setToolTip(tr("Magnify the photo around the cursor while placing or dragging points"));
  connect(loupe, &QAction::toggled, canvas_, &Canvas::setLoupeEnabled);
  view->addAction(tr("&Reset 3D View"), QKeySequence(tr("Ctrl+Shift+R")), cloud_view_,
                  &CloudView::resetView)
      ->setToolTip(tr("Back to the default orbit of the point cloud"));
  QAction* grid = view->addAction(tr("Show &Grid"));
  grid->setCheckable(true);
  grid->setChecked(canvas_->isGridVisible());
  grid->setShortcut(QKeySequence(tr("Ctrl+'")));
  grid->setToolTip(tr("Rule-of-thirds lines and a grid of eighths over the picture"));
  connect(grid, &QAction::toggled, canvas_, &Canvas::setGridVisible);
  QAction* magnify = view->addAction(tr("&Magnify Residuals ×10"));
  magnify->setCheckable(true);
  magnify->setChecked(canvas_->areResidualsMagnified());
  magnify->setShortcut(QKeySequence(tr("Ctrl+Shift+M")));
  magnify->setToolTip(tr("Draw each pair's miss, from where the fit sends its source to the "
                         "clicked target, ten times longer"));
  connect(magnify, &QAction::toggled, canvas_, &Canvas::setResidualsMagnified);
  QAction* overlay = view->addAction(tr("Show &Depth Overlay"));
  overlay->setCheckable(true);
  overlay->setChecked(depth_overlay_->isVisible());
  overlay->setShortcut(QKeySequence(tr("Shift+D")));
  overlay->setToolTip(tr("Colour the photo by depth (red near, blue far) with a legend"));
  connect(overlay, &QAction::toggled, depth_overlay_, &DepthOverlay::setVisible);
  connect(depth_overlay_, &DepthOverlay::changed, overlay,
          [this, overlay] { overlay->setChecked(depth_overlay_->isVisible()); });

  QMenu* model = menuBar()->addMenu(tr("&Model"));
  auto* group = new QActionGroup(this);
  const std::pair<ModelClass, QString> models[] = {
      {ModelClass::Auto, tr("&Auto (simplest that fits)")},
      {ModelClass::Translation, tr("&Translation")},
      {ModelClass::Similarity, tr("&Similarity")},
      {ModelClass::Affine, tr("A&ffine")},
      {ModelClass::Homography, tr("&Homography")},
      {ModelClass::Quadratic, tr("&Rational quadratic")}};
  for (const auto& [m, label] : models) {
    QAction* a = model->addAction(label);
    a->setCheckable(true);
    a->setChecked(m == document_->model());
    group->addAction(a);
    const ModelClass chosen = m;
    connect(a, &QAction::triggered, this, [this, chosen] {
      if (document_->model() != chosen)
        document_->undoStack()->push(new SetModelCommand(document_, chosen));
    });
    connect(document_, &Document::modelChanged, a,
            [this, a, chosen] { a->setChecked(document_->model() == chosen); });
  }
  model->addSeparator();
  new ManualCameraBanner(document_, canvas_);  // over the canvas while the camera is hand-set
  model->addAction(tr("Use &Fitted Camera"), this, [this] {
    if (document_->manualCamera())
      document_->undoStack()->push(
          new SetCameraCommand(document_, std::nullopt, tr("Use fitted camera")));
  });

  QMenu* lens = menuBar()->addMenu(tr("&Lens"));
  lens->addAction(tr("From &Database…"), session_, &Session::lensFromDatabaseDialog)
      ->setToolTip(tr("The camera that corrects a lens of the lensfun database for this photo"));
  // The table's lens-distortion row in the effect stack: its k1, k2, centre and scale are the
  // Effects panel's sliders.
  auto distortion_sliders = [this] {
    auto* panel = findChild<EffectsPanel*>();
    if (!panel || !panel->addEffect(QStringLiteral("lens-distortion"))) return;
    if (auto* dock = findChild<QDockWidget*>(QStringLiteral("effectsDock"))) {
      dock->show();
      dock->raise();
    }
  };
  lens->addAction(tr("&Distortion Sliders"), this, distortion_sliders)
      ->setToolTip(tr("Bend the picture by a lens's strengths (k1, k2, centre, scale) on sliders"));

  QMenu* help = menuBar()->addMenu(tr("&Help"));
  help->addAction(tr("&Quick Start"), QKeySequence::HelpContents, this,
                  [this] { makeQuickStartDialog(this)->show(); })
      ->setToolTip(tr("The workflow in five steps"));
  help->addAction(tr("&Keyboard Shortcuts"), QKeySequence(tr("Ctrl+/")), this,
                  [this] { makeShortcutsDialog(this)->show(); })
      ->setToolTip(tr("Every shortcut of the studio, read from its actions"));
  help->addSeparator();
  new SpacePanFilter(canvas_);  // Space+drag pans over the canvas whatever has the focus
  help->addAction(tr("&About ARTcam Studio"), this, [this] {
    QMessageBox::about(
        this, tr("About ARTcam Studio"),
        tr("<b>ARTcam Studio</b><p>Warp photographs through one rational tensor camera: "
           "click a source point, then where it should go. Middle drag or Space+drag pans, "
           "the wheel zooms, Del deletes selected pairs, Esc drops a half-made pair.</p>"
           "<p>Depth: paint a region (B brush, E eraser, G polygon), then click three points "
           "in it (D) and type their depths in the Depth panel; Shift+D shows the overlay.</p>"));
  });
}

void MainWindow::createToolActions(QMenu* menu, QToolBar* bar) {
  tool_switcher_ = new ToolSwitcher(canvas_, document_, this);
  statusBar()->insertPermanentWidget(0, tool_switcher_->label());
  struct Entry {
    QString label;
    QString short_label;  // the toolbar's
    QString key;
    QString tip;
    std::function<std::unique_ptr<Tool>()> make;
  };
  auto depth = [this](DepthToolMode mode) {
    return [this, mode]() -> std::unique_ptr<Tool> {
      return std::make_unique<DepthTool>(canvas_, document_, depth_settings_, mode);
    };
  };
  const Entry entries[] = {
      {tr("&Pairs"), tr("Pairs"), "P", tr("Click a source point, then its target (P)"),
       [this] { return std::make_unique<PairTool>(canvas_, document_); }},
      {tr("&Lines"), tr("Lines"), "S",
       tr("Click points along a straight edge, Enter ends the line: the camera straightens the "
          "lines (S)"),
       [this] { return std::make_unique<LineTool>(canvas_, document_); }},
      {tr("Depth &Brush"), tr("Brush"), "B",
       tr("Paint the selected depth plane's region (B; [ ] size)"), depth(DepthToolMode::Brush)},
      {tr("Depth &Eraser"), tr("Eraser"), "E",
       tr("Erase from the selected depth plane's region (E)"), depth(DepthToolMode::Eraser)},
      {tr("Depth Pol&ygon"), tr("Polygon"), "G",
       tr("Click corners; Enter or the first corner closes (Alt: erase) (G)"),
       depth(DepthToolMode::Polygon)},
      {tr("Depth P&oints"), tr("Points"), "D",
       tr("Click three points of the region and give each its depth (D)"),
       depth(DepthToolMode::Points)},
  };
  for (const Entry& e : entries) {
    QAction* a = menu->addAction(e.label);
    a->setCheckable(true);
    a->setIconText(e.short_label);
    a->setShortcut(QKeySequence(e.key));
    a->setToolTip(e.tip);
    tool_switcher_->addAction(a, /*is_default=*/&e == &entries[0]);
    bar->addAction(a);
    connect(a, &QAction::triggered, this, [this, make = e.make] { canvas_->setTool(make()); });
  }
  menu->addAction(tr("&Clear Lines"), this, [this] { pushClearLines(document_); })
      ->setToolTip(tr("Remove every straight line (undoable)"));
  menu->addSeparator();
  menu->addAction(tr("Smaller Brush"), QKeySequence(tr("[")), this,
                  [this] { depth_settings_->setRadius(depth_settings_->radius() / 1.25); });
  menu->addAction(tr("Larger Brush"), QKeySequence(tr("]")), this,
                  [this] { depth_settings_->setRadius(depth_settings_->radius() * 1.25); });
  menu->addAction(tr("&New Depth Plane"), QKeySequence(tr("Ctrl+Shift+N")), depth_panel_,
                  &DepthPanel::addLayer)
      ->setToolTip(tr("A new empty depth region"));
}

void MainWindow::rebuildRecentMenu() {
  if (!recent_menu_) return;
  recent_menu_->clear();
  const QStringList files = session_->recentFiles();
  for (const QString& f : files)
    recent_menu_->addAction(QFileInfo(f).fileName(), this, [this, f] { session_->openPath(f); })
        ->setToolTip(f);
  recent_menu_->setEnabled(!files.isEmpty());
}

void MainWindow::updateTitle() {
  setWindowTitle(tr("%1[*] — ARTcam Studio").arg(session_->displayName()));
  setWindowModified(document_->isModified());
}

void MainWindow::closeEvent(QCloseEvent* event) {
  // A save the close asks for runs off the GUI thread: the window closes once it succeeded.
  if (!close_accepted_) {
    auto inside = std::make_shared<bool>(true);
    session_->maybeSaveThen([this, inside] {
      session_->closedCleanly();
      QSettings settings;
      settings.setValue(kGeometryKey, saveGeometry());
      settings.setValue(kStateKey, saveState());
      close_accepted_ = true;
      if (!*inside) close();  // the save has finished: close again, accepted now
    });
    *inside = false;
  }
  if (close_accepted_)
    event->accept();
  else
    event->ignore();
}

void MainWindow::dragEnterEvent(QDragEnterEvent* event) {
  if (event->mimeData()->hasUrls()) event->acceptProposedAction();
}

void MainWindow::dropEvent(QDropEvent* event) {
  const QList<QUrl> urls = event->mimeData()->urls();
  if (urls.isEmpty() || !urls.front().isLocalFile()) return;
  session_->openPath(urls.front().toLocalFile());
  event->acceptProposedAction();
}

}  // namespace artcam::ui
