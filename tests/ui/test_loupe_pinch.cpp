// SPDX-License-Identifier: Apache-2.0
// Pinch zoom (touchpad native zoom gestures and touch-screen QPinchGesture, synthetic events)
// keeps the image point under the gesture fixed; the loupe shows while a point is placed or
// dragged and its pixels are the photo's, magnified about the exact cursor position.
#include "tests/ui/ui_fixtures.h"
#include "ui/canvas.h"
#include "ui/document.h"
#include "ui/tools/pair_tool.h"

#include <QGestureEvent>
#include <QNativeGestureEvent>
#include <QPinchGesture>
#include <QPointingDevice>
#include <QtTest/QtTest>

#include <cmath>
#include <memory>

using namespace artcam;
using namespace artcam::ui;

class TestLoupePinch : public QObject {
  Q_OBJECT

 private slots:
  void nativePinchZoomsAboutTheGesture() {
    Document doc;
    Canvas canvas(&doc);
    canvas.resize(640, 480);
    doc.reset(test::syntheticPhoto());
    canvas.zoomToFit();
    const double s0 = canvas.view().scale();
    const QPointF at(400.0, 150.0);
    const QPointF image_at = canvas.view().imageFromWidget(at);
    QNativeGestureEvent zoom(Qt::ZoomNativeGesture, QPointingDevice::primaryPointingDevice(), 2,
                             at, at, canvas.mapToGlobal(at), 0.5, QPointF(), 1);
    QVERIFY(QCoreApplication::sendEvent(&canvas, &zoom));
    QVERIFY(std::abs(canvas.view().scale() - 1.5 * s0) < 1e-12);
    const QPointF still = canvas.view().widgetFromImage(image_at);
    QVERIFY(std::hypot(still.x() - at.x(), still.y() - at.y()) < 1e-9);
    QNativeGestureEvent out(Qt::ZoomNativeGesture, QPointingDevice::primaryPointingDevice(), 2,
                            at, at, canvas.mapToGlobal(at), -0.2, QPointF(), 1);
    QCoreApplication::sendEvent(&canvas, &out);
    QVERIFY(std::abs(canvas.view().scale() - 1.5 * 0.8 * s0) < 1e-12);
  }

  void touchPinchGestureZooms() {
    Document doc;
    Canvas canvas(&doc);
    canvas.resize(640, 480);
    canvas.show();
    QVERIFY(QTest::qWaitForWindowExposed(&canvas));
    doc.reset(test::syntheticPhoto());
    canvas.zoomToFit();
    const double s0 = canvas.view().scale();
    const QPointF at(200.0, 300.0);
    const QPointF image_at = canvas.view().imageFromWidget(at);
    QPinchGesture pinch;
    pinch.setScaleFactor(2.0);
    pinch.setChangeFlags(QPinchGesture::ScaleFactorChanged);
    pinch.setCenterPoint(canvas.mapToGlobal(at));
    QGestureEvent event({&pinch});
    QVERIFY(QCoreApplication::sendEvent(&canvas, &event));
    QVERIFY(std::abs(canvas.view().scale() - 2.0 * s0) < 1e-12);
    const QPointF still = canvas.view().widgetFromImage(image_at);
    QVERIFY(std::hypot(still.x() - at.x(), still.y() - at.y()) < 1e-6);
  }

  void loupeMagnifiesAroundTheCursorWhilePlacing() {
    Document doc;
    Canvas canvas(&doc);
    canvas.setTool(std::make_unique<PairTool>(&canvas, &doc));
    canvas.resize(640, 480);
    canvas.show();
    QVERIFY(QTest::qWaitForWindowExposed(&canvas));
    doc.reset(test::syntheticPhoto());
    canvas.zoomToFit();
    const QPoint cursor(200, 250);
    test::sendMouse(&canvas, QEvent::MouseMove, cursor, Qt::NoButton, Qt::NoButton);
    QVERIFY(!canvas.loupe().isValid());  // hovering: no loupe
    test::click(&canvas, cursor);        // a source placed: now placing its target
    const QPoint target_cursor(230, 260);
    test::sendMouse(&canvas, QEvent::MouseMove, target_cursor, Qt::NoButton, Qt::NoButton);
    const LoupeGeometry g = canvas.loupe();
    QVERIFY(g.isValid());
    QVERIFY(g.scale >= Loupe::kMinScale);
    const QPointF image_cursor = canvas.view().imageFromWidget(QPointF(target_cursor));
    QCOMPARE(g.image_centre, image_cursor);
    QVERIFY(!g.widget_rect.contains(QPointF(target_cursor)));  // never over the point placed

    // The loupe's pixels are the photo's display pixels at the mapped positions.
    const QImage shot = canvas.grab().toImage().convertToFormat(QImage::Format_RGB32);
    const QImage& display = doc.photo()->display;
    int checked = 0;
    for (int dy = -60; dy <= 60; dy += 13)
      for (int dx = -60; dx <= 60; dx += 11) {
        if (std::abs(dx) < 16 || std::abs(dy) < 16) continue;  // the crosshair
        const QPointF w = g.widget_rect.center() + QPointF(dx, dy);
        const QPointF p = g.imageFromWidget(w + QPointF(0.5, 0.5));  // centre of widget pixel
        // Skip samples within a tenth of a photo pixel of a pixel edge (rounding either way).
        const double fx = p.x() - std::floor(p.x()), fy = p.y() - std::floor(p.y());
        if (fx < 0.1 || fx > 0.9 || fy < 0.1 || fy > 0.9) continue;
        const QRgb expected = display.pixel(static_cast<int>(p.x()), static_cast<int>(p.y()));
        const QRgb actual = shot.pixel(static_cast<int>(w.x()), static_cast<int>(w.y()));
        QVERIFY2(qRed(expected) == qRed(actual) && qGreen(expected) == qGreen(actual) &&
                     qBlue(expected) == qBlue(actual),
                 qPrintable(QString("at %1,%2").arg(dx).arg(dy)));
        ++checked;
      }
    QVERIFY(checked > 20);

    // Turned off, or once the pair is complete, it goes away.
    canvas.setLoupeEnabled(false);
    QVERIFY(!canvas.loupe().isValid());
    canvas.setLoupeEnabled(true);
    test::click(&canvas, target_cursor);
    QCOMPARE(doc.pairs().size(), size_t{1});
    QVERIFY(!canvas.loupe().isValid());
  }
};

QTEST_MAIN(TestLoupePinch)
#include "test_loupe_pinch.moc"
