// SPDX-License-Identifier: Apache-2.0
// Help ▸ Quick Start (the workflow in a few steps) and Help ▸ Keyboard Shortcuts. The
// shortcuts table is built from the window's actual QActions each time it is opened, so it
// cannot go stale: a new action with a shortcut appears in it without an edit here.
#pragma once

#include <QString>

class QDialog;
class QTableWidget;
class QWidget;

namespace artcam::ui {

QString quickStartHtml();
QDialog* makeQuickStartDialog(QWidget* parent);

// One row per action of `window` (menus included) that has a shortcut: the action's text
// (without its & mnemonic), its shortcuts in the platform's native text, its tooltip.
// Sorted by action text.
QTableWidget* makeShortcutTable(const QWidget* window, QWidget* parent = nullptr);
QDialog* makeShortcutsDialog(QWidget* window);

}  // namespace artcam::ui
