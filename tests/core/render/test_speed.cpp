// Render speed of the homography and rational kernels, printed so it can be quoted. Runs on a
// 600×400 synthetic image; set ARTCAM_RENDER_BENCH_SIZE=6000x4000 for a full-size figure.
// The only assertion is a generous floor that catches a kernel falling off a cliff.
#include "core/render/warp.h"
#include "tests/core/render/render_fixtures.h"
#include "tests/support/test_support.h"

#include <QtTest/QtTest>

#include <cstdlib>
#include <cstdio>
#include <thread>

using namespace artcam;

class TestSpeed : public QObject {
  Q_OBJECT

 private slots:
  void kernels() {
    FrameSize size{600, 400};
    if (const char* env = std::getenv("ARTCAM_RENDER_BENCH_SIZE"))
      if (std::sscanf(env, "%dx%d", &size.width, &size.height) != 2) size = {600, 400};
    const ImageF src = test::syntheticImage(size.width, size.height);
    test::rng().seed(5);
    const Camera rational = test::randomRationalCamera(size, size, 0.1);
    Eigen::Matrix3d h;
    h << 1.05, 0.08, 0.02, -0.06, 0.97, -0.03, 0.06, -0.04, 1.0;
    const Camera homography = test::homographyCamera(h, size, size);
    const double mpix = size.width * static_cast<double>(size.height) / 1e6;
    for (Filter f : {Filter::Bilinear, Filter::Bicubic}) {
      for (const auto& [name, camera] : {std::pair{"homography", &homography}, std::pair{"rational", &rational}}) {
        WarpOptions o;
        o.filter = f;
        WarpSummary s;
        const ImageF out = warpImage(src, *camera, o, &s);
        QVERIFY(!out.empty());
        const double rate = mpix / (s.render_ms / 1000.0);
        qInfo("%dx%d %s %s: %.1f ms, %.1f Mpix/s on %d threads (kernel %s)", size.width, size.height,
              name, filterName(f).data(), s.render_ms, rate, resolveThreads(), s.kernel.c_str());
        QVERIFY(rate > 0.1);  // a cliff, not a benchmark: CI machines are shared
      }
    }
  }

 private:
  static int resolveThreads() { return static_cast<int>(std::max(1u, std::thread::hardware_concurrency())); }
};

QTEST_GUILESS_MAIN(TestSpeed)
#include "test_speed.moc"
