// SPDX-License-Identifier: Apache-2.0
// The AVX-512 8-bit (to RGB and to RGBA), 16-bit and float RGB bilinear (span_sampler_avx512.h)
// against the portable scalar code and the AVX2 clone, on the spans a warp actually produces:
// smooth runs of positions, where a group of sixteen reads one 64-byte window per source row.
// Its cases, each bit-identical to the scalar path (bytes and transparent counts):
// - groups within one source row, and groups crossing one row (the blended second permute);
// - groups it gathers pixel by pixel (8-bit) or hands to the AVX2 clone: crossing two rows,
//   wider than its window (minified), running right to left; groups touching a border or an
//   invalid pixel, and the tails of spans whose length is not a multiple of sixteen (the
//   clone); groups wholly outside the source (the AVX2 clone writes their zeros without the
//   scalar pass) and groups with no valid pixel;
// - the lower-row limit of the interior (positions just above and below h − 2.5);
// - no read past the image's last byte: the image ends where an unreadable page begins, so a
//   window load that is not masked there (the spans along the last rows' right end) faults.
// On a CPU without AVX-512 the test still compares the AVX2 clone (or the scalar code, when
// there is no SIMD at all) with the scalar path and says so.
#include "core/model/image_view.h"
#include "core/mapping/coordinates.h"
#include "core/sampling/span_sampler.h"
#include "tests/support/test_support.h"

#include <QtTest/QtTest>

#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

using namespace artcam;

namespace {

// Every byte varies (a linear congruential hash), so any wrong tap or weight shows.
std::vector<std::uint8_t> noiseRgb(int w, int h) {
  std::vector<std::uint8_t> img(static_cast<size_t>(w) * static_cast<size_t>(h) * 3);
  std::uint32_t state = 987654321u;
  for (std::uint8_t& b : img) {
    state = state * 1664525u + 1013904223u;
    b = static_cast<std::uint8_t>(state >> 24);
  }
  return img;
}

// A copy of `bytes` bytes that ends exactly where a page no process may read begins.
class GuardedCopy {
 public:
  GuardedCopy(const void* data, size_t bytes) {
    const size_t page = static_cast<size_t>(sysconf(_SC_PAGESIZE));
    span_ = (bytes + page - 1) / page * page + page;
    void* map = mmap(nullptr, span_, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (map == MAP_FAILED) qFatal("mmap failed");
    map_ = static_cast<unsigned char*>(map);
    if (mprotect(map_ + span_ - page, page, PROT_NONE) != 0) qFatal("mprotect failed");
    data_ = map_ + span_ - page - bytes;
    std::memcpy(data_, data, bytes);
  }
  ~GuardedCopy() { munmap(map_, span_); }
  GuardedCopy(const GuardedCopy&) = delete;
  GuardedCopy& operator=(const GuardedCopy&) = delete;
  const void* data() const { return data_; }

 private:
  unsigned char* map_ = nullptr;
  unsigned char* data_ = nullptr;
  size_t span_ = 0;
};

}  // namespace

class TestSimdWindows : public QObject {
  Q_OBJECT

 private slots:
  void smoothSpansMatchScalar() {
    const int w = 150, h = 61;  // rows of 450 bytes: the 64-byte windows fit (dispatch rule)
    const std::vector<std::uint8_t> img = noiseRgb(w, h);
    compareOnSmoothSpans(packedView<const void>(img.data(), w, h, 3, PixelType::UInt8, -1), 1);
  }

  // RGB8 → RGBA8 with alpha appended (the render front door's layout), on the same spans.
  void smoothSpansToRgbaMatchScalar() {
    const int w = 150, h = 61;
    const std::vector<std::uint8_t> img = noiseRgb(w, h);
    compareOnSmoothSpans(packedView<const void>(img.data(), w, h, 3, PixelType::UInt8, -1), 1, 4);
  }

  // The float kernel (eight pixels from 32-float windows) on the same spans, bit for bit.
  void smoothFloatSpansMatchScalar() {
    const int w = 150, h = 61;
    const std::vector<std::uint8_t> bytes = noiseRgb(w, h);
    std::vector<float> img(bytes.size());
    for (size_t i = 0; i < img.size(); ++i) img[i] = static_cast<float>(bytes[i]) * (1.0f / 255.0f) - 0.1f;
    compareOnSmoothSpans(packedView<const void>(img.data(), w, h, 3, PixelType::Float, -1), 4);
  }

  // The 16-bit kernel (the same windows, widened from one 64-byte load a row), bit for bit;
  // samples span the whole 16-bit range, 65535 included, so the rounding clamp is reached.
  void smooth16BitSpansMatchScalar() {
    const int w = 150, h = 61;
    const std::vector<std::uint8_t> bytes = noiseRgb(w, h);
    std::vector<std::uint16_t> img(bytes.size());
    for (size_t i = 0; i < img.size(); ++i)
      img[i] = bytes[i] >= 250 ? 65535 : static_cast<std::uint16_t>(bytes[i] * 257 + (i % 251));
    compareOnSmoothSpans(packedView<const void>(img.data(), w, h, 3, PixelType::UInt16, -1), 2);
  }

 private:
  // `out_channels`: 3, or 4 for RGBA with alpha appended.
  static void compareOnSmoothSpans(const ConstImageView& packed, int sample_bytes, int out_channels = 3) {
    const int w = packed.width, h = packed.height;
    const GuardedCopy guarded(packed.data, static_cast<size_t>(packed.row_bytes) * static_cast<size_t>(h));
    ConstImageView src = packed;
    src.data = guarded.data();
    const int oc = out_channels, alpha = oc == 4 ? 3 : -1;
    std::vector<std::uint8_t> a(static_cast<size_t>(kSpanPixels) * oc * sample_bytes), b(a.size()), c(a.size());
    const PixelType type = src.type;
    const ImageView out_a = packedView<void>(a.data(), kSpanPixels, 1, oc, type, alpha);
    const ImageView out_b = packedView<void>(b.data(), kSpanPixels, 1, oc, type, alpha);
    const ImageView out_c = packedView<void>(c.data(), kSpanPixels, 1, oc, type, alpha);
    const SpanSampler best(src, out_a, Filter::Bilinear, true, true);
    const SpanSampler avx2(src, out_b, Filter::Bilinear, true, false);
    const SpanSampler scalar(src, out_c, Filter::Bilinear, false);
    QVERIFY(!scalar.usesSimd());
    QVERIFY(!avx2.usesAvx512());
    qInfo("AVX-512 window sampler in use: %s", best.usesAvx512() ? "yes" : "no (this CPU lacks avx512bw/vl/vbmi)");
    test::rng().seed(41);
    float sx[kSpanPixels], sy[kSpanPixels];
    unsigned char valid[kSpanPixels];
    for (int round = 0; round < 3000; ++round) {
      const int kind = round % 8;
      // Along the span: columns per pixel (kind 5: minified beyond the window; kind 6: right
      // to left), rows per pixel (kind 4: steep, crossing rows within a group), a little
      // curvature as a lens has.
      double ax = test::uniform(0.3, 1.2), ay = test::uniform(-0.12, 0.12);
      if (kind == 4) ay = test::uniform(0.15, 0.6) * (round % 16 < 8 ? 1 : -1);
      if (kind == 5) ax = test::uniform(1.3, 2.5);
      if (kind == 6) ax = -test::uniform(0.3, 1.2);
      double curve = test::uniform(-2e-3, 2e-3);
      if (kind == 2 && round % 16 < 8) ay = curve = 0.0;  // a whole span at the lower-row limit
      const int n = kind == 7 ? 1 + static_cast<int>(test::uniform(0, kSpanPixels - 1)) : kSpanPixels;
      const double span_x = std::abs(ax) * n + 8;
      double ox = ax > 0 ? test::uniform(1.0, w - span_x) : test::uniform(span_x, w - 1.0);
      double oy = test::uniform(8.0, h - 8.0);
      if (kind == 3) {  // straddling a border
        ox = test::uniform(-6.0, 6.0);
        oy = round % 16 < 8 ? test::uniform(-2.0, 2.0) : test::uniform(h - 4.0, h + 1.0);
        if (round % 24 == 3) oy = test::uniform(h + 0.2, h + 3.0);  // wholly outside: zeros
        if (round % 24 == 11) ox = test::uniform(-30.0, -8.0);      // outside, then entering
      }
      if (kind == 2 && round % 16 < 8) oy = h - 2.0 + test::uniform(-0.02, 0.02);  // fy ≈ h − 2.5
      if (kind == 1 && round % 16 < 8) {  // the last rows' right end: the windows' masked loads
        oy = h - 1.6 + test::uniform(-0.3, 0.3);
        ox = w - 1.5 - ax * n;
        if (ox < 1.0) ox = 1.0;
      }
      for (int i = 0; i < n; ++i) {
        sx[i] = static_cast<float>(ox + ax * i + curve * i * i);
        sy[i] = static_cast<float>(oy + ay * i + curve * i * i);
        valid[i] = (kind == 1 && i % 23 == 7) ? 0 : 1;
        if (kind == 6 && round % 16 < 8 && i >= 16 && i < 56) valid[i] = 0;  // whole groups without a preimage
      }
      const long long ta = best.run(0, 0, n, sx, sy, valid), tb = avx2.run(0, 0, n, sx, sy, valid);
      const long long tc = scalar.run(0, 0, n, sx, sy, valid);
      QCOMPARE(ta, tc);
      QCOMPARE(tb, tc);
      const size_t bytes = static_cast<size_t>(n) * oc * static_cast<size_t>(sample_bytes);
      QVERIFY2(std::equal(a.begin(), a.begin() + static_cast<std::ptrdiff_t>(bytes), c.begin()),
               qPrintable(QString("round %1 (kind %2): the AVX-512 path differs from the scalar").arg(round).arg(kind)));
      QVERIFY2(std::equal(b.begin(), b.begin() + static_cast<std::ptrdiff_t>(bytes), c.begin()),
               qPrintable(QString("round %1 (kind %2): the AVX2 path differs from the scalar").arg(round).arg(kind)));
    }
  }
};

QTEST_GUILESS_MAIN(TestSimdWindows)
#include "test_simd_windows.moc"
