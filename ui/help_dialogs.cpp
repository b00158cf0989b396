// SPDX-License-Identifier: Apache-2.0
#include "ui/help_dialogs.h"

#include <QAction>
#include <QDialog>
#include <QDialogButtonBox>
#include <QHeaderView>
#include <QLabel>
#include <QRegularExpression>
#include <QSet>
#include <QTableWidget>
#include <QVBoxLayout>

#include <algorithm>
#include <vector>

namespace artcam::ui {

namespace {

QString tr(const char* text) { return QDialog::tr(text); }

QDialog* dialogWith(QWidget* parent, const QString& title, QWidget* content) {
  auto* dialog = new QDialog(parent);
  dialog->setAttribute(Qt::WA_DeleteOnClose);
  dialog->setWindowTitle(title);
  auto* layout = new QVBoxLayout(dialog);
  content->setParent(dialog);
  layout->addWidget(content);
  auto* buttons = new QDialogButtonBox(QDialogButtonBox::Close, dialog);
  QObject::connect(buttons, &QDialogButtonBox::rejected, dialog, &QDialog::reject);
  layout->addWidget(buttons);
  return dialog;
}

}  // namespace

QString quickStartHtml() {
  return tr(
      "<h3>Quick start</h3><ol>"
      "<li><b>Open a photo</b> (Ctrl+O) or drop one on the window.</li>"
      "<li><b>Click pairs</b> with the pair tool (P): a point in the photo, then where it should "
      "go. The camera is fitted after every pair; Model ▸ Auto picks the simplest model that "
      "fits. Markers go green → red by residual (legend bottom right; View ▸ Magnify Residuals "
      "shows each miss ×10).</li>"
      "<li><b>Or straighten a lens</b> with the line tool (S): click points along edges that "
      "are straight in the world, Enter ends each line; every line shows its remaining bow.</li>"
      "<li><b>Check the preview</b> dock; drag a marker to refine it, Del deletes the selection, "
      "Ctrl+Z / Ctrl+Y undo and redo.</li>"
      "<li><b>Depth</b> (optional): paint a plane (B brush, E eraser, G polygon), give it depth "
      "at three points (D), then use depth effects (Effects dock).</li>"
      "<li><b>Export</b> the warped image (Ctrl+E) or the camera (File ▸ Export Camera), and save "
      "the project (Ctrl+S).</li></ol>"
      "<p>Pan: middle drag or Space+drag over the canvas. Zoom: wheel, Ctrl+0 fits. "
      "Help ▸ Keyboard Shortcuts lists every shortcut.</p>");
}

QDialog* makeQuickStartDialog(QWidget* parent) {
  auto* label = new QLabel(quickStartHtml());
  label->setWordWrap(true);
  label->setTextFormat(Qt::RichText);
  label->setMinimumWidth(460);
  return dialogWith(parent, tr("Quick Start"), label);
}

QTableWidget* makeShortcutTable(const QWidget* window, QWidget* parent) {
  struct Row {
    QString action, keys, tip;
  };
  std::vector<Row> rows;
  QSet<const QAction*> seen;
  for (const QAction* a : window->findChildren<QAction*>()) {
    if (a->shortcuts().isEmpty() || seen.contains(a)) continue;
    seen.insert(a);
    QStringList keys;
    for (const QKeySequence& k : a->shortcuts()) keys << k.toString(QKeySequence::NativeText);
    QString text = a->text();
    text.remove(QRegularExpression(QStringLiteral("&(?!&)")));
    rows.push_back({text, keys.join(QStringLiteral(", ")), a->toolTip()});
  }
  std::sort(rows.begin(), rows.end(), [](const Row& l, const Row& r) {
    return QString::localeAwareCompare(l.action, r.action) < 0;
  });
  auto* table = new QTableWidget(static_cast<int>(rows.size()), 3, parent);
  table->setObjectName(QStringLiteral("shortcutTable"));
  table->setHorizontalHeaderLabels({tr("Action"), tr("Shortcut"), tr("What it does")});
  table->setEditTriggers(QAbstractItemView::NoEditTriggers);
  table->verticalHeader()->setVisible(false);
  table->horizontalHeader()->setSectionResizeMode(0, QHeaderView::ResizeToContents);
  table->horizontalHeader()->setSectionResizeMode(1, QHeaderView::ResizeToContents);
  table->horizontalHeader()->setStretchLastSection(true);
  for (int i = 0; i < static_cast<int>(rows.size()); ++i) {
    const Row& r = rows[static_cast<size_t>(i)];
    table->setItem(i, 0, new QTableWidgetItem(r.action));
    table->setItem(i, 1, new QTableWidgetItem(r.keys));
    table->setItem(i, 2, new QTableWidgetItem(r.tip));
  }
  return table;
}

QDialog* makeShortcutsDialog(QWidget* window) {
  QTableWidget* table = makeShortcutTable(window);
  QDialog* dialog = dialogWith(window, tr("Keyboard Shortcuts"), table);
  dialog->resize(720, 520);
  return dialog;
}

}  // namespace artcam::ui
