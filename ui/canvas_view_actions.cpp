// SPDX-License-Identifier: Apache-2.0
#include "ui/canvas_view_actions.h"

#include "ui/canvas.h"

#include <QAction>
#include <QActionGroup>
#include <QLabel>
#include <QMainWindow>
#include <QMenu>
#include <QSlider>
#include <QToolBar>

#include <cmath>

namespace artcam::ui {

void addCanvasViewActions(QMainWindow* window, Canvas* canvas, QMenu* view_menu) {
  QToolBar* bar = window->addToolBar(Canvas::tr("Canvas"));
  bar->setObjectName("canvasToolBar");
  auto* group = new QActionGroup(window);
  struct Entry {
    CanvasViewMode mode;
    QString label;
    QString key;
    QString tip;
  };
  const Entry entries[] = {
      {CanvasViewMode::Photo, Canvas::tr("&Photo"), "Alt+1",
       Canvas::tr("Show the photo; sources and targets are edited (Alt+1)")},
      {CanvasViewMode::Result, Canvas::tr("&Result"), "Alt+2",
       Canvas::tr("Show the warped result; targets are edited on it (Alt+2)")},
      {CanvasViewMode::Split, Canvas::tr("&Split"), "Alt+3",
       Canvas::tr("Photo left of the divider, result right; drag its handle or Alt+drag (Alt+3)")},
      {CanvasViewMode::Onion, Canvas::tr("&Onion"), "Alt+4",
       Canvas::tr("The result over the photo at the opacity set beside (Alt+4)")},
  };
  QList<QPair<CanvasViewMode, QAction*>> actions;
  for (const Entry& e : entries) {
    QAction* a = view_menu->addAction(e.label);
    a->setCheckable(true);
    a->setShortcut(QKeySequence(e.key));
    a->setToolTip(e.tip);
    a->setObjectName(QStringLiteral("canvasMode_%1").arg(canvasViewModeName(e.mode)));
    group->addAction(a);
    bar->addAction(a);
    const CanvasViewMode mode = e.mode;
    QObject::connect(a, &QAction::triggered, canvas, [canvas, mode] { canvas->setViewMode(mode); });
    actions.append({e.mode, a});
  }
  QAction* toggle = view_menu->addAction(Canvas::tr("&Before/After"));
  toggle->setShortcut(QKeySequence(Qt::Key_Backslash));
  toggle->setObjectName("canvasBeforeAfter");
  toggle->setToolTip(Canvas::tr("Photo ↔ the last result view (\\)"));
  QObject::connect(toggle, &QAction::triggered, canvas, &Canvas::toggleBeforeAfter);

  auto* label = new QLabel(Canvas::tr(" Onion opacity "), bar);
  auto* slider = new QSlider(Qt::Horizontal, bar);
  slider->setObjectName("onionOpacitySlider");
  slider->setRange(0, 100);
  slider->setMaximumWidth(120);
  slider->setToolTip(Canvas::tr("Opacity of the result over the photo (Onion)"));
  bar->addWidget(label);
  bar->addWidget(slider);
  QObject::connect(slider, &QSlider::valueChanged, canvas,
                   [canvas](int v) { canvas->setOnionOpacity(v / 100.0); });

  // The canvas's state is the truth (a project's view state sets it): controls follow it.
  auto sync = [canvas, actions, slider] {
    const CanvasViewState& s = canvas->viewState();
    for (const auto& [mode, a] : actions) a->setChecked(mode == s.mode);
    const QSignalBlocker block(slider);
    slider->setValue(static_cast<int>(std::lround(s.onion_opacity * 100)));
  };
  QObject::connect(canvas, &Canvas::viewStateChanged, slider, sync);
  sync();
}

}  // namespace artcam::ui
