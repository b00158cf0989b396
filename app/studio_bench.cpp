// SPDX-License-Identifier: Apache-2.0
// artcam-studio-bench: the studio's responsiveness (a benchmark, not a test; run it on an
// otherwise idle machine and quote the load). Two modes, both printing key=value lines:
//
//   latency (default): a 24-megapixel photo (made in code, or --photo FILE) is loaded as the
//     studio loads it (a JPEG's reduced first look, then the full photo swapped in; display
//     copy and 8-bit mip pyramid built once per photo), ten pairs through a
//     rational lens are fitted, then each edit moves one target point and the clock runs from
//     the edit (the refit included) until the final pass of the preview (fitted into 1920×1080)
//     is in the controller.
//   --drag: the whole studio window (canvas with the pair tool, pairs table, preview, panels)
//     with --pairs pairs (default 300) through the same lens; the mouse grabs one target point
//     and drags it through --moves mouse-move events (default 120), one every 8 ms (a 125 Hz
//     mouse). It measures the GUI thread's time inside each move event, the event loop's
//     longest stalls (a 1 ms heartbeat timer's gaps), the edit-to-preview latency of every move
//     (until a final preview of that edit or a newer one is shown), the GUI thread's CPU time
//     over the drag (what it did itself, against the wall time others kept it waiting) and
//     where the fits ran.
#include "core/io/first_look.h"
#include "core/io/image_io.h"
#include "core/io/jpeg_decode.h"
#include "ui/canvas.h"
#include "ui/document.h"
#include "ui/document_fit.h"
#include "ui/image_loader.h"
#include "ui/main_window.h"
#include "ui/photo.h"
#include "ui/preview_controller.h"
#include "ui/session.h"

#include <QApplication>
#include <QElapsedTimer>
#include <QEventLoop>
#include <QMouseEvent>
#include <QFile>
#include <QStandardPaths>
#include <QTimer>

#include <time.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <map>
#include <string>
#include <vector>

using namespace artcam;
using namespace artcam::ui;

namespace {

const char kUsage[] =
    "usage: artcam-studio-bench [--drag] [--photo FILE] [--edits N] [--strength S]\n"
    "                           [--pairs N] [--moves N] [--fit-on-gui-thread]\n"
    "                           [--export PROJECT -o OUT] [--help]\n"
    "\n"
    "Measures the studio's responsiveness and prints key=value lines. Run it on an idle\n"
    "machine; the figures are wall-clock times.\n"
    "\n"
    "modes:\n"
    "  (default)            edit-to-preview latency: ten pairs through a rational lens on a\n"
    "                       24-megapixel photo; each edit moves one target point and waits for\n"
    "                       the final preview pass (median, min, p90); also\n"
    "                       first_preview_ms and first_final_preview_ms, from opening the\n"
    "                       photo as the studio opens it (a JPEG's first look, decoded\n"
    "                       reduced; first_look_delivered_ms when it reaches the document)\n"
    "                       to its first and its final preview, full_photo_ms to\n"
    "                       the full photo swapped in, and apart: decode_ms and prepare_ms\n"
    "                       (the whole read and its copies) and djpeg_ms (one libjpeg decode)\n"
    "  --drag               a mouse drag in the whole studio window: one target point of\n"
    "                       --pairs pairs is dragged through --moves mouse moves at 125 Hz;\n"
    "                       prints the GUI thread's time per move event (median, max), the\n"
    "                       event loop's longest stalls, the GUI thread's CPU time, the\n"
    "                       edit-to-preview latency and how many fits ran on the GUI thread\n"
    "\n"
    "options:\n"
    "  --photo FILE         use this photo instead of a synthetic 6000x4000 one\n"
    "  --edits N            latency mode: number of edits (default 40, at least 3)\n"
    "  --strength S         the lens's radial term at the frame corner (default 0.12)\n"
    "  --pairs N            drag mode: number of pairs (default 300, at least 10)\n"
    "  --moves N            drag mode: number of mouse-move events (default 120, at least 5)\n"
    "  --fit-on-gui-thread  drag mode: fit every move on the GUI thread (the old behaviour),\n"
    "                       for comparison\n"
    "  --export PROJECT -o OUT  the studio's export of PROJECT to OUT (Session::exportImage),\n"
    "                       timed from the call to its outcome (studio_export_ms), to set\n"
    "                       beside `artcam export PROJECT -o OUT`\n"
    "  --help               this text\n";

struct Options {
  bool drag = false;
  std::string photo_path;
  int edits = 40;
  double strength = 0.12;
  int pairs = 300;
  int moves = 120;
  bool fit_on_gui = false;
  std::string export_project;  // --export PROJECT -o OUT
  std::string export_output;
};

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

// Runs the GUI thread's event loop until done() holds or timeout_ms pass; false on the
// timeout. It sleeps between events as the studio's own loop does: processEvents with a
// time limit returns at once when nothing is pending, so polling it would keep one of the
// machine's cores spinning, away from the render's threads, and time the spin too.
bool waitUntil(const std::function<bool()>& done, int timeout_ms) {
  QElapsedTimer t;
  t.start();
  QTimer deadline;  // its timeout is an event: it wakes the wait
  deadline.setSingleShot(true);
  while (!done()) {
    const qint64 left = timeout_ms - t.elapsed();
    if (left <= 0) return false;
    deadline.start(static_cast<int>(left));
    QCoreApplication::processEvents(QEventLoop::WaitForMoreEvents);
  }
  return true;
}

bool waitForFinal(const PreviewController& c, int timeout_ms) {
  return waitUntil(
      [&c] {
        return c.imageIsFinal() && c.imageGeneration() == c.requestedGeneration() &&
               !c.image().isNull();
      },
      timeout_ms);
}

double percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<size_t>(q * static_cast<double>(v.size())))];
}

// CPU time this thread has used (not wall time): separates the GUI thread's own work from the
// time other threads and processes keep it off the CPU.
double threadCpuMs() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) * 1e3 + static_cast<double>(t.tv_nsec) / 1e6;
}

double msSince(const QElapsedTimer& clock, qint64 start_ns) {
  return static_cast<double>(clock.nsecsElapsed() - start_ns) / 1e6;
}

// A source point and its image under a mild rational lens about the centre (the quadratic
// model fits it exactly).
Pair lensPair(const Eigen::Vector2d& s, FrameSize size, double strength) {
  const Eigen::Vector2d c(0.5 * size.width, 0.5 * size.height);
  const Eigen::Vector2d d = (s - c) / c.norm();
  return {s, c + (s - c) / (1.0 + strength * d.squaredNorm()), true};
}

struct LoadedPhoto {
  PhotoPtr photo;
  double decode_ms = 0.0;
  double prepare_ms = 0.0;
};

std::optional<LoadedPhoto> loadPhoto(const std::string& path) {
  QElapsedTimer clock;
  clock.start();
  LoadedImage loaded;
  if (path.empty()) {
    loaded = syntheticPhoto(6000, 4000);
  } else {
    auto r = readImage(path);
    if (!r) {
      std::fprintf(stderr, "%s\n", r.status.message.c_str());
      return std::nullopt;
    }
    loaded = std::move(*r);
  }
  LoadedPhoto out;
  out.decode_ms = static_cast<double>(clock.restart());
  out.photo = makePhoto(QString::fromStdString(path), std::move(loaded));
  out.prepare_ms = static_cast<double>(clock.restart());
  return out;
}

std::vector<Pair> latencyPairs(FrameSize size, double strength) {
  std::vector<Pair> pairs;
  for (int k = 0; k < 10; ++k) {
    // Offsets are shares of the frame, so every pair stays inside a photo of any size.
    const Eigen::Vector2d s(size.width * (0.15 + 0.7 * (k % 4) / 3.0),
                            size.height * (0.15 + 0.7 * (k / 4) / 2.0 + 0.00925 * k));
    pairs.push_back(lensPair(s, size, strength));
  }
  return pairs;
}

// One full libjpeg decode of the file (JpegDecoder at scale 1 into 8-bit rows, djpeg's own
// loop): the yardstick for opening. Negative when the codec path does not take the file.
double djpegMs(const std::string& path) {
  QElapsedTimer clock;
  clock.start();
  auto decoder = JpegDecoder::open(path);
  if (!decoder || !(*decoder.value)->supported()) return -1.0;
  JpegDecoder& d = **decoder.value;
  const size_t row = static_cast<size_t>(d.width()) * static_cast<size_t>(d.channels());
  std::vector<std::uint8_t> pixels(row * static_cast<size_t>(d.height()));
  if (!d.decode(pixels.data(), row)) return -1.0;
  return static_cast<double>(clock.nsecsElapsed()) / 1e6;
}

// Opening as the studio opens a photo (Session: ImageLoader with the first look,
// Document::reset, then Document::refinePhoto), timed from the open: the first preview shown
// (any pass), its final pass, and the full photo swapped in.
struct StudioOpen {
  int reduced_by = 1;
  double delivered_ms = -1.0;  // the first photo (look or whole) handed to the document
  double first_preview_ms = -1.0;
  double first_final_preview_ms = -1.0;
  double full_photo_ms = -1.0;
};

std::optional<StudioOpen> openAsStudio(const std::string& path, double strength, Document& doc,
                                       const PreviewController& controller) {
  StudioOpen out;
  bool failed = false, refined = false;
  ImageLoader loader(QString::fromStdString(path));
  loader.setFirstLook(true);
  // As MainWindow does: the whole read waits for the first look's preview.
  loader.setHoldWholeRead(true);
  QObject::connect(&controller, &PreviewController::previewChanged, &loader, [&] {
    if (controller.imageIsFinal()) loader.releaseWholeRead();
  });
  QElapsedTimer clock;
  QObject::connect(&loader, &ImageLoader::loaded, [&](const PhotoPtr& photo) {
    out.reduced_by = photo->reduced_by;
    out.delivered_ms = static_cast<double>(clock.nsecsElapsed()) / 1e6;
    doc.reset(photo, latencyPairs(photo->size(), strength), ModelClass::Quadratic);
    if (photo->hasFullImage()) {
      refined = true;
      out.full_photo_ms = static_cast<double>(clock.nsecsElapsed()) / 1e6;
    }
  });
  QObject::connect(&loader, &ImageLoader::refined, [&](const PhotoPtr& photo) {
    doc.refinePhoto(photo);
    refined = true;
    out.full_photo_ms = static_cast<double>(clock.nsecsElapsed()) / 1e6;
  });
  const auto fail = [&failed](const QString& message) {
    std::fprintf(stderr, "%s\n", qPrintable(message));
    failed = true;
  };
  QObject::connect(&loader, &ImageLoader::failed, fail);
  QObject::connect(&loader, &ImageLoader::refineFailed, fail);
  clock.start();
  loader.start();
  // The preview's arrivals are stamped where they happen, not when a wait next looks.
  QObject::connect(&controller, &PreviewController::previewChanged, &loader, [&] {
    if (controller.image().isNull()) return;
    const double now_ms = static_cast<double>(clock.nsecsElapsed()) / 1e6;
    if (out.first_preview_ms < 0.0) out.first_preview_ms = now_ms;
    if (out.first_final_preview_ms < 0.0 && controller.imageIsFinal())
      out.first_final_preview_ms = now_ms;
  });
  waitUntil([&] { return failed || (refined && out.first_final_preview_ms >= 0.0); }, 60000);
  if (failed || !refined || out.first_final_preview_ms < 0.0) {
    if (!failed) std::fprintf(stderr, "the photo or its first preview did not arrive\n");
    return std::nullopt;
  }
  // The preview of the full photo, before the edits are timed.
  if (!waitForFinal(controller, 60000)) {
    std::fprintf(stderr, "the preview of the full photo did not arrive\n");
    return std::nullopt;
  }
  return out;
}

int runEdits(const Options& o, Document& doc, const PreviewController& controller) {
  QElapsedTimer clock;
  clock.start();
  std::vector<double> latency_ms, render_ms;
  for (int e = 0; e < o.edits; ++e) {
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
  std::printf(
      "edits=%d\nedit_to_preview_ms_median=%.1f\nedit_to_preview_ms_min=%.1f\n"
      "edit_to_preview_ms_p90=%.1f\nfinal_pass_render_ms_median=%.1f\n",
      o.edits, percentile(latency_ms, 0.5), percentile(latency_ms, 0.0),
      percentile(latency_ms, 0.9), percentile(render_ms, 0.5));
  return 0;
}

// A photo file: opened as the studio opens it (first look, then the full photo); then, apart,
// the whole read and the copies (decode_ms, prepare_ms) and one libjpeg decode (djpeg_ms), so
// the figures sit side by side; then the edits.
int runLatencyFile(const Options& o) {
  Document doc;
  PreviewController controller(&doc);
  const std::optional<StudioOpen> opened = openAsStudio(o.photo_path, o.strength, doc, controller);
  if (!opened) return 1;
  const std::optional<LoadedPhoto> whole = loadPhoto(o.photo_path);
  if (!whole) return 1;
  const double djpeg_ms = djpegMs(o.photo_path);
  // The first look's two stages on this thread: its read, then its copies.
  QElapsedTimer clock;
  clock.start();
  auto look = readFirstLook(o.photo_path, kLivePreviewMaxWidth, kLivePreviewMaxHeight);
  const double look_read_ms = static_cast<double>(clock.nsecsElapsed()) / 1e6;
  clock.restart();
  if (look && *look) makeFirstLookPhoto(QString(), std::move(**look));
  const double look_prepare_ms = static_cast<double>(clock.nsecsElapsed()) / 1e6;
  const FrameSize size = doc.photo()->size();
  const FrameSize preview = livePreviewSize(*doc.photo());
  std::printf("mode=latency\n");
  std::printf("lens_strength=%.3g\n", o.strength);
  std::printf("photo=%dx%d\npreview=%dx%d\n", size.width, size.height, preview.width,
              preview.height);
  // The whole read (readImage) and its copies (makePhoto) timed apart; libjpeg's decode alone.
  std::printf("decode_ms=%.0f\nprepare_ms=%.0f\ndjpeg_ms=%.0f\n", whole->decode_ms,
              whole->prepare_ms, djpeg_ms);
  // From the open: the first look handed to the document (first_look_delivered_ms), its
  // preview shown (any pass, then its final pass), then the full photo swapped in.
  // first_look_reduced_by 1: the file was read whole (no first look).
  std::printf("first_look_reduced_by=%d\nfirst_look_read_ms=%.0f\nfirst_look_prepare_ms=%.0f\n"
              "first_look_delivered_ms=%.0f\n",
              opened->reduced_by, look_read_ms, look_prepare_ms, opened->delivered_ms);
  std::printf("first_preview_ms=%.0f\nfirst_final_preview_ms=%.0f\nfull_photo_ms=%.0f\n",
              opened->first_preview_ms, opened->first_final_preview_ms, opened->full_photo_ms);
  return runEdits(o, doc, controller);
}

int runLatency(const Options& o) {
  if (!o.photo_path.empty()) return runLatencyFile(o);
  // The synthetic photo: made in memory (decode_ms), its copies built (prepare_ms).
  const std::optional<LoadedPhoto> loaded = loadPhoto(o.photo_path);
  if (!loaded) return 1;
  const PhotoPtr& photo = loaded->photo;
  const FrameSize size = photo->size();
  const FrameSize preview = livePreviewSize(*photo);
  Document doc;
  PreviewController controller(&doc);
  QElapsedTimer clock;
  clock.start();
  doc.reset(photo, latencyPairs(size, o.strength), ModelClass::Quadratic);
  // The first picture of any quality, then the final one, both counted from the made photo.
  double first_any_ms = -1.0;
  waitUntil([&controller] { return !controller.image().isNull(); }, 60000);
  if (!controller.image().isNull()) first_any_ms = static_cast<double>(clock.nsecsElapsed()) / 1e6;
  if (!waitForFinal(controller, 60000)) {
    std::fprintf(stderr, "the first preview did not arrive\n");
    return 1;
  }
  const double first_final_ms = static_cast<double>(clock.nsecsElapsed()) / 1e6;
  std::printf("mode=latency\n");
  std::printf("lens_strength=%.3g\n", o.strength);
  std::printf("photo=%dx%d\ndecode_ms=%.0f\nprepare_ms=%.0f\npreview=%dx%d\n", size.width,
              size.height, loaded->decode_ms, loaded->prepare_ms, preview.width, preview.height);
  std::printf("first_preview_ms=%.0f\nfirst_final_preview_ms=%.0f\n",
              loaded->decode_ms + loaded->prepare_ms + first_any_ms,
              loaded->decode_ms + loaded->prepare_ms + first_final_ms);
  return runEdits(o, doc, controller);
}

void sendMouse(QWidget* w, QEvent::Type type, const QPointF& pos, Qt::MouseButton button,
               Qt::MouseButtons buttons) {
  QMouseEvent event(type, pos, w->mapToGlobal(pos), button, buttons, Qt::NoModifier);
  QCoreApplication::sendEvent(w, &event);
}

int runDrag(const Options& o) {
  QStandardPaths::setTestModeEnabled(true);  // no autosave or settings in the user's folders
  const std::optional<LoadedPhoto> loaded = loadPhoto(o.photo_path);
  if (!loaded) return 1;
  const PhotoPtr& photo = loaded->photo;
  const FrameSize size = photo->size();
  // A grid of pairs over the frame, each a little off the grid so no two are collinear rows.
  const int cols = std::max(2, static_cast<int>(std::lround(std::sqrt(o.pairs * 1.5))));
  std::vector<Pair> pairs;
  for (int k = 0; k < o.pairs; ++k) {
    const double fx = 0.04 + 0.92 * (k % cols) / (cols - 1.0);
    const double fy = 0.04 + 0.92 * (k / cols) / std::max(1.0, (o.pairs - 1) / cols * 1.0);
    const Eigen::Vector2d s(size.width * (fx + 0.0012 * (k % 5)),
                            size.height * (fy + 0.00125 * (k % 3)));
    pairs.push_back(lensPair(s, size, o.strength));
  }

  MainWindow window;
  window.session()->setInteractive(false);
  window.show();
  Document* doc = window.document();
  doc->setFitsInWorker(!o.fit_on_gui);
  PreviewController* controller = window.preview();
  Canvas* canvas = window.canvas();
  doc->reset(photo, pairs, ModelClass::Auto);
  if (!waitForFinal(*controller, 60000)) {
    std::fprintf(stderr, "the first preview did not arrive\n");
    return 1;
  }
  // The grabbed pair: the one whose target is farthest from its own source (a corner), so the
  // press cannot land on its source; checked after the drag anyway.
  size_t grabbed = 0;
  for (size_t k = 0; k < pairs.size(); ++k)
    if ((pairs[k].target - pairs[k].source).norm() >
        (pairs[grabbed].target - pairs[grabbed].source).norm())
      grabbed = k;
  const Pair before = doc->pairs()[grabbed];
  const QPointF start =
      canvas->view().widgetFromImage(QPointF(before.target.x(), before.target.y()));
  const QPointF centre(canvas->width() / 2.0, canvas->height() / 2.0);
  const QPointF toward =
      (centre - start) / std::hypot(centre.x() - start.x(), centre.y() - start.y());

  QElapsedTimer clock;
  clock.start();
  // Each camera delivery: which document edit revision the preview request it makes shows.
  std::map<quint64, quint64> revision_of_generation;
  QObject::connect(doc, &Document::cameraChanged, controller, [&] {
    revision_of_generation[controller->requestedGeneration()] = doc->cameraRevision();
  });
  struct Move {
    quint64 revision = 0;
    qint64 at_ns = 0;
    double latency_ms = -1.0;
  };
  std::vector<Move> moves;
  QObject::connect(controller, &PreviewController::previewChanged, controller, [&] {
    if (!controller->imageIsFinal()) return;
    const auto it = revision_of_generation.find(controller->imageGeneration());
    if (it == revision_of_generation.end()) return;
    for (Move& m : moves)
      if (m.latency_ms < 0.0 && m.revision <= it->second) m.latency_ms = msSince(clock, m.at_ns);
  });

  std::vector<qint64> beats;
  beats.reserve(100000);
  QTimer heartbeat;
  heartbeat.setTimerType(Qt::PreciseTimer);
  heartbeat.setInterval(1);
  QObject::connect(&heartbeat, &QTimer::timeout, [&] { beats.push_back(clock.nsecsElapsed()); });

  const FitThreadCounts fits_before = fitThreadCounts();
  std::vector<double> handler_ms;
  QEventLoop loop;
  QTimer mouse;
  mouse.setTimerType(Qt::PreciseTimer);
  mouse.setInterval(8);
  int step = 0;
  QObject::connect(&mouse, &QTimer::timeout, [&] {
    if (step == 0) {
      sendMouse(canvas, QEvent::MouseButtonPress, start, Qt::LeftButton, Qt::LeftButton);
    } else if (step <= o.moves) {
      // Along the line toward the centre, then a little sideways: 2 widget px per move.
      const QPointF p =
          start + toward * (2.0 * step) + QPointF(toward.y(), -toward.x()) * (step % 7);
      const qint64 t0 = clock.nsecsElapsed();
      sendMouse(canvas, QEvent::MouseMove, p, Qt::NoButton, Qt::LeftButton);
      handler_ms.push_back(msSince(clock, t0));
      moves.push_back({doc->editRevision(), t0, -1.0});
    } else {
      mouse.stop();
      loop.quit();
    }
    ++step;
  });
  const double cpu_start_ms = threadCpuMs();
  const qint64 drag_start_ns = clock.nsecsElapsed();
  heartbeat.start();
  mouse.start();
  loop.exec();
  const qint64 drag_end_ns = clock.nsecsElapsed();
  const double gui_cpu_ms = threadCpuMs() - cpu_start_ms;
  const double drag_wall_ms = static_cast<double>(drag_end_ns - drag_start_ns) / 1e6;
  const QPointF end =
      start + toward * (2.0 * o.moves) + QPointF(toward.y(), -toward.x()) * (o.moves % 7);
  sendMouse(canvas, QEvent::MouseButtonRelease, end, Qt::LeftButton, Qt::NoButton);
  // Until the last edit's preview is shown.
  waitUntil(
      [&] {
        return !doc->fitPending() && controller->imageIsFinal() &&
               controller->imageGeneration() == controller->requestedGeneration();
      },
      60000);
  const double settle_ms = msSince(clock, drag_end_ns);
  heartbeat.stop();
  const FitThreadCounts fits_after = fitThreadCounts();

  if ((doc->pairs()[grabbed].target - before.target).norm() < 1.0) {
    std::fprintf(stderr, "the drag did not move the grabbed target point\n");
    return 1;
  }
  // Event-loop stalls: heartbeat gaps beyond the timer's own 1 ms, during the drag only.
  std::vector<double> stall_ms;
  for (size_t i = 1; i < beats.size(); ++i)
    if (beats[i] <= drag_end_ns)
      stall_ms.push_back(std::max(0.0, static_cast<double>(beats[i] - beats[i - 1]) / 1e6 - 1.0));
  std::vector<double> latency_ms;
  int unanswered = 0;
  for (const Move& m : moves) {
    if (m.latency_ms >= 0.0)
      latency_ms.push_back(m.latency_ms);
    else
      ++unanswered;
  }
  std::printf("mode=drag\n");
  std::printf("fits=%s\n", o.fit_on_gui ? "gui_thread" : "worker");
  std::printf("photo=%dx%d\npairs=%d\nmodel=%s\n", size.width, size.height, o.pairs,
              doc->fit().record.model.c_str());
  std::printf("moves=%d\nmove_interval_ms=8\n", o.moves);
  std::printf(
      "move_event_gui_ms_median=%.2f\nmove_event_gui_ms_p90=%.2f\nmove_event_gui_ms_max=%.2f\n",
      percentile(handler_ms, 0.5), percentile(handler_ms, 0.9), percentile(handler_ms, 1.0));
  std::printf(
      "event_loop_stall_ms_median=%.2f\nevent_loop_stall_ms_p99=%.2f\n"
      "event_loop_stall_ms_max=%.2f\n",
      percentile(stall_ms, 0.5), percentile(stall_ms, 0.99), percentile(stall_ms, 1.0));
  std::printf(
      "edit_to_preview_ms_median=%.1f\nedit_to_preview_ms_p90=%.1f\n"
      "edit_to_preview_ms_max=%.1f\nmoves_without_preview_during_drag=%d\n",
      percentile(latency_ms, 0.5), percentile(latency_ms, 0.9), percentile(latency_ms, 1.0),
      unanswered);
  std::printf("drag_wall_ms=%.0f\ngui_thread_cpu_ms=%.0f\ngui_thread_cpu_ms_per_move=%.2f\n",
              drag_wall_ms, gui_cpu_ms, gui_cpu_ms / o.moves);
  std::printf("release_to_final_preview_ms=%.1f\n", settle_ms);
  std::printf("fits_on_gui_thread=%ld\nfits_on_worker=%ld\n",
              fits_after.gui_thread - fits_before.gui_thread,
              fits_after.other_threads - fits_before.other_threads);
  return 0;
}

// The studio's export of a project (Session::exportImage, the ExportJob), timed from the call
// to its outcome, the project opened as the studio opens it and its full photo in first. The
// figure to set beside `artcam export PROJECT -o OUT` (which also reads the photo: see
// export_read_ms, the studio's whole read of it, for that share).
int runExport(const Options& o) {
  QStandardPaths::setTestModeEnabled(true);  // no autosave or settings in the user's folders
  Document doc;
  Session session(&doc, nullptr);
  session.setInteractive(false);
  QElapsedTimer clock;
  clock.start();
  session.openPath(QString::fromStdString(o.export_project));
  waitUntil([&doc] { return doc.photo() && doc.photo()->hasFullImage(); }, 120000);
  if (!doc.photo() || !doc.photo()->hasFullImage()) {
    std::fprintf(stderr, "the project's photo did not arrive\n");
    return 1;
  }
  const double open_ms = static_cast<double>(clock.nsecsElapsed()) / 1e6;
  QFile::remove(QString::fromStdString(o.export_output));
  bool done = false, ok = false;
  QString message;
  QObject::connect(&session, &Session::exportFinished, [&](bool success, const QString& m) {
    done = true;
    ok = success;
    message = m;
  });
  clock.restart();
  session.exportImage(QString::fromStdString(o.export_output));
  waitUntil([&done] { return done; }, 600000);
  const double export_ms = static_cast<double>(clock.nsecsElapsed()) / 1e6;
  if (!ok) {
    std::fprintf(stderr, "%s\n", done ? qPrintable(message) : "the export did not finish");
    return 1;
  }
  clock.restart();
  const auto read = readImage(doc.photo()->path.toStdString());
  const double read_ms = static_cast<double>(clock.nsecsElapsed()) / 1e6;
  std::printf("mode=export\nphoto=%dx%d\nopen_to_full_photo_ms=%.0f\n", doc.photo()->size().width,
              doc.photo()->size().height, open_ms);
  std::printf("studio_export_ms=%.0f\nexport_read_ms=%.0f\n", export_ms, read ? read_ms : -1.0);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const bool has_value = i + 1 < argc;
    if (std::strcmp(argv[i], "--help") == 0 || std::strcmp(argv[i], "-h") == 0) {
      std::fputs(kUsage, stdout);
      return 0;
    }
    if (std::strcmp(argv[i], "--drag") == 0)
      o.drag = true;
    else if (std::strcmp(argv[i], "--fit-on-gui-thread") == 0)
      o.fit_on_gui = true;
    else if (std::strcmp(argv[i], "--export") == 0 && i + 2 < argc &&
             std::strcmp(argv[i + 2], "-o") == 0 && i + 3 < argc) {
      o.export_project = argv[i + 1];
      o.export_output = argv[i + 3];
      i += 3;
    } else if (std::strcmp(argv[i], "--photo") == 0 && has_value)
      o.photo_path = argv[++i];
    else if (std::strcmp(argv[i], "--edits") == 0 && has_value)
      o.edits = std::max(3, std::atoi(argv[++i]));
    else if (std::strcmp(argv[i], "--strength") == 0 && has_value)
      o.strength = std::atof(argv[++i]);
    else if (std::strcmp(argv[i], "--pairs") == 0 && has_value)
      o.pairs = std::max(10, std::atoi(argv[++i]));
    else if (std::strcmp(argv[i], "--moves") == 0 && has_value)
      o.moves = std::max(5, std::atoi(argv[++i]));
    else {
      std::fprintf(stderr,
                   "artcam-studio-bench: unknown option or missing value: %s\n"
                   "see artcam-studio-bench --help\n",
                   argv[i]);
      return 2;
    }
  }
  if (qEnvironmentVariableIsEmpty("QT_QPA_PLATFORM")) qputenv("QT_QPA_PLATFORM", "offscreen");
  QApplication app(argc, argv);
  if (!o.export_project.empty()) return runExport(o);
  return o.drag ? runDrag(o) : runLatency(o);
}
