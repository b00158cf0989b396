// SPDX-License-Identifier: Apache-2.0
// The AVX2 16-bit and float samplers (nearest and bilinear, span_sampler_avx2_wide.h) against
// the portable scalar code: every output sample identical (floats bit for bit) and the same
// transparent count, for RGB, RGBA, RGB with alpha appended and RGBA with alpha, on:
// - random positions over the image and past its borders, and smooth spans as a warp makes;
// - exact pixel centres (a zero weight times a sample: −0 for a −0 sample, which the scalar
//   sum turns to +0) and the interior's exact limits, the last row and column included;
// - the image's last pixels, whose loads must stay inside the buffer: the source ends right
//   before a page the process may not read, so a load past it crashes the test;
// - invalid pixels, NaN, infinite and huge positions; groups wholly outside;
// - sources with −0, NaN and out-of-range float samples, 16-bit samples at full scale (the
//   rounding offset clamps), alphas of 0 (transparent) and, for float, outside [0, 1];
// - rows with padding between them.
// On a CPU without AVX2 the comparison is scalar against scalar, and the test says so.
#include "core/model/image_view.h"
#include "core/mapping/coordinates.h"
#include "core/sampling/span_sampler.h"
#include "tests/support/test_support.h"

#include <QtTest/QtTest>

#include <sys/mman.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

using namespace artcam;

namespace {

// `bytes` of memory whose last byte is followed by a page that may not be read.
class GuardedBuffer {
 public:
  explicit GuardedBuffer(size_t bytes) : bytes_(bytes) {
    const size_t page = static_cast<size_t>(sysconf(_SC_PAGESIZE));
    const size_t data_pages = (bytes + page - 1) / page;
    size_ = (data_pages + 1) * page;
    void* m = mmap(nullptr, size_, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (m == MAP_FAILED) qFatal("mmap failed");
    base_ = static_cast<unsigned char*>(m);
    if (mprotect(base_ + data_pages * page, page, PROT_NONE) != 0) qFatal("mprotect failed");
    data_ = base_ + data_pages * page - bytes;
  }
  ~GuardedBuffer() { munmap(base_, size_); }
  GuardedBuffer(const GuardedBuffer&) = delete;
  GuardedBuffer& operator=(const GuardedBuffer&) = delete;
  unsigned char* data() const { return data_; }
  size_t bytes() const { return bytes_; }

 private:
  unsigned char* base_ = nullptr;
  unsigned char* data_ = nullptr;
  size_t size_ = 0, bytes_ = 0;
};

std::uint32_t hashStep(std::uint32_t& state) {
  state = state * 1664525u + 1013904223u;
  return state;
}

// One sample of pixel (x, y), channel c: noise, with blocks that exercise the stores.
template <class T>
T sampleAt(int x, int y, int c, int alpha, std::uint32_t& state) {
  const std::uint32_t r = hashStep(state);
  const bool block_a = (x / 3 + y / 3) % 7 == 0;  // 3 × 3 blocks: whole bilinear cells
  const bool block_b = (x / 4 + 2 * (y / 4)) % 9 == 4;
  if constexpr (std::is_same_v<T, std::uint16_t>) {
    if (c == alpha && block_a) return 0;              // transparent cells
    if (block_b) return 65535;                        // + ½ clamps
    return static_cast<std::uint16_t>(r >> 16);
  } else {
    if (c == alpha) {
      if (block_a) return (r & 256) ? -0.0f : 0.0f;   // transparent, −0 included
      return static_cast<float>(static_cast<double>(r >> 8) / 16777216.0 * 1.4 - 0.2);  // [−0.2, 1.2)
    }
    if (block_a) return -0.0f;                        // −0 cells: the sum's + 0 matters
    if (block_b && r % 5 == 0) return std::numeric_limits<float>::quiet_NaN();
    if (block_b) return (r & 512) ? 3.0e30f : -7.5f;
    return static_cast<float>(static_cast<double>(r >> 8) / 16777216.0 * 2.0 - 0.5);  // [−0.5, 1.5)
  }
}

struct Config {
  PixelType type;
  int channels, alpha;  // alpha = channels: appended to the output
  Filter filter;
  int padding;          // samples between rows
};

template <class T>
void compareSampler(const Config& cfg) {
  const int w = 37, h = 23;  // odd sizes
  const int C = cfg.channels, S = static_cast<int>(sizeof(T));
  const bool append = cfg.alpha == C;
  const int src_alpha = append ? -1 : cfg.alpha, out_channels = C + (append ? 1 : 0);
  const std::ptrdiff_t row = static_cast<std::ptrdiff_t>(w * C + cfg.padding) * S;
  // The buffer ends at the last pixel's last byte (no padding after the last row).
  GuardedBuffer buffer(static_cast<size_t>((h - 1) * row + w * C * S));
  std::uint32_t state = 777u + static_cast<std::uint32_t>(C * 10 + cfg.alpha);
  for (int y = 0; y < h; ++y) {
    T* r = static_cast<T*>(static_cast<void*>(buffer.data() + y * row));
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < C; ++c) r[x * C + c] = sampleAt<T>(x, y, c, src_alpha, state);
  }
  ConstImageView src = packedView<const void>(buffer.data(), w, h, C, cfg.type, src_alpha);
  src.row_bytes = row;
  const int n_max = kSpanPixels;
  std::vector<T> a(static_cast<size_t>(n_max * out_channels)), b(a.size());
  const ImageView out_a = packedView<void>(a.data(), n_max, 1, out_channels, cfg.type, append ? C : src_alpha);
  const ImageView out_b = packedView<void>(b.data(), n_max, 1, out_channels, cfg.type, append ? C : src_alpha);
  const SpanSampler simd(src, out_a, cfg.filter, true), scalar(src, out_b, cfg.filter, false);
  QVERIFY(!scalar.usesSimd());
  static bool told = false;
  if (!told) qInfo("AVX2 16-bit/float sampler in use: %s", simd.usesSimd() ? "yes" : "no (this CPU has no AVX2)");
  told = true;

  test::rng().seed(static_cast<unsigned>(C * 100 + cfg.alpha * 7 + static_cast<int>(cfg.filter)));
  float sx[kSpanPixels], sy[kSpanPixels];
  unsigned char valid[kSpanPixels];
  const float below_w = std::nextafter(w - 0.5f, 0.0f), below_h = std::nextafter(h - 0.5f, 0.0f);
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  long long vector_groups = 0;
  for (int round = 0; round < 1500; ++round) {
    const int kind = round % 8;
    const int n = round % 3 == 0 ? 61 : n_max;  // 61: a scalar tail
    const double ax = test::uniform(0.3, 1.3), ay = test::uniform(-0.1, 0.1);
    const double ox = test::uniform(0.5, w - 0.5 - ax * n / 2), oy = test::uniform(0.5, h - 0.5);
    for (int i = 0; i < n; ++i) {
      valid[i] = 1;
      switch (kind) {
        case 0:  // anywhere, and past the borders
          sx[i] = static_cast<float>(test::uniform(-3.0, w + 3.0));
          sy[i] = static_cast<float>(test::uniform(-3.0, h + 3.0));
          break;
        case 1:  // inside
          sx[i] = static_cast<float>(test::uniform(0.5, w - 0.5));
          sy[i] = static_cast<float>(test::uniform(0.5, h - 0.5));
          break;
        case 2:  // a smooth run, as the warp's spans (wrapping in x to stay mostly inside)
          sx[i] = static_cast<float>(std::fmod(ox + ax * i, w - 1.0) + 0.5);
          sy[i] = static_cast<float>(oy + ay * i);
          break;
        case 3: {  // pixel centres and the interior's exact limits
          const int pick = static_cast<int>(test::uniform(0, 8));
          const float cx[8] = {0.5f, 1.5f, w - 1.5f, w - 0.5f, below_w, 0.5f, static_cast<float>(w / 2) + 0.5f, w - 1.0f};
          const float cy[8] = {0.5f, h - 1.5f, below_h, h - 0.5f, 1.0f, below_h, static_cast<float>(h / 2) + 0.5f, 0.5f};
          sx[i] = i % 2 ? cx[pick] : static_cast<float>(static_cast<int>(test::uniform(0, w))) + 0.5f;
          sy[i] = i % 3 ? cy[pick] : static_cast<float>(static_cast<int>(test::uniform(0, h))) + 0.5f;
          break;
        }
        case 4:  // the last row and column: the loads' end of the buffer
          sx[i] = static_cast<float>(test::uniform(w - 3.0, w + 0.2));
          sy[i] = static_cast<float>(test::uniform(h - 3.0, h + 0.2));
          if (i % 5 == 0) sx[i] = below_w, sy[i] = below_h;
          break;
        case 5:  // invalid pixels, NaN, infinite and huge positions among interior ones
          sx[i] = static_cast<float>(test::uniform(0.5, w - 0.5));
          sy[i] = static_cast<float>(test::uniform(0.5, h - 0.5));
          if (i % 11 == 3) valid[i] = 0;
          if (i % 13 == 5) sx[i] = nan;
          if (i % 17 == 6) sy[i] = nan;
          if (i % 19 == 7) sx[i] = i % 2 ? inf : -inf;
          if (i % 23 == 8) sy[i] = i % 2 ? 3.0e9f : -3.0e9f;
          break;
        case 6:  // whole groups outside, then entering
          sx[i] = static_cast<float>(i < n / 2 ? test::uniform(-40.0, -2.0) : test::uniform(-1.5, 3.0));
          sy[i] = static_cast<float>(test::uniform(0.0, h));
          break;
        default:  // mostly interior, a few invalid
          sx[i] = static_cast<float>(ox + ax * i * 0.4);
          sy[i] = static_cast<float>(oy + ay * i);
          valid[i] = i % 29 == 13 ? 0 : 1;
          break;
      }
    }
    std::fill(a.begin(), a.end(), T(1));
    std::fill(b.begin(), b.end(), T(2));
    const long long ta = simd.run(0, 0, n, sx, sy, valid), tb = scalar.run(0, 0, n, sx, sy, valid);
    QVERIFY2(ta == tb, qPrintable(QString("round %1 (kind %2): transparent %3 vs %4").arg(round).arg(kind).arg(ta).arg(tb)));
    const size_t samples = static_cast<size_t>(n * out_channels);
    for (size_t s = 0; s < samples; ++s)
      if (std::memcmp(&a[s], &b[s], sizeof(T)) != 0) {
        const double va = static_cast<double>(a[s]), vb = static_cast<double>(b[s]);
        const int p = static_cast<int>(s) / out_channels;
        QFAIL(qPrintable(QString("round %1 (kind %2), pixel %3 (%4, %5) channel %6: %7 vs scalar %8%9")
                             .arg(round).arg(kind).arg(p).arg(sx[p], 0, 'g', 9).arg(sy[p], 0, 'g', 9)
                             .arg(static_cast<int>(s) % out_channels).arg(va, 0, 'g', 9).arg(vb, 0, 'g', 9)
                             .arg(std::signbit(va) != std::signbit(vb) ? " (sign)" : "")));
      }
    // The samples past the span untouched.
    for (size_t s = samples; s < a.size(); ++s) QVERIFY(a[s] == T(1));
    vector_groups += kind == 1 || kind == 2;
  }
  QVERIFY(vector_groups > 0);
}

}  // namespace

class TestWideSampler : public QObject {
  Q_OBJECT

 private slots:
  void simdMatchesScalar_data() {
    QTest::addColumn<int>("type");
    QTest::addColumn<int>("channels");
    QTest::addColumn<int>("alpha");
    QTest::addColumn<int>("filter");
    QTest::addColumn<int>("padding");
    for (int t : {1, 2})
      for (int f : {0, 1})
        for (int c : {3, 4})
          for (int a : {-1, c - 1, c}) {
            if (c == 4 && a == 4) continue;  // alpha appended only to RGB
            for (int pad : {0, 3}) {
              const char* type = t == 1 ? "uint16" : "float";
              const char* filter = f == 0 ? "nearest" : "bilinear";
              QTest::newRow(qPrintable(QString("%1 %2 %3ch alpha %4 pad %5").arg(type, filter).arg(c).arg(a).arg(pad)))
                  << t << c << a << f << pad;
            }
          }
  }

  void simdMatchesScalar() {
    QFETCH(int, type);
    QFETCH(int, channels);
    QFETCH(int, alpha);
    QFETCH(int, filter);
    QFETCH(int, padding);
    const Config cfg{type == 1 ? PixelType::UInt16 : PixelType::Float, channels, alpha,
                     filter == 0 ? Filter::Nearest : Filter::Bilinear, padding};
    if (cfg.type == PixelType::UInt16) compareSampler<std::uint16_t>(cfg);
    else compareSampler<float>(cfg);
  }

  // The supersampled and bicubic paths stay scalar; the sampler takes them all the same.
  void otherPathsStillMatch() {
    const int w = 19, h = 11;
    std::vector<float> img(static_cast<size_t>(w * h * 3));
    std::uint32_t state = 5u;
    for (float& v : img) v = static_cast<float>(hashStep(state) >> 8) / 16777216.0f;
    const ConstImageView src = packedView<const void>(img.data(), w, h, 3, PixelType::Float);
    std::vector<float> a(static_cast<size_t>(16 * 3)), b(a.size());
    const ImageView out_a = packedView<void>(a.data(), 16, 1, 3, PixelType::Float);
    const ImageView out_b = packedView<void>(b.data(), 16, 1, 3, PixelType::Float);
    float sx[16], sy[16], jac[4] = {1.5f, 0.1f, -0.2f, 1.3f};
    unsigned char valid[16];
    for (int i = 0; i < 16; ++i) sx[i] = 2.0f + 0.7f * i, sy[i] = 5.3f, valid[i] = 1;
    for (Filter f : {Filter::Nearest, Filter::Bilinear, Filter::Bicubic}) {
      const SpanSampler simd(src, out_a, f, true), scalar(src, out_b, f, false);
      QCOMPARE(simd.run(0, 0, 16, sx, sy, valid, 3, jac), scalar.run(0, 0, 16, sx, sy, valid, 3, jac));
      QVERIFY(std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0);
      QCOMPARE(simd.run(0, 0, 16, sx, sy, valid), scalar.run(0, 0, 16, sx, sy, valid));
      QVERIFY(std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0);
    }
  }
};

QTEST_GUILESS_MAIN(TestWideSampler)
#include "test_wide_sampler.moc"
