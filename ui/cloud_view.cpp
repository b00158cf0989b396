// SPDX-License-Identifier: Apache-2.0
#include "ui/cloud_view.h"

#include "core/render/attributed.h"

#include "core/cameras/projective_cameras.h"
#include "core/io/ply.h"
#include "core/model/structure.h"
#include "ui/document.h"

#include <QComboBox>
#include <QFileInfo>
#include <QMouseEvent>
#include <QPainter>
#include <QWheelEvent>

#include <algorithm>
#include <cmath>
#include <exception>
#include <numbers>

namespace artcam::ui {
namespace {

double defaultYaw() { return std::atan2(4.0, 5.0); }
double defaultPitch() { return std::asin(3.0 / std::sqrt(50.0)); }

Eigen::Vector3d orbitDirection(double yaw, double pitch) {
  // In the cloud's world (y up, as defaultViewPose's lookAt): the eye rises with pitch.
  return {std::cos(pitch) * std::sin(yaw), std::sin(pitch), -std::cos(pitch) * std::cos(yaw)};
}

}  // namespace

Result<LoadedCloud> CloudView::load(const QString& path) {
  try {
    Result<PointCloud> read = readPly(path.toStdString());
    if (!read) return Result<LoadedCloud>::failure(read.status.message);
    LoadedCloud out;
    out.path = QFileInfo(path).absoluteFilePath();
    out.bounds = cloudBounds(*read);
    if (out.bounds.empty)
      return Result<LoadedCloud>::failure(path.toStdString() + ": the cloud has no finite point");
    out.point_spacing = estimatePointSpacing(*read);
    out.focal = framingPinhole(*read, defaultViewPose(out.bounds), 512, 512).focal;
    out.cloud = std::make_shared<const PointCloud>(std::move(*read.value));
    return Result<LoadedCloud>::success(std::move(out));
  } catch (const std::exception& e) {
    return Result<LoadedCloud>::failure(path.toStdString() + ": " + e.what());
  }
}

CloudView::CloudView(Document* document, QWidget* parent)
    : QWidget(parent), document_(document), effect_box_(new QComboBox(this)) {
  setMinimumSize(200, 150);
  setAttribute(Qt::WA_OpaquePaintEvent);
  setToolTip(tr("Drag to orbit, wheel to zoom; the image camera applies as a lens"));
  effect_box_->addItem(tr("No 3D effect"), QString());
  for (const Effect3dSpec& spec : effect3dSpecs()) {
    effect_box_->addItem(QString::fromStdString(spec.label), QString::fromStdString(spec.name));
    effect_box_->setItemData(effect_box_->count() - 1, QString::fromStdString(spec.summary),
                             Qt::ToolTipRole);
  }
  effect_box_->setToolTip(tr("An object-space effect of the paper's Fig 1, before the view"));
  effect_box_->move(8, 8);
  connect(effect_box_, &QComboBox::currentIndexChanged, this, [this](int index) {
    setEffect(effect_box_->itemData(index).toString().toStdString());
  });
  connect(&worker_, &CloudRenderWorker::rendered, this, &CloudView::onRendered,
          Qt::QueuedConnection);
  connect(
      &worker_, &CloudRenderWorker::failed, this,
      [this](const QString& message, quint64) { emit renderFailed(message); },
      Qt::QueuedConnection);
  // The lens is the document's camera: every edit re-renders the view.
  connect(document_, &Document::cameraChanged, this, &CloudView::schedule);
}

CloudView::~CloudView() { worker_.shutdown(); }

void CloudView::setCloud(LoadedCloud cloud) {
  cloud_ = std::move(cloud);
  resetView();
}

void CloudView::resetView() {
  setOrbit(defaultYaw(), defaultPitch(), kDefaultDistance * std::max(cloud_.bounds.radius(), 1e-9));
}

void CloudView::setOrbit(double yaw, double pitch, double distance) {
  yaw_ = std::remainder(yaw, 2.0 * std::numbers::pi);
  pitch_ = std::clamp(pitch, -kMaxPitch, kMaxPitch);
  const double r = std::max(cloud_.bounds.radius(), 1e-9);
  distance_ = std::clamp(distance, 0.2 * r, 50.0 * r);
  emit viewChanged();
  schedule();
}

void CloudView::setEffect(const std::string& name) {
  const std::string effect = findEffect3d(name) ? name : std::string();
  if (effect == effect_) return;
  effect_ = effect;
  const int index = effect_box_->findData(QString::fromStdString(effect));
  if (index >= 0 && effect_box_->currentIndex() != index) effect_box_->setCurrentIndex(index);
  schedule();
}

Eigen::Vector3d CloudView::orbitEye() const {
  return cloud_.bounds.centre() + distance_ * orbitDirection(yaw_, pitch_);
}

ObjectFrame CloudView::effectFrame() const {
  const double radius = cloud_.bounds.radius();
  return {cloud_.bounds.centre(), radius > 0 ? radius : 1.0};
}

EffectValues CloudView::effectValues() const {
  EffectValues values;
  const Effect3dSpec* spec = findEffect3d(effect_);
  if (!spec) return values;
  for (const EffectParam& p : spec->params) values[p.name] = p.value;
  if (spec->viewer) {
    const ObjectFrame frame = effectFrame();
    const Eigen::Vector3d eye = frame.fromWorld(orbitEye());
    const Eigen::Vector3d at = frame.fromWorld(cloud_.bounds.centre());
    values["eye"] = {eye.x(), eye.y(), eye.z()};
    values["at"] = {at.x(), at.y(), at.z()};
  }
  return values;
}

QSize CloudView::renderSize() const {
  QSize s = size();
  const int side = std::max(s.width(), s.height());
  if (side > kMaxRenderSide) s = s * kMaxRenderSide / side;
  return s.expandedTo(QSize(1, 1));
}

CloudRenderRequest CloudView::currentRequest() const {
  CloudRenderRequest r;
  r.cloud = cloud_.cloud;
  r.point_spacing = cloud_.point_spacing;
  const QSize s = renderSize();
  r.width = s.width();
  r.height = s.height();
  if (!cloud_.cloud) return r;
  const Eigen::Vector3d centre = cloud_.bounds.centre();
  const Eigen::Vector3d eye = orbitEye();
  PinholeParams pinhole;
  pinhole.pose = CameraPose::lookAt(eye, centre);
  // The focal was made for a square frame; the normalised frame's shorter half-side is
  // min/max of the sides, so scale it to keep the same framing.
  pinhole.focal = cloud_.focal * std::min(r.width, r.height) / std::max(r.width, r.height);
  r.view = pinholeCamera(pinhole);
  if (const Effect3dSpec* spec = findEffect3d(effect_)) {
    r.effects.push_back(buildEffect3d(spec->name, effectValues(), effectFrame()));
    if (spec->colour_layers) r.layers = RenderLayers::Rgb;
  }
  // The document's image camera as a lens, unless it is the identity (nothing to apply).
  // Its geometry only: the lens warp is a gather of positions (a colour block is the photo's).
  if (document_->photo() && analyseStructure(document_->camera()).geometry != GeometryClass::Identity)
    r.lens = document_->camera().blocks().size() == 1 ? document_->camera()
                                                      : positionPart(document_->camera());
  return r;
}

void CloudView::schedule() {
  if (!cloud_.cloud) return;
  CloudRenderRequest r;
  try {
    r = currentRequest();
  } catch (const std::exception& e) {  // an effect the table refuses in this view
    emit renderFailed(QString::fromUtf8(e.what()));
    return;
  }
  r.generation = ++generation_;
  worker_.request(std::move(r));
}

void CloudView::onRendered(const QImage& image, quint64 generation, bool final_pass, double ms) {
  if (generation < image_generation_) return;
  if (generation == image_generation_ && image_final_ && !final_pass) return;
  image_ = image;
  image_generation_ = generation;
  image_final_ = final_pass;
  last_ms_ = ms;
  update();
}

void CloudView::paintEvent(QPaintEvent*) {
  QPainter painter(this);
  painter.fillRect(rect(), QColor(36, 36, 40));
  if (!cloud_.cloud) {
    painter.setPen(QColor(180, 180, 180));
    painter.drawText(rect(), Qt::AlignCenter, tr("Open a point cloud (File ▸ Open Point Cloud…)"));
    return;
  }
  if (!image_.isNull()) {
    // A coarse pass is drawn scaled up to the full size.
    painter.setRenderHint(QPainter::SmoothPixmapTransform, true);
    const QSize full = renderSize().scaled(size(), Qt::KeepAspectRatio);
    const QRect target(QPoint((width() - full.width()) / 2, (height() - full.height()) / 2), full);
    painter.drawImage(target, image_);
  }
  painter.setPen(QColor(200, 200, 200));
  painter.drawText(rect().adjusted(8, 8, -8, -8), Qt::AlignRight | Qt::AlignBottom,
                   tr("%1 · %2 points · %3 ms")
                       .arg(QFileInfo(cloud_.path).fileName())
                       .arg(cloud_.cloud->size())
                       .arg(last_ms_, 0, 'f', 0));
}

void CloudView::resizeEvent(QResizeEvent*) { schedule(); }

void CloudView::mousePressEvent(QMouseEvent* event) {
  if (event->button() != Qt::LeftButton) return;
  dragging_ = true;
  drag_last_ = event->position().toPoint();
  setCursor(Qt::ClosedHandCursor);
}

void CloudView::mouseMoveEvent(QMouseEvent* event) {
  if (!dragging_) return;
  const QPoint p = event->position().toPoint();
  const QPoint d = p - drag_last_;
  drag_last_ = p;
  // Dragging right turns the object right (the eye goes left); dragging down tilts it down.
  setOrbit(yaw_ - d.x() * kRadiansPerPixel, pitch_ + d.y() * kRadiansPerPixel, distance_);
}

void CloudView::mouseReleaseEvent(QMouseEvent* event) {
  if (event->button() != Qt::LeftButton) return;
  dragging_ = false;
  unsetCursor();
}

void CloudView::wheelEvent(QWheelEvent* event) {
  const double steps = event->angleDelta().y() / 120.0;
  if (steps == 0.0 || !cloud_.cloud) return;
  setOrbit(yaw_, pitch_, distance_ * std::pow(1.15, -steps));
}

}  // namespace artcam::ui
