// SPDX-License-Identifier: Apache-2.0
#include "ui/tool_switcher.h"

#include "ui/canvas.h"
#include "ui/document.h"
#include "ui/tools/tool.h"

#include <QAction>
#include <QActionGroup>
#include <QLabel>

namespace artcam::ui {

ToolSwitcher::ToolSwitcher(Canvas* canvas, Document* document, QWidget* window)
    : QObject(window), canvas_(canvas), group_(new QActionGroup(this)), label_(new QLabel(window)) {
  label_->setObjectName(QStringLiteral("activeToolLabel"));
  label_->setToolTip(tr("The active canvas tool (Tools menu and toolbar)"));
  connect(canvas_, &Canvas::toolChanged, this, &ToolSwitcher::updateLabel);
  // After the document's own reset (the canvas has already dropped the old tool's gesture).
  connect(document, &Document::photoChanged, this, [this] {
    if (default_) default_->trigger();  // an exclusive group keeps a checked action checked
  });
  updateLabel();
}

void ToolSwitcher::addAction(QAction* action, bool is_default) {
  action->setCheckable(true);
  group_->addAction(action);
  if (is_default) {
    default_ = action;
    action->setChecked(true);
  }
}

void ToolSwitcher::updateLabel() {
  const Tool* tool = canvas_->tool();
  const QString name = tool ? tool->name() : QString();
  label_->setText(name.isEmpty() ? QString() : tr("Tool: %1").arg(name));
}

}  // namespace artcam::ui
