// SPDX-License-Identifier: Apache-2.0
#include "ui/space_pan.h"

#include "ui/canvas.h"

#include <QAbstractSpinBox>
#include <QApplication>
#include <QKeyEvent>
#include <QLineEdit>
#include <QPlainTextEdit>
#include <QTextEdit>

namespace artcam::ui {

namespace {

// Where Space is typed as text (a name, a number, a cell being edited) it stays text.
bool focusTakesText() {
  const QWidget* w = QApplication::focusWidget();
  return qobject_cast<const QLineEdit*>(w) || qobject_cast<const QAbstractSpinBox*>(w) ||
         qobject_cast<const QTextEdit*>(w) || qobject_cast<const QPlainTextEdit*>(w);
}

}  // namespace

SpacePanFilter::SpacePanFilter(Canvas* canvas) : QObject(canvas), canvas_(canvas) {
  QCoreApplication::instance()->installEventFilter(this);
}

bool SpacePanFilter::eventFilter(QObject* watched, QEvent* event) {
  const QEvent::Type type = event->type();
  if (type != QEvent::KeyPress && type != QEvent::KeyRelease && type != QEvent::ShortcutOverride)
    return QObject::eventFilter(watched, event);
  auto* key = static_cast<QKeyEvent*>(event);
  if (key->key() != Qt::Key_Space || key->modifiers() != Qt::NoModifier || !canvas_->isVisible())
    return QObject::eventFilter(watched, event);
  const bool ours = type == QEvent::KeyRelease ? canvas_->isSpacePanning()
                                               : canvas_->isPointerInside() && !focusTakesText();
  if (!ours) return QObject::eventFilter(watched, event);
  if (type == QEvent::ShortcutOverride) {
    // Claimed as a key, so no shortcut of the focus widget's window takes it first.
    event->accept();
    return true;
  }
  if (!key->isAutoRepeat()) canvas_->setSpacePan(type == QEvent::KeyPress);
  return true;
}

}  // namespace artcam::ui
