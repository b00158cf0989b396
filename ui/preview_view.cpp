// SPDX-License-Identifier: Apache-2.0
#include "ui/preview_view.h"

#include "ui/document.h"
#include "ui/preview_controller.h"

#include <QComboBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QPainter>
#include <QSlider>
#include <QVBoxLayout>

#include <algorithm>

namespace artcam::ui {
namespace {

// The largest rect of the given aspect centred in `area`.
QRectF fitted(const QRectF& area, double aspect) {
  if (aspect <= 0.0 || area.isEmpty()) return area;
  double w = area.width();
  double h = w / aspect;
  if (h > area.height()) {
    h = area.height();
    w = h * aspect;
  }
  return {area.center().x() - w / 2, area.center().y() - h / 2, w, h};
}

}  // namespace

PreviewArea::PreviewArea(Document* document, PreviewController* controller, QWidget* parent)
    : QWidget(parent), document_(document), controller_(controller) {
  setMinimumSize(160, 120);
  connect(controller_, &PreviewController::previewChanged, this, qOverload<>(&QWidget::update));
  connect(document_, &Document::photoChanged, this, qOverload<>(&QWidget::update));
  connect(document_, &Document::photoRefined, this, qOverload<>(&QWidget::update));
}

void PreviewArea::setMode(PreviewMode mode) {
  mode_ = mode;
  update();
}

void PreviewArea::setOpacity(double opacity) {
  opacity_ = std::clamp(opacity, 0.0, 1.0);
  update();
}

void PreviewArea::setSplit(double split) {
  split_ = std::clamp(split, 0.0, 1.0);
  update();
}

void PreviewArea::paintEvent(QPaintEvent*) {
  QPainter painter(this);
  painter.fillRect(rect(), QColor(40, 40, 44));
  const PhotoPtr& photo = document_->photo();
  if (!photo) return;
  const QImage& source = photo->display;
  const QImage& warped = controller_->image();
  const FrameSize f = photo->size();
  const double aspect = static_cast<double>(f.width) / f.height;
  painter.setRenderHint(QPainter::SmoothPixmapTransform, true);
  // A checkerboard under the warped image so transparent (no preimage) pixels read as such.
  auto checker = [&](const QRectF& r) {
    painter.save();
    painter.setClipRect(r);
    painter.fillRect(r, QColor(90, 90, 90));
    constexpr int kCell = 8;
    for (int y = static_cast<int>(r.top()); y < r.bottom(); y += kCell)
      for (int x = static_cast<int>(r.left()) + ((y / kCell) % 2) * kCell; x < r.right();
           x += 2 * kCell)
        painter.fillRect(QRect(x, y, kCell, kCell), QColor(120, 120, 120));
    painter.restore();
  };
  switch (mode_) {
    case PreviewMode::SideBySide: {
      const QRectF left = fitted(QRectF(0, 0, width() / 2.0 - 2, height()), aspect);
      const QRectF right =
          fitted(QRectF(width() / 2.0 + 2, 0, width() / 2.0 - 2, height()), aspect);
      source_cache_.draw(painter, left, source);
      checker(right);
      if (!warped.isNull()) painter.drawImage(right, warped);
      break;
    }
    case PreviewMode::Overlay: {
      const QRectF r = fitted(QRectF(rect()), aspect);
      source_cache_.draw(painter, r, source);
      painter.setOpacity(opacity_);
      if (!warped.isNull()) painter.drawImage(r, warped);
      painter.setOpacity(1.0);
      break;
    }
    case PreviewMode::Split: {
      const QRectF r = fitted(QRectF(rect()), aspect);
      const double x = r.left() + split_ * r.width();
      painter.save();
      painter.setClipRect(QRectF(r.left(), r.top(), x - r.left(), r.height()));
      source_cache_.draw(painter, r, source);
      painter.restore();
      painter.save();
      const QRectF right(x, r.top(), r.right() - x, r.height());
      checker(right);
      painter.setClipRect(right);
      if (!warped.isNull()) painter.drawImage(r, warped);
      painter.restore();
      painter.setPen(QPen(Qt::white, 1.5));
      painter.drawLine(QPointF(x, r.top()), QPointF(x, r.bottom()));
      break;
    }
    case PreviewMode::WarpedOnly: {
      const QRectF r = fitted(QRectF(rect()), aspect);
      checker(r);
      if (!warped.isNull()) painter.drawImage(r, warped);
      break;
    }
  }
}

PreviewView::PreviewView(Document* document, PreviewController* controller, QWidget* parent)
    : QWidget(parent),
      area_(new PreviewArea(document, controller, this)),
      mode_box_(new QComboBox(this)),
      slider_(new QSlider(Qt::Horizontal, this)) {
  mode_box_->addItem(tr("Side by side"), static_cast<int>(PreviewMode::SideBySide));
  mode_box_->addItem(tr("Overlay"), static_cast<int>(PreviewMode::Overlay));
  mode_box_->addItem(tr("Split"), static_cast<int>(PreviewMode::Split));
  mode_box_->addItem(tr("Warped only"), static_cast<int>(PreviewMode::WarpedOnly));
  slider_->setRange(0, 100);
  slider_->setValue(50);
  auto* controls = new QHBoxLayout;
  controls->addWidget(new QLabel(tr("Preview:"), this));
  controls->addWidget(mode_box_);
  controls->addWidget(slider_, 1);
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(2, 2, 2, 2);
  layout->addLayout(controls);
  layout->addWidget(area_, 1);
  connect(mode_box_, &QComboBox::currentIndexChanged, this, [this](int) {
    area_->setMode(static_cast<PreviewMode>(mode_box_->currentData().toInt()));
    updateSliderRole();
  });
  connect(slider_, &QSlider::valueChanged, this, [this](int v) {
    if (area_->mode() == PreviewMode::Split)
      area_->setSplit(v / 100.0);
    else
      area_->setOpacity(v / 100.0);
  });
  updateSliderRole();
}

void PreviewView::setMode(PreviewMode mode) {
  mode_box_->setCurrentIndex(mode_box_->findData(static_cast<int>(mode)));
}

void PreviewView::setOpacity(double opacity) {
  area_->setOpacity(opacity);
  updateSliderRole();
}

void PreviewView::updateSliderRole() {
  const PreviewMode m = area_->mode();
  slider_->setEnabled(m == PreviewMode::Overlay || m == PreviewMode::Split);
  slider_->setToolTip(m == PreviewMode::Split ? tr("Divider position")
                                              : tr("Warped image opacity"));
  const QSignalBlocker block(slider_);
  slider_->setValue(
      static_cast<int>((m == PreviewMode::Split ? area_->split() : area_->opacity()) * 100 + 0.5));
}

}  // namespace artcam::ui
