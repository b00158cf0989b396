// SPDX-License-Identifier: Apache-2.0
// A finish leaves the program's floating-point mode alone: Debian's libgmic is built with
// -ffast-math, whose loader turns on flush-to-zero and denormals-are-zero (finish_gmic.cpp), and
// every later float result of the program (the .artcam writer's round trip of a denormal, the
// fits) would change with it.
#include "core/effects/finish.h"

#include <QtTest/QtTest>

#include <cstdint>
#include <limits>
#include <vector>
#if defined(__SSE__)
#include <xmmintrin.h>
#endif

using namespace artcam;

class TestFinishFloatMode : public QObject {
  Q_OBJECT

 private slots:
  void denormalsSurviveAFinish() {
#if defined(__SSE__)
    const unsigned before = _mm_getcsr();
#endif
    std::vector<uint8_t> pixels(64 * 48 * 3, 128);
    for (size_t i = 0; i < pixels.size(); ++i) pixels[i] = static_cast<uint8_t>(i * 7);
    QVERIFY(applyFinish(packedView<void>(pixels.data(), 64, 48, 3, PixelType::UInt8), "cartoon"));
#if defined(__SSE__)
    QCOMPARE(_mm_getcsr() & 0x8040u, before & 0x8040u);  // FTZ (bit 15) and DAZ (bit 6)
#endif
    volatile double tiny = std::numeric_limits<double>::denorm_min();
    volatile double twice = tiny * 2.0;
    QVERIFY(twice > 0.0);
  }
};

QTEST_GUILESS_MAIN(TestFinishFloatMode)
#include "test_finish_float_mode.moc"
