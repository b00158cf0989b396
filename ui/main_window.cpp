#include "ui/main_window.h"

#include "ui/canvas.h"
#include "ui/commands.h"
#include "ui/document.h"
#include "ui/fit_status.h"
#include "ui/panels/effects_panel.h"
#include "ui/panels/pairs_panel.h"
#include "ui/panels/tensor_panel.h"
#include "ui/preview_controller.h"
#include "ui/preview_view.h"
#include "ui/session.h"
#include "ui/tools/pair_tool.h"

#include <QAction>
#include <QActionGroup>
#include <QApplication>
#include <QCloseEvent>
#include <QDockWidget>
#include <QDragEnterEvent>
#include <QDropEvent>
#include <QFileInfo>
#include <QKeySequence>
#include <QMenu>
#include <QMenuBar>
#include <QMessageBox>
#include <QMimeData>
#include <QStatusBar>
#include <QToolBar>
#include <QUrl>

namespace artcam::ui {

MainWindow::MainWindow(QWidget* parent)
    : QMainWindow(parent),
      document_(new Document(this)),
      preview_(new PreviewController(document_, this)),
      canvas_(new Canvas(document_, this)),
      preview_view_(new PreviewView(document_, preview_, this)),
      pairs_panel_(new PairsPanel(document_, this)),
      fit_status_(new FitStatus(document_, preview_, this)),
      session_(new Session(document_, this, this)) {
  canvas_->setTool(std::make_unique<PairTool>(canvas_, document_));
  setCentralWidget(canvas_);
  setAcceptDrops(true);

  auto* preview_dock = new QDockWidget(tr("Preview"), this);
  preview_dock->setObjectName("previewDock");
  preview_dock->setWidget(preview_view_);
  addDockWidget(Qt::RightDockWidgetArea, preview_dock);
  auto* pairs_dock = new QDockWidget(tr("Pairs"), this);
  pairs_dock->setObjectName("pairsDock");
  pairs_dock->setWidget(pairs_panel_);
  addDockWidget(Qt::RightDockWidgetArea, pairs_dock);
  auto* tensor_dock = new QDockWidget(tr("Tensors"), this);
  tensor_dock->setObjectName("tensorDock");
  tensor_dock->setWidget(new TensorPanel(document_, this));
  tabifyDockWidget(pairs_dock, tensor_dock);
  auto* effects_dock = new QDockWidget(tr("Effects"), this);
  effects_dock->setObjectName("effectsDock");
  effects_dock->setWidget(new EffectsPanel(document_, this));
  tabifyDockWidget(tensor_dock, effects_dock);
  pairs_dock->raise();

  // The preview is the point of the session: give it room beside the canvas.
  resizeDocks({preview_dock}, {560}, Qt::Horizontal);
  resizeDocks({preview_dock, pairs_dock}, {420, 360}, Qt::Vertical);
  statusBar()->addPermanentWidget(fit_status_);
  connect(session_, &Session::statusMessage, this,
          [this](const QString& m) { statusBar()->showMessage(m, 8000); });
  connect(session_, &Session::loadProgress, fit_status_, &FitStatus::setLoadProgress);
  connect(canvas_, &Canvas::cursorMoved, fit_status_, &FitStatus::setCursorPosition);
  connect(session_, &Session::titleChanged, this, &MainWindow::updateTitle);
  connect(session_, &Session::recentFilesChanged, this, &MainWindow::rebuildRecentMenu);
  connect(preview_, &PreviewController::renderFailed, this, [this](const QString& m) {
    statusBar()->showMessage(tr("Preview failed: %1").arg(m), 8000);
  });
  connect(document_->undoStack(), &QUndoStack::cleanChanged, this, &MainWindow::updateTitle);
  connect(document_, &Document::photoChanged, this, &MainWindow::updateTitle);
  session_->setViewStateProvider([this] {
    ViewState v;
    v.scale = canvas_->view().scale();
    v.centre = canvas_->view().centre(QSizeF(canvas_->size()));
    v.preview_mode = static_cast<int>(preview_view_->area()->mode());
    v.opacity = preview_view_->area()->opacity();
    return v;
  });
  connect(session_, &Session::viewStateLoaded, this, [this](const ViewState& v) {
    if (v.scale > 0.0) canvas_->setView(v.scale, v.centre);
    preview_view_->setMode(static_cast<PreviewMode>(v.preview_mode));
    preview_view_->setOpacity(v.opacity);
  });

  createMenus();
  updateTitle();
  resize(1400, 900);
}

MainWindow::~MainWindow() = default;

void MainWindow::createMenus() {
  QMenu* file = menuBar()->addMenu(tr("&File"));
  QToolBar* bar = addToolBar(tr("Main"));
  bar->setObjectName("mainToolBar");
  QAction* open = file->addAction(tr("&Open…"), QKeySequence::Open, session_, &Session::openDialog);
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
  file->addAction(tr("&Quit"), QKeySequence::Quit, this, &QWidget::close);
  bar->addAction(open);
  bar->addAction(save);
  bar->addAction(export_image);
  bar->addSeparator();

  QMenu* edit = menuBar()->addMenu(tr("&Edit"));
  QAction* undo = document_->undoStack()->createUndoAction(this, tr("&Undo"));
  undo->setShortcut(QKeySequence::Undo);
  QAction* redo = document_->undoStack()->createRedoAction(this, tr("&Redo"));
  redo->setShortcut(QKeySequence::Redo);
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
  bar->addAction(undo);
  bar->addAction(redo);
  bar->addSeparator();

  QMenu* view = menuBar()->addMenu(tr("&View"));
  view->addAction(tr("Zoom to &Fit"), QKeySequence(tr("Ctrl+0")), canvas_, &Canvas::zoomToFit);
  view->addAction(tr("&Actual Pixels"), QKeySequence(tr("Ctrl+1")), canvas_, &Canvas::zoomActual);
  QAction* zoom_in = view->addAction(tr("Zoom &In"), canvas_, &Canvas::zoomIn);
  zoom_in->setShortcuts(
      {QKeySequence(tr("Ctrl+=")), QKeySequence(tr("Ctrl++")), QKeySequence::ZoomIn});
  QAction* zoom_out = view->addAction(tr("Zoom &Out"), canvas_, &Canvas::zoomOut);
  zoom_out->setShortcuts({QKeySequence(tr("Ctrl+-")), QKeySequence::ZoomOut});
  view->addSeparator();
  for (QDockWidget* dock : findChildren<QDockWidget*>()) view->addAction(dock->toggleViewAction());

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
  model->addAction(tr("Use &Fitted Camera"), this, [this] {
    if (document_->manualCamera())
      document_->undoStack()->push(
          new SetCameraCommand(document_, std::nullopt, tr("Use fitted camera")));
  });

  QMenu* help = menuBar()->addMenu(tr("&Help"));
  help->addAction(tr("&About ARTcam Studio"), this, [this] {
    QMessageBox::about(
        this, tr("About ARTcam Studio"),
        tr("<b>ARTcam Studio</b><p>Warp photographs through one rational tensor camera: "
           "click a source point, then where it should go. Middle drag or Space+drag pans, "
           "the wheel zooms, Del deletes selected pairs, Esc drops a half-made pair.</p>"));
  });
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
  if (session_->maybeSave())
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
