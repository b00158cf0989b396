// SPDX-License-Identifier: Apache-2.0
// The guards of auto for straight lines (core/fit/line_model_guard.h) against maps whose
// spacing and coverage this file works out by hand: a keystone y = x / (1 + a u) in the
// normalised frame (its spacings worked out below), and a shift by 30 % of
// the frame's width (which leaves that much of the frame empty).
#include "core/fit/line_model_guard.h"
#include "core/model/frames.h"

#include <QtTest/QtTest>

#include <algorithm>
#include <cmath>

using namespace artcam;

namespace {

const FrameSize kFrame{960, 720};

// Tensors (normalised frames) of y = (u + t_u, v) / (1 + a u): x Q_i xᵀ with x = (u, v, 1).
Camera projective(double a, double t_u) {
  Eigen::Matrix3d q1 = Eigen::Matrix3d::Zero(), q2 = Eigen::Matrix3d::Zero(),
                  q3 = Eigen::Matrix3d::Zero();
  q1(0, 2) = q1(2, 0) = 0.5;
  q1(2, 2) = t_u;
  q2(1, 2) = q2(2, 1) = 0.5;
  q3(0, 2) = q3(2, 0) = a / 2;
  q3(2, 2) = 1.0;
  return Camera::rtcam({q1, q2, q3}, kFrame, kFrame);
}

}  // namespace

class TestLineModelGuard : public QObject {
  Q_OBJECT

 private slots:
  void sameMapChangesNothing() {
    const Camera identity = projective(0.0, 0.0);
    QVERIFY(spacingChange(identity, identity) < 1e-9);
    QVERIFY(std::abs(frameCoverage(identity) - 1.0) < 1e-9);
  }

  void keystoneIsMeasured() {
    const double a = 0.3;
    // Over the guard's 9×7 grid (5 % in from the edges): a row's spacing |∂y/∂u| is
    // √(1 + a²v²) / (1 + a u)², a column's |∂y/∂v| is 1 / (1 + a u).
    double expected = 0.0;
    for (int j = 0; j < 7; ++j)
      for (int i = 0; i < 9; ++i) {
        const Eigen::Vector2d n = normalizedFromPixel(
            kFrame,
            {kFrame.width * (0.05 + 0.9 * i / 8.0), kFrame.height * (0.05 + 0.9 * j / 6.0)});
        const double w = 1 + a * n.x();
        expected = std::max({expected, std::abs(std::sqrt(1 + a * a * n.y() * n.y()) / (w * w) - 1),
                             std::abs(1 / w - 1)});
      }
    const double measured = spacingChange(projective(a, 0.0), projective(0.0, 0.0));
    qInfo("keystone %.2f: spacing change %.4f, by hand %.4f", a, measured, expected);
    QVERIFY2(std::abs(measured - expected) < 0.02 * expected,
             qPrintable(QString::number(measured)));
  }

  void shiftLeavesTheFrameEmpty() {
    // 30 % of the width: the shift in normalised units is 0.3 w / (max(w, h) / 2).
    const double t_u = 0.3 * kFrame.width / (std::max(kFrame.width, kFrame.height) / 2.0);
    const double covered = frameCoverage(projective(0.0, t_u));
    qInfo("shift by 30 %% of the width: covered %.4f", covered);
    QVERIFY2(std::abs(covered - 0.7) < 0.03, qPrintable(QString::number(covered)));
  }
};

QTEST_GUILESS_MAIN(TestLineModelGuard)
#include "test_line_model_guard.moc"
