// artcam-studio-bench: the studio's edit-to-preview latency (a benchmark,
// not a test). A 24-megapixel photo (made in code, or --photo FILE) is loaded as the studio
// loads it (display copy and 8-bit mip pyramid built once), ten pairs through a rational lens
// are fitted, and then each edit moves one target point and the clock runs from the edit (the
// refit included) until the final pass of the preview (fitted into 1920×1080) is in the controller.
// Prints the median, minimum and 90th percentile; run on an otherwise idle machine.
#include "core/io/image_io.h"
#include "ui/document.h"
#include "ui/photo.h"
#include "ui/preview_controller.h"

#include <QApplication>
#include <QElapsedTimer>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

using namespace artcam;
using namespace artcam::ui;

namespace {

LoadedImage syntheticPhoto(int w, int h) {
  LoadedImage loaded;
  loaded.image = ImageF(w, h, 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      float* p = loaded.image.pixel(x, y);
      p[0] = static_cast<float>(0.5 + 0.4 * std::sin(x / 37.0));
      p[1] = static_cast<float>(0.5 + 0.4 * std::cos(y / 53.0));
      p[2] = static_cast<float>(((x / 64 + y / 64) % 2) ? 0.8 : 0.2);
    }
  return loaded;
}

bool waitForFinal(const PreviewController& c, int timeout_ms) {
  QElapsedTimer t;
  t.start();
  while (t.elapsed() < timeout_ms) {
    if (c.imageIsFinal() && c.imageGeneration() == c.requestedGeneration() && !c.image().isNull())
      return true;
    QCoreApplication::processEvents(QEventLoop::AllEvents, 1);
  }
  return false;
}

double percentile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<size_t>(q * static_cast<double>(v.size())))];
}

}  // namespace

int main(int argc, char** argv) {
  if (qEnvironmentVariableIsEmpty("QT_QPA_PLATFORM")) qputenv("QT_QPA_PLATFORM", "offscreen");
  QApplication app(argc, argv);
  std::string photo_path;
  int edits = 40;
  double strength = 0.12;  // the lens's radial term at the frame corner (normalised radius 1)
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--photo") == 0 && i + 1 < argc) photo_path = argv[++i];
    else if (std::strcmp(argv[i], "--edits") == 0 && i + 1 < argc) edits = std::max(3, std::atoi(argv[++i]));
    else if (std::strcmp(argv[i], "--strength") == 0 && i + 1 < argc) strength = std::atof(argv[++i]);
    else {
      std::printf("usage: artcam-studio-bench [--photo FILE] [--edits N] [--strength S]\n");
      return 2;
    }
  }
  QElapsedTimer clock;
  clock.start();
  LoadedImage loaded;
  if (photo_path.empty()) {
    loaded = syntheticPhoto(6000, 4000);
  } else {
    auto r = readImage(photo_path);
    if (!r) {
      std::fprintf(stderr, "%s\n", r.status.message.c_str());
      return 1;
    }
    loaded = std::move(*r);
  }
  const double decode_ms = static_cast<double>(clock.restart());
  const PhotoPtr photo = makePhoto(QString::fromStdString(photo_path), std::move(loaded));
  const double prepare_ms = static_cast<double>(clock.restart());
  const FrameSize size = photo->size();
  const FrameSize preview = livePreviewSize(*photo);

  // Ten pairs through a mild rational lens about the centre (so the quadratic model fits).
  std::vector<Pair> pairs;
  const Eigen::Vector2d c(0.5 * size.width, 0.5 * size.height);
  for (int k = 0; k < 10; ++k) {
    const Eigen::Vector2d s(size.width * (0.15 + 0.7 * (k % 4) / 3.0),
                            size.height * (0.15 + 0.7 * (k / 4) / 2.0) + 37.0 * k);
    const Eigen::Vector2d d = (s - c) / c.norm();
    pairs.push_back({s, c + (s - c) / (1.0 + strength * d.squaredNorm()), true});
  }
  Document doc;
  PreviewController controller(&doc);
  doc.reset(photo, pairs, ModelClass::Quadratic);
  if (!waitForFinal(controller, 60000)) {
    std::fprintf(stderr, "the first preview did not arrive\n");
    return 1;
  }
  std::vector<double> latency_ms, render_ms;
  for (int e = 0; e < edits; ++e) {
    Pair moved = doc.pairs()[static_cast<size_t>(e % 10)];
    moved.target.x() += (e % 2 ? -3.0 : 3.0);
    clock.restart();
    doc.setPairs({e % 10}, {moved});
    if (!waitForFinal(controller, 60000)) {
      std::fprintf(stderr, "edit %d: no preview\n", e);
      return 1;
    }
    latency_ms.push_back(static_cast<double>(clock.nsecsElapsed()) / 1e6);
    render_ms.push_back(controller.lastRenderMs());
  }
  std::printf("lens strength %.3g\n", strength);
  std::printf("photo %dx%d (decode %.0f ms, display copy + pyramid %.0f ms), preview %dx%d\n",
              size.width, size.height, decode_ms, prepare_ms, preview.width, preview.height);
  std::printf("edit-to-preview over %d edits: median %.1f ms, min %.1f ms, p90 %.1f ms "
              "(final-pass render alone: median %.1f ms)\n",
              edits, percentile(latency_ms, 0.5), percentile(latency_ms, 0.0),
              percentile(latency_ms, 0.9), percentile(render_ms, 0.5));
  return 0;
}
