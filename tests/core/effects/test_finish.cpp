// SPDX-License-Identifier: Apache-2.0
// The finishing marks (core/effects/finish.h) against G'MIC run directly on the same values: the
// conversion in and out is exact to a quantisation step, alpha is kept, the seeded finish
// repeats, and unknown names are refused.
#include "core/effects/finish.h"

#include <gmic.h>

#include <QtTest/QtTest>

#include <cmath>
#include <cstdint>
#include <vector>

extern "C" void omp_set_num_threads(int threads);  // libgomp, which libgmic loads

using namespace artcam;

namespace {

std::vector<uint8_t> photo(int w, int h, int channels) {
  std::vector<uint8_t> p(static_cast<size_t>(w) * h * channels);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < channels; ++c)
        p[(static_cast<size_t>(y) * w + x) * channels + c] = static_cast<uint8_t>(
            c == 3 ? 255 : 127 + 100 * std::sin(x / 6.0 + c) * std::cos(y / 9.0 - c));
  return p;
}

}  // namespace

class TestFinish : public QObject {
  Q_OBJECT

 private slots:
  void equalsGmicOnTheSameValues() {
    const int w = 96, h = 64;
    for (const FinishInfo& f : finishes()) {
      std::vector<uint8_t> ours = photo(w, h, 3);
      QVERIFY2(applyFinish(packedView<void>(ours.data(), w, h, 3, PixelType::UInt8), f.name),
               f.name.c_str());
      // G'MIC by hand: planar 0…255 floats in, the same pipeline, rounded back.
      const std::vector<uint8_t> in = photo(w, h, 3);
      gmic_list<float> images;
      gmic_list<char> names;
      images.assign(1);
      images[0].assign(w, h, 1, 3);
      for (int c = 0; c < 3; ++c)
        for (int y = 0; y < h; ++y)
          for (int x = 0; x < w; ++x)
            images[0](x, y, 0, c) = in[(static_cast<size_t>(y) * w + x) * 3 + c];
      if (f.random) omp_set_num_threads(1);  // as the finish runs its random strokes
      gmic(f.gmic.c_str(), images, names, nullptr, true);
      omp_set_num_threads(2);
      int worst = 0;
      for (int c = 0; c < 3; ++c)
        for (int y = 0; y < h; ++y)
          for (int x = 0; x < w; ++x) {
            const unsigned from = std::min<unsigned>(c, images[0]._spectrum - 1);
            const long expected = std::lround(std::clamp(images[0](x, y, 0, from), 0.0f, 255.0f));
            worst = std::max<int>(
                worst, std::abs(ours[(static_cast<size_t>(y) * w + x) * 3 + c] - expected));
          }
      QVERIFY2(worst <= 1, qPrintable(QString("%1: %2").arg(f.name.c_str()).arg(worst)));
      QVERIFY2(ours != in, f.name.c_str());  // it marked something
    }
  }

  void keepsAlphaAndRepeats() {
    const int w = 80, h = 60;
    std::vector<uint8_t> a = photo(w, h, 4), b = photo(w, h, 4);
    for (int y = 0; y < h; ++y)
      a[(static_cast<size_t>(y) * w + 5) * 4 + 3] = b[(static_cast<size_t>(y) * w + 5) * 4 + 3] = 0;
    const ImageView va = packedView<void>(a.data(), w, h, 4, PixelType::UInt8, 3);
    const ImageView vb = packedView<void>(b.data(), w, h, 4, PixelType::UInt8, 3);
    QVERIFY(applyFinish(va, "pencil"));
    QVERIFY(applyFinish(vb, "pencil"));
    QVERIFY(a == b);  // the seeded strokes repeat
    for (int y = 0; y < h; ++y) {
      const uint8_t* p = &a[(static_cast<size_t>(y) * w + 5) * 4];
      QCOMPARE(int(p[3]), 0);
      QCOMPARE(int(p[0]), 0);  // premultiplied: nothing where alpha is 0
      const uint8_t* q = &a[(static_cast<size_t>(y) * w + 20) * 4];
      QCOMPARE(int(q[3]), 255);
      QCOMPARE(int(q[0]), int(q[1]));  // pencil is grey
    }
  }

  void refusals() {
    std::vector<uint8_t> p = photo(8, 8, 3);
    const Status s = applyFinish(packedView<void>(p.data(), 8, 8, 3, PixelType::UInt8), "crayola");
    QVERIFY(!s);
    QVERIFY(QString::fromStdString(s.message).contains("unknown finish"));
    QVERIFY(QString::fromStdString(s.message).contains("pencil"));
  }
};

QTEST_GUILESS_MAIN(TestFinish)
#include "test_finish.moc"
