// SPDX-License-Identifier: Apache-2.0
// artcam bench render: speed and position error of every render kernel and filter.
// A benchmark, not a test: figures are medians of repeated renders on a photo-sized image made
// in code; the error is the distance (source pixels) between the fused kernel's source
// positions and an exact double-precision inverse (coordinates.h, makeReferenceInverse).
#include "app/cli/args.h"
#include "app/cli/bench_suite.h"
#include "app/cli/commands.h"
#include "app/cli/memory.h"
#include "app/cli/outputs.h"
#include "core/io/artcam_file.h"
#include "core/io/image_io.h"
#include "core/io/stored_image.h"
#include "core/model/frames.h"
#include "core/model/structure.h"
#include "core/piecewise/piecewise_render.h"
#include "core/pipeline/render.h"
#include "core/mapping/coordinates.h"
#include "core/render/preview.h"
#include "core/model/pixel_buffer.h"
#include "core/render/warp.h"

#include <sys/resource.h>
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <optional>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace artcam::cli {

const char* const kBenchUsage =
    "usage: artcam bench render [--size WxH] [--reps N] [--threads LIST] [--plot OUT.png]\n"
    "                           [--peer DIR] [--only KERNEL,…] [--no-suite] [--no-e2e]\n"
    "                           [--overwrite]\n"
    "       artcam bench render --cameras CAM.artcam [CAM.artcam …] [--size WxH] …\n"
    "       artcam bench fit [--counts LIST] [--noise LIST] [--seconds S] [--methods LIST]\n"
    "                        [--plot OUT.png] [--colour] [--overwrite]\n"
    "       artcam bench effects …   (artcam bench effects --help)\n\n"
    "bench render times the fused warp on a WxH RGB8 image made in code: each kernel\n"
    "(identity, translation-copy, affine, homography, rational, rational-scalar without the\n"
    "SIMD clone, and a minifying homography with anti-aliasing) with each filter, on each\n"
    "thread count, as the median of N renders. Prints CSV on stdout:\n"
    "  source,kernel,filter,threads,ms,mpix_per_s,max_err_px,rms_err_px,newton_share,\n"
    "  certified_share,cpu_ms\n"
    "where cpu_ms is the process CPU time of the median render (all threads; on a loaded\n"
    "shared machine it stays near the unloaded wall time × threads while ms grows), and the\n"
    "error is the distance of the kernel's source positions from an exact double-precision\n"
    "inverse on a sample of rows, where the exact preimage lies within 2 px of the source\n"
    "frame (beyond, the output is transparent whatever the position). A memcpy row\n"
    "(source \"memcpy\") gives the copy ceiling.\n"
    "Then the camera suite (source \"suite\"), bilinear, through the render front door:\n"
    "the homography (the yardstick), quadratic fits of a compact zoom's, a wide angle's and\n"
    "a fisheye's radial distortion, every image preset at its default and a strong setting\n"
    "(barrel-strong leaves the corners without a preimage), and the fisheye as a piecewise\n"
    "camera; stderr gives each camera's time as a multiple of the homography's: the median\n"
    "of N ratios, each against a homography render made just before (a machine's speed\n"
    "drifts; pairs taken side by side cancel it).\n"
    "  --size WxH       image size (default 6000x4000)\n"
    "  --reps N         renders per row, the median is reported (default 5)\n"
    "  --threads LIST   comma-separated thread counts (default 1,2)\n"
    "  --plot OUT.png   a PNG of speed (x, log) against error (y, log), one colour per kernel\n"
    "  --overwrite      replace an existing OUT.png (--force is the same; bench fit too)\n"
    "  --peer DIR       also run DIR/cvwarp (the OpenCV maps + remap peer) on the same image,\n"
    "                   then five rounds of the rational kernel's bilinear render and the\n"
    "                   peer's in turn (median of 3 each): stderr gives the median of the\n"
    "                   five ratios per thread count (a machine's speed drifts; pairs cancel it;\n"
    "                   the peer times all its filters and map loops: minutes, not seconds)\n"
    "  --cameras FILE…  time these .artcam files (after the homography yardstick) instead of\n"
    "                   the kernel rows and the suite, e.g. lenses from `artcam lens camera`\n"
    "  --no-suite       skip the camera suite\n"
    "  --only LIST      run only the named kernels (default: all)\n"
    "  --filter LIST    run only the named filters: nearest,bilinear,bicubic (default: all)\n"
    "  --type TYPE      the kernel rows' pixels: uint8 (default), uint16 or float, the same\n"
    "                   image scaled to full range; the kernel names get -uint16 or -float\n"
    "                   (the suite, the peer and the e2e line stay 8-bit)\n"
    "  --no-e2e         skip the last part: `artcam warp`'s path on a JPEG of the image\n"
    "                   (decode into 8-bit, render, encode) timed by part, and the 1920-px\n"
    "                   preview from the mip pyramid, on stderr\n\n"
    "bench fit times every fitting method (raw DLT, conditioned DLT, + refine, + robust,\n"
    "auto) against its error over match counts and noise levels; CSV on stdout\n"
    "(method,matches,noise_px,median_us,median_cpu_us,reps,rms_err_px,max_err_px).\n"
    "  --counts LIST    match counts (default 9,30,100,1000,10000,100000)\n"
    "  --noise LIST     Gaussian noise on the targets, px (default 0,0.5,2)\n"
    "  --seconds S      time budget per row; at least 3, at most 200 fits (default 0.3)\n"
    "  --methods LIST   raw-dlt,dlt,refine,robust,auto (default: all five)\n"
    "  --plot OUT.png   a PNG of time against error, one colour per method\n"
    "  --colour         then time the colour-block fit (auto and robust auto) on 24, 100\n"
    "                   and 1000 samples and report its mean and max dE00\n\n"
    "Examples:\n"
    "  artcam bench render --size 3000x2000 --threads 1,2 --plot speed.png\n"
    "  artcam bench fit --counts 9,100 --methods dlt,auto\n";

namespace {

struct Case {
  std::string name;
  Camera camera;
  bool antialias = false;
  bool scalar_only = false;  // the portable code where a SIMD clone exists
};

// A photo-like RGB8 image: smooth gradients, edges and hash noise, made in code.
PixelBuffer makeImage(int w, int h) {
  PixelBuffer img(static_cast<size_t>(w) * static_cast<size_t>(h) * 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      std::uint32_t n = static_cast<std::uint32_t>(x) * 73856093u ^ static_cast<std::uint32_t>(y) * 19349663u;
      n = (n ^ (n >> 13)) * 0x5bd1e995u;
      const int noise = static_cast<int>(n >> 28) - 8;
      std::uint8_t* p = img.data() + (static_cast<size_t>(y) * static_cast<size_t>(w) + static_cast<size_t>(x)) * 3;
      const bool check = ((x / 97) + (y / 89)) % 2 == 0;
      p[0] = static_cast<std::uint8_t>(std::clamp(40 + 160 * x / w + noise, 0, 255));
      p[1] = static_cast<std::uint8_t>(std::clamp(40 + 160 * y / h + noise, 0, 255));
      p[2] = static_cast<std::uint8_t>(std::clamp((check ? 200 : 50) + noise, 0, 255));
    }
  return img;
}

Camera homography(const Eigen::Matrix3d& h, FrameSize size) {
  Stage stage;
  for (const Eigen::MatrixXd& q : liftHomography(h)) stage.q.push_back(q);
  return Camera({Block{BlockKind::Position, 3}}, {stage}, size, size);
}

std::vector<Case> makeCases(FrameSize size) {
  std::vector<Case> cases;
  const Eigen::Matrix3d id = Eigen::Matrix3d::Identity();
  cases.push_back({"identity", Camera::identity({Block{BlockKind::Position, 3}}, size, size), false});
  Eigen::Matrix3d t = id;
  const double s = std::max(size.width, size.height) / 2.0;  // normalised frame scale (frames.h)
  t(0, 2) = 3.0 / s;
  t(1, 2) = -2.0 / s;
  cases.push_back({"translation-copy", homography(t, size), false});
  Eigen::Matrix3d a = id;
  a << 1.02, 0.05, 0.01, -0.04, 0.99, -0.02, 0, 0, 1;
  cases.push_back({"affine", homography(a, size), false});
  Eigen::Matrix3d h = a;
  h(2, 0) = 0.03;
  h(2, 1) = -0.02;
  cases.push_back({"homography", homography(h, size), false});
  // The peer's mild lens-like map (peerbench/common.hpp default_map) as our forward camera.
  const double p[3][6] = {{0.030, 0.020, 1.000, -0.010, 0.010, 0.005},
                          {0.010, -0.020, 0.015, 0.030, 0.980, -0.004},
                          {0.020, 0.010, 0.040, -0.020, -0.030, 1.000}};
  std::vector<Eigen::Matrix3d> q(3);
  for (int k = 0; k < 3; ++k)
    q[static_cast<size_t>(k)] << p[k][0], p[k][1] / 2, p[k][2] / 2, p[k][1] / 2, p[k][3],
        p[k][4] / 2, p[k][2] / 2, p[k][4] / 2, p[k][5];
  cases.push_back({"rational", Camera::rtcam(q, size, size), false});
  cases.push_back({"rational-scalar", Camera::rtcam(q, size, size), false, true});
  Eigen::Matrix3d m = id;
  m(0, 0) = m(1, 1) = 2.5;  // the target shows the source at 1/2.5 scale
  m(2, 0) = 0.1;
  cases.push_back({"homography-minify", homography(m, size), true});
  return cases;
}

struct PositionError {
  double max = 0.0, rms = 0.0;
  long long validity_mismatch = 0;
};

PositionError measureError(const Camera& camera, FrameSize size) {
  const CameraStructure structure = analyseStructure(camera);
  const KernelChoice choice = makeCoordinateKernel(camera, structure, size, size, {});
  const auto reference = makeReferenceInverse(camera, structure, size, size);
  PositionError e;
  double sum = 0.0;
  long long count = 0;
  std::vector<Eigen::Vector2d> exact(static_cast<size_t>(size.width));
  std::vector<unsigned char> exact_valid(static_cast<size_t>(size.width));
  float sx[kSpanPixels], sy[kSpanPixels];
  unsigned char valid[kSpanPixels];
  const int step = std::max(1, size.height / 60);
  for (int y = step / 2; y < size.height; y += step) {
    reference->row(y, size.width, exact.data(), exact_valid.data());
    RowState row_state;
    for (int x0 = 0; x0 < size.width; x0 += kSpanPixels) {
      const int n = std::min(kSpanPixels, size.width - x0);
      choice.kernel->span(y, x0, n, sx, sy, valid, row_state);
      for (int i = 0; i < n; ++i) {
        const size_t k = static_cast<size_t>(x0 + i);
        // Only where the output can show it: an exact preimage within bicubic's reach (2 px)
        // of the source frame. Beyond, the pixel is transparent whatever position the kernel
        // gives it, or whether it gives one (inverse_cells.h: empty cells).
        if (exact_valid[k] && (exact[k].x() < -2.0 || exact[k].y() < -2.0 || exact[k].x() > size.width + 2.0 ||
                               exact[k].y() > size.height + 2.0))
          continue;
        if ((valid[i] != 0) != (exact_valid[k] != 0)) ++e.validity_mismatch;
        if (!valid[i] || !exact_valid[k]) continue;
        const double d = std::hypot(sx[i] - exact[k].x(), sy[i] - exact[k].y());
        e.max = std::max(e.max, d);
        sum += d * d;
        ++count;
      }
    }
  }
  e.rms = count ? std::sqrt(sum / count) : 0.0;
  return e;
}

struct Row {
  std::string source, kernel, filter;
  int threads = 1;
  double ms = 0, mpix = 0, max_err = -1, rms_err = -1, newton_share = 0, certified_share = 0, cpu_ms = -1;
};

void printRow(const Row& r) {
  const auto num = [](double v) { return v < 0 ? std::string() : std::to_string(v); };
  std::printf("%s,%s,%s,%d,%.2f,%.1f,%s,%s,%.4f,%.4f,%s\n", r.source.c_str(), r.kernel.c_str(),
              r.filter.c_str(), r.threads, r.ms, r.mpix, num(r.max_err).c_str(),
              num(r.rms_err).c_str(), r.newton_share, r.certified_share, num(r.cpu_ms).c_str());
  std::fflush(stdout);
}

// OpenCV peer rows from peerbench's cvwarp (its report format: name, threads, ms, Mpix/s).
std::vector<Row> runPeer(const std::string& dir, const PixelBuffer& img, FrameSize size,
                         int reps) {
  std::vector<Row> rows;
  const std::string exe = dir + "/cvwarp";
  if (!std::filesystem::exists(exe)) {
    std::fprintf(stderr, "bench: no %s, peer skipped\n", exe.c_str());
    return rows;
  }
  const std::filesystem::path ppm = std::filesystem::temp_directory_path() / "artcam-bench-peer.ppm";
  if (FILE* f = std::fopen(ppm.c_str(), "wb")) {
    std::fprintf(f, "P6\n%d %d\n255\n", size.width, size.height);
    std::fwrite(img.data(), 1, img.size(), f);
    std::fclose(f);
  }
  // cvwarp also writes img/cv_linear.ppm relative to its working directory: run it in /tmp.
  std::filesystem::create_directories(std::filesystem::temp_directory_path() / "img");
  const std::string cmd = "cd " + std::filesystem::temp_directory_path().string() + " && " + exe +
                          " " + ppm.string() + " " + std::to_string(reps) + " 2>/dev/null";
  FILE* pipe = popen(cmd.c_str(), "r");
  if (!pipe) return rows;
  std::map<std::pair<std::string, int>, double> ms;
  char line[512];
  while (std::fgets(line, sizeof line, pipe)) {
    // Lines end in "<threads> <ms> <Mpix/s>"; the name is the words before.
    std::vector<std::string> words;
    for (char* tok = std::strtok(line, " \t\n"); tok; tok = std::strtok(nullptr, " \t\n"))
      words.emplace_back(tok);
    if (words.size() < 4) continue;
    const auto threads = readInteger(words[words.size() - 3]);
    const auto t = readNumber(words[words.size() - 2]);
    if (!threads || !t || *threads < 1 || *threads > kMaxThreads) continue;  // not a timing line
    const int thr = static_cast<int>(*threads);
    std::string name;
    for (size_t i = 0; i + 3 < words.size(); ++i) name += (i ? " " : "") + words[i];
    ms[{name, thr}] = *t;
  }
  pclose(pipe);
  const double mpix = size.width * static_cast<double>(size.height) / 1e6;
  for (int thr = 1; thr <= 2; ++thr) {
    const auto get = [&](const std::string& n) {
      const auto it = ms.find({n, thr});
      return it == ms.end() ? -1.0 : it->second;
    };
    // The peer labels its fastest map loop with its own build flags; match the stable prefix.
    const auto maps_it = std::find_if(ms.begin(), ms.end(), [&](const auto& kv) {
      return kv.first.second == thr && kv.first.first.rfind("maps: auto-vectorised loop", 0) == 0;
    });
    const double maps = maps_it == ms.end() ? -1.0 : maps_it->second;
    const struct { const char* filter; double remap; } peers[] = {
        {"nearest", get("remap INTER_NEAREST, float maps")},
        {"bilinear", get("remap INTER_LINEAR, float maps")},
        {"bicubic", get("remap INTER_CUBIC, float maps")}};
    for (const auto& p : peers) {
      if (maps < 0 || p.remap < 0) continue;
      Row r;
      r.source = "opencv-maps+remap";
      r.kernel = "rational";
      r.filter = p.filter;
      r.threads = thr;
      r.ms = maps + p.remap;
      r.mpix = mpix / (r.ms / 1000.0);
      // INTER_LINEAR/CUBIC quantise positions to 1/32 px: up to 1/64 px off per axis.
      r.max_err = p.filter == std::string("nearest") ? -1 : std::sqrt(2.0) / 64.0;
      rows.push_back(r);
    }
  }
  return rows;
}

void drawPlot(const std::vector<Row>& rows, const std::string& path) {
  const int w = 800, h = 500, left = 60, bottom = 40, right = 20, top = 20;
  ImageF img(w, h, 3);
  std::fill(img.data.begin(), img.data.end(), 1.0f);
  const auto put = [&](int x, int y, const float c[3]) {
    if (x < 0 || y < 0 || x >= w || y >= h) return;
    float* p = img.pixel(x, y);
    for (int k = 0; k < 3; ++k) p[k] = c[k];
  };
  const float black[3] = {0, 0, 0}, grey[3] = {0.8f, 0.8f, 0.8f};
  // x: log10 Mpix/s in [0, 4]; y: log10 max error in [−8, 0] (0 error drawn at the bottom).
  const auto xOf = [&](double mpix) {
    return left + static_cast<int>((w - left - right) * std::clamp(std::log10(std::max(mpix, 1.0)) / 4.0, 0.0, 1.0));
  };
  const auto yOf = [&](double err) {
    const double l = err > 0 ? std::log10(err) : -8.0;
    return h - bottom - static_cast<int>((h - top - bottom) * std::clamp((l + 8.0) / 8.0, 0.0, 1.0));
  };
  for (int d = 0; d <= 4; ++d)
    for (int y = top; y < h - bottom; ++y) put(xOf(std::pow(10.0, d)), y, grey);
  for (int d = -8; d <= 0; ++d)
    for (int x = left; x < w - right; ++x) put(x, yOf(std::pow(10.0, d)), grey);
  for (int x = left; x < w - right; ++x) put(x, h - bottom, black);
  for (int y = top; y < h - bottom; ++y) put(left, y, black);
  const float target[3] = {0.9f, 0.3f, 0.3f};  // the 1/256 px budget
  for (int x = left; x < w - right; x += 2) put(x, yOf(1.0 / 256.0), target);
  const std::map<std::string, std::array<float, 3>> colours = {
      {"identity", {0.1f, 0.1f, 0.1f}},       {"translation-copy", {0.5f, 0.5f, 0.5f}},
      {"affine", {0.1f, 0.6f, 0.1f}},         {"homography", {0.1f, 0.3f, 0.9f}},
      {"rational", {0.9f, 0.5f, 0.0f}},       {"homography-minify", {0.6f, 0.1f, 0.7f}},
      {"rational-scalar", {0.6f, 0.4f, 0.1f}}};
  for (const Row& r : rows) {
    if (r.max_err < 0) continue;  // no error figure (OpenCV nearest): nothing to place
    auto it = colours.find(r.kernel);
    std::array<float, 3> c = it == colours.end() ? std::array<float, 3>{0, 0, 0} : it->second;
    const bool peer = r.source != "artcam";
    if (peer) c = {0.9f, 0.1f, 0.1f};
    const int cx = xOf(r.mpix), cy = yOf(std::max(r.max_err, 0.0));
    const int rad = r.threads == 1 ? 3 : 5;
    for (int dy = -rad; dy <= rad; ++dy)
      for (int dx = -rad; dx <= rad; ++dx)
        if (!peer || std::abs(dx) == std::abs(dy) || dx == 0 || dy == 0) put(cx + dx, cy + dy, c.data());
  }
  if (const Status s = writeImage(path, img); !s) throw CommandError(s.message);
}

double processCpuMs() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) * 1e3 + static_cast<double>(t.tv_nsec) * 1e-6;
}

double medianOf(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

// The rational kernel against the peer in rounds, each ours then the peer's, so a drift of the
// machine's speed between the two (a third here from minute to minute) cancels in each round's
// ratio, as the suite's ratios against the homography do.
void pairedPeer(const std::string& dir, const PixelBuffer& pixels, const ConstImageView& src, const ImageView& dst,
                FrameSize size, const Camera& rational, const std::vector<int>& thread_counts) {
  constexpr int kRounds = 5, kReps = 3;
  std::map<int, std::vector<double>> ratios;
  for (int round = 0; round < kRounds; ++round) {
    std::map<int, double> ours;
    for (int threads : thread_counts) {
      WarpOptions o;
      o.threads = threads;
      WarpSummary s;
      warpImage(src, rational, dst, o, &s);  // warm-up
      std::vector<double> times;
      for (int r = 0; r < kReps; ++r) {
        warpImage(src, rational, dst, o, &s);
        times.push_back(s.render_ms);
      }
      ours[threads] = medianOf(times);
    }
    for (const Row& peer : runPeer(dir, pixels, size, kReps))
      if (peer.filter == "bilinear" && ours.count(peer.threads))
        ratios[peer.threads].push_back(peer.ms / ours[peer.threads]);
  }
  for (const auto& [threads, r] : ratios) {
    std::string list;
    for (double x : r) {
      char one[32];
      std::snprintf(one, sizeof one, "%s%.2f", list.empty() ? "" : " ", x);
      list += one;
    }
    std::fprintf(stderr, "peer pairs: rational bilinear, %d thread%s: opencv maps+remap / artcam = %.2f "
                 "(median of %zu rounds: %s)\n", threads, threads == 1 ? "" : "s", medianOf(r), r.size(), list.c_str());
  }
}


// What `artcam warp` does with a JPEG, timed by part: decode into the file's 8-bit samples
// (stored_image.h), the render alone, encode. One run each; the shares say where an export's
// time goes. Then the float path's decode (linear light) that the preview pyramid starts from.
void endToEndJpeg(const PixelBuffer& pixels, FrameSize size, const Camera& camera) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path();
  const std::string in = (dir / "artcam-bench-in.jpg").string(), out = (dir / "artcam-bench-out.jpg").string();
  {
    const ConstImageView view = packedView<const void>(pixels.data(), size.width, size.height, 3, PixelType::UInt8);
    if (const Status s = writeStoredImage(in, view); !s) throw CommandError(s.message);
  }
  using Clock = std::chrono::steady_clock;
  const auto ms = [](Clock::time_point a, Clock::time_point b) {
    return std::chrono::duration<double, std::milli>(b - a).count();
  };
  const auto t0 = Clock::now();
  auto stored = readStoredImage(in);
  if (!stored) throw CommandError(stored.status.message);
  const auto t1 = Clock::now();
  {
    // Uninitialised, as `artcam warp` allocates it (warp_job.cpp): the render's threads touch it.
    StoredImage warped = makeStoredImage(size.width, size.height, 3, -1, PixelType::UInt8,
                                         PixelBuffer::Init::Uninitialised);
    WarpSummary summary;
    warpImage(std::as_const(*stored).view(), camera, warped.view(), {}, &summary);
    const auto t2 = Clock::now();
    if (const Status s = writeStoredImage(out, std::as_const(warped).view(), &stored->info); !s)
      throw CommandError(s.message);
    const auto t3 = Clock::now();
    const double total = ms(t0, t3);
    std::fprintf(stderr,
                 "e2e_jpeg (artcam warp path, 8-bit): decode_ms=%.1f render_ms=%.1f (alloc+render %.1f) "
                 "encode_ms=%.1f total_ms=%.1f render_share=%.2f\n",
                 ms(t0, t1), summary.render_ms, ms(t1, t2), ms(t2, t3), total, ms(t1, t2) / total);
  }
  // Edit-to-preview: an 8-bit mip pyramid built once per photo, then for every edit a
  // 1920×1080 RGBA preview of the camera from the level that matches (mip_pyramid.h), into a
  // buffer the viewer keeps, all threads. Timed from the call to the finished pixels.
  const auto p0 = Clock::now();
  const StoredMipPyramid pyramid(std::as_const(*stored).view());
  const auto p1 = Clock::now();
  PixelBuffer preview(1920u * 1080u * 4u);
  const ImageView preview_view = packedView<void>(preview.data(), 1920, 1080, 4, PixelType::UInt8, 3);
  std::vector<double> times, cpu;
  WarpSummary preview_summary;
  for (int r = 0; r < 11; ++r) {
    const double c0 = processCpuMs();
    const auto a = Clock::now();
    warpPreview(pyramid, camera, preview_view, {}, &preview_summary);
    times.push_back(ms(a, Clock::now()));
    cpu.push_back(processCpuMs() - c0);
  }
  std::fprintf(stderr,
               "preview 1920x1080 RGBA8 of the %dx%d photo: pyramid_ms=%.1f (once) preview_ms=%.1f "
               "(median of 11; min %.1f; cpu_ms %.1f; %s, certified %.2f)\n",
               size.width, size.height, ms(p0, p1), medianOf(times),
               *std::min_element(times.begin(), times.end()), medianOf(cpu),
               preview_summary.note.c_str(), preview_summary.certified_share);
  std::filesystem::remove(in);
  std::filesystem::remove(out);
}


}  // namespace

// The largest position error of an Artcam's geometry against the exact inverse: every layer's
// camera; for a piecewise camera the mesh's error as the render estimates it (chooseMeshStep,
// checked against the exact inverse by the piecewise tests); negative where there is no figure.
double suiteError(const Artcam& camera, FrameSize size) {
  if (camera.isPiecewise()) return chooseMeshStep(*camera.pieces, size, size).error_px;
  double worst = 0.0;
  for (const Camera& layer : camera.layers) {
    try {
      worst = std::max(worst, measureError(layer, size).max);
    } catch (const std::exception&) {
      return -1.0;
    }
  }
  return worst;
}

// The camera suite (bench_suite.h) or --cameras files, each rendered through the render front
// door on the RGB8 image (layered and piecewise cameras from its linear float copy, as every
// caller does), bilinear, median of `reps`. Returns the rows; prints each, and on stderr each
// camera's time as a multiple of the homography's.
std::vector<Row> runSuite(const std::vector<SuiteCamera>& suite, const PixelBuffer& pixels,
                          FrameSize size, const std::vector<int>& thread_counts, int reps) {
  std::vector<Row> rows;
  const ConstImageView src = packedView<const void>(pixels.data(), size.width, size.height, 3, PixelType::UInt8);
  std::optional<ImageF> linear;
  std::unique_ptr<PixelBuffer> out8;
  std::optional<ImageF> outf;
  // The yardstick (suite[0], the homography) renders into its own buffer, once before each
  // render of every other camera: on a shared machine whose speed drifts from one second to
  // the next (the same camera measured 37 and 58 ms a minute apart), the multiple is the
  // median of these side-by-side pairs, not of two medians taken at different moments.
  const SuiteCamera& yardstick = suite.front();
  const OutputFrame yardstick_frame = outputFrameFor(yardstick.camera, size);
  PixelBuffer yardstick_out(static_cast<size_t>(yardstick_frame.size.width) *
                            static_cast<size_t>(yardstick_frame.size.height) * 4);
  const ImageView yardstick_view = packedView<void>(yardstick_out.data(), yardstick_frame.size.width,
                                                    yardstick_frame.size.height, 4, PixelType::UInt8, 3);
  const double mpix = size.width * static_cast<double>(size.height) / 1e6;
  for (const SuiteCamera& c : suite) {
    const bool float_path = needsLinearPhoto(c.camera);
    if (float_path && !linear) {
      linear.emplace(size.width, size.height, 4, 3);
      for (size_t i = 0, n = static_cast<size_t>(size.width) * static_cast<size_t>(size.height); i < n; ++i) {
        for (int k = 0; k < 3; ++k) {
          const float v = pixels[i * 3 + static_cast<size_t>(k)] / 255.0f;
          linear->data[i * 4 + static_cast<size_t>(k)] = v * v;  // near enough to linear for timing
        }
        linear->data[i * 4 + 3] = 1.0f;
      }
    }
    const OutputFrame frame = outputFrameFor(c.camera, size);
    const double err = suiteError(c.camera, size);
    for (int threads : thread_counts) {
      RenderOptions o;
      o.warp.filter = Filter::Bilinear;
      o.warp.threads = threads;
      RenderInputs in;
      in.photo = src;
      if (float_path) in.linear = &*linear;
      ImageView out;
      if (float_path) {
        if (!outf || outf->width != frame.size.width || outf->height != frame.size.height)
          outf.emplace(frame.size.width, frame.size.height, 4, 3);
        out = packedView<void>(outf->data.data(), outf->width, outf->height, 4, PixelType::Float, 3);
      } else {
        const size_t bytes = static_cast<size_t>(frame.size.width) * static_cast<size_t>(frame.size.height) * 4;
        if (!out8 || out8->size() != bytes) out8 = std::make_unique<PixelBuffer>(bytes);
        out = packedView<void>(out8->data(), frame.size.width, frame.size.height, 4, PixelType::UInt8, 3);
      }
      std::vector<double> times, cpu, yardstick_times, ratios;
      RenderSummary s;
      const bool paired = &c != &yardstick;
      RenderInputs yardstick_in;
      yardstick_in.photo = src;
      try {
        render(in, c.camera, o, out, &s);  // warm-up
        for (int r = 0; r < reps; ++r) {
          if (paired) {
            RenderSummary ys;
            render(yardstick_in, yardstick.camera, o, yardstick_view, &ys);
            yardstick_times.push_back(ys.render_ms);
          }
          const double c0 = processCpuMs();
          render(in, c.camera, o, out, &s);
          cpu.push_back(processCpuMs() - c0);
          times.push_back(s.render_ms);
          if (paired) ratios.push_back(s.render_ms / yardstick_times.back());
        }
      } catch (const std::exception& e) {
        std::fprintf(stderr, "bench: %s: %s\n", c.name.c_str(), e.what());
        break;
      }
      Row row;
      row.source = "suite";
      row.kernel = c.name;
      row.filter = "bilinear";
      row.threads = threads;
      row.ms = medianOf(times);
      row.cpu_ms = medianOf(cpu);
      row.mpix = mpix / (row.ms / 1000.0);
      row.max_err = err;
      printRow(row);
      rows.push_back(row);
      char multiple[96] = "x1.000 homography";
      if (paired)
        std::snprintf(multiple, sizeof multiple, "x%.3f homography (paired; it took %.1f ms)", medianOf(ratios),
                      medianOf(yardstick_times));
      std::fprintf(stderr, "suite: %-28s %d thr %8.1f ms  %s  max err %s px  (%s, %s)\n", c.name.c_str(),
                   threads, row.ms, multiple, err < 0 ? "-" : std::to_string(err).c_str(),
                   std::string(renderPathName(s.path)).c_str(), s.kernel.c_str());
    }
  }
  return rows;
}

int benchCommand(const std::vector<std::string>& argv) {
  if (!argv.empty() && argv[0] == "fit") return benchFitCommand({argv.begin() + 1, argv.end()});
  if (!argv.empty() && argv[0] == "effects") return benchEffectsCommand({argv.begin() + 1, argv.end()});
  const Args args(argv, {{"--size", "", true},
                         {"--reps", "", true},
                         {"--threads", "", true},
                         {"--plot", "", true},
                         {"--peer", "", true},
                         {"--only", "", true},
                         {"--filter", "", true},
                         {"--type", "", true},
                         {"--no-e2e", "", false},
                         {"--cameras", "", true},
                         {"--no-suite", "", false},
                         {"--overwrite", "", false},
                         {"--force", "", false}});
  // --cameras FILE… : the first file is the option's value, the rest follow as arguments.
  if (!args.has("--cameras")) args.expectPositional(1, "what to benchmark (render)");
  else if (args.positional().empty()) throw UsageError("missing what to benchmark (render)");
  if (args.positional()[0] != "render")
    throw UsageError("bench what? \"render\", \"fit\" or \"effects\"",
                     didYouMean(args.positional()[0], {"render", "fit", "effects"}));
  if (const auto plot = args.value("--plot")) checkOutputs(args, {*plot}, {});
  const FrameSize size = args.has("--size") ? parseSize(*args.value("--size"), "--size")
                                            : FrameSize{6000, 4000};
  checkImageMemory(size, "--size");
  // Refused, not clamped: a benchmark of other settings than asked would be silently wrong.
  const int reps = intOption(args, "--reps", 5, 1, 1000);
  std::vector<int> thread_counts;
  for (const long long t :
       parseIntegerList(args.valueOr("--threads", "1,2"), "--threads", 1, kMaxThreads))
    thread_counts.push_back(static_cast<int>(t));

  const std::string type_name = args.valueOr("--type", "uint8");
  PixelType type = PixelType::UInt8;
  if (type_name == "uint16") type = PixelType::UInt16;
  else if (type_name == "float") type = PixelType::Float;
  else if (type_name != "uint8")
    throw UsageError("--type expects uint8, uint16 or float", didYouMean(type_name, {"uint8", "uint16", "float"}));

  // Whole images live on huge pages where the kernel allows (pixel_buffer.h), as in `artcam warp`.
  const PixelBuffer pixels = makeImage(size.width, size.height);
  const ConstImageView src8 = packedView<const void>(pixels.data(), size.width, size.height, 3, PixelType::UInt8);
  PixelBuffer out_pixels(pixels.size());
  // --type: the kernel rows' copy of the image in that type (full scale: 255 → 65535 or 1).
  const size_t samples = pixels.size();
  const size_t sample_bytes = static_cast<size_t>(pixelTypeSize(type));
  std::optional<PixelBuffer> typed_in, typed_out;
  if (type != PixelType::UInt8) {
    typed_in.emplace(samples * sample_bytes);
    typed_out.emplace(samples * sample_bytes);
    for (size_t i = 0; i < samples; ++i) {
      if (type == PixelType::UInt16) {
        const auto v = static_cast<std::uint16_t>(pixels[i] * 257u);
        std::memcpy(typed_in->data() + i * 2, &v, 2);
      } else {
        const float v = pixels[i] / 255.0f;
        std::memcpy(typed_in->data() + i * 4, &v, 4);
      }
    }
  }
  const ConstImageView src = typed_in ? packedView<const void>(typed_in->data(), size.width, size.height, 3, type) : src8;
  const ImageView dst = packedView<void>(typed_out ? typed_out->data() : out_pixels.data(), size.width, size.height, 3, type);
  const std::string type_suffix = type == PixelType::UInt8 ? "" : "-" + type_name;
  const double mpix = size.width * static_cast<double>(size.height) / 1e6;

  std::printf("source,kernel,filter,threads,ms,mpix_per_s,max_err_px,rms_err_px,newton_share,certified_share,cpu_ms\n");
  {
    // The memory ceiling: one image read, one written (the identity kernel's job), 1 thread.
    std::vector<double> times;
    for (int r = 0; r < reps + 1; ++r) {
      const auto a = std::chrono::steady_clock::now();
      std::memcpy(out_pixels.data(), pixels.data(), pixels.size());
      times.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - a).count());
    }
    times.erase(times.begin());  // first touch of the output pages
    Row row;
    row.source = "memcpy";
    row.kernel = "copy";
    row.filter = "none";
    row.ms = medianOf(times);
    row.mpix = mpix / (row.ms / 1000.0);
    printRow(row);
  }
  std::vector<Row> rows;
  const std::string only = args.valueOr("--only", "");
  const std::string filters = args.valueOr("--filter", "");
  // --cameras: those files (after the homography yardstick) instead of the kernel rows and the
  // built-in suite.
  const bool files_only = args.has("--cameras");
  std::vector<SuiteCamera> files;
  if (files_only) {
    std::vector<std::string> paths{*args.value("--cameras")};
    paths.insert(paths.end(), args.positional().begin() + 1, args.positional().end());
    for (const std::string& path : paths) {
      Result<Artcam> camera = readArtcam(path);
      if (!camera) throw CommandError(camera.status.message);
      files.push_back({std::filesystem::path(path).stem().string(), std::move(*camera)});
    }
  }
  for (const Case& c : makeCases(size)) {
    if (files_only) break;
    if (!only.empty() && ("," + only + ",").find("," + c.name + ",") == std::string::npos) continue;
    const PositionError err = measureError(c.camera, size);
    if (err.validity_mismatch)
      std::fprintf(stderr, "bench: %s: %lld sampled pixels differ from the reference in having a "
                   "preimage\n", c.name.c_str(), err.validity_mismatch);
    for (Filter f : {Filter::Nearest, Filter::Bilinear, Filter::Bicubic}) {
      if ((c.antialias || c.scalar_only) && f != Filter::Bilinear) continue;
      if (!filters.empty() && ("," + filters + ",").find("," + std::string(filterName(f)) + ",") == std::string::npos)
        continue;
      for (int threads : thread_counts) {
        WarpOptions o;
        o.filter = f;
        o.threads = threads;
        o.antialias = c.antialias;
        o.coordinates.scalar_only = c.scalar_only;
        std::vector<double> times, cpu;
        WarpSummary s;
        warpImage(src, c.camera, dst, o, &s);  // warm-up
        for (int r = 0; r < reps; ++r) {
          const double c0 = processCpuMs();
          warpImage(src, c.camera, dst, o, &s);
          cpu.push_back(processCpuMs() - c0);
          times.push_back(s.render_ms);
        }
        Row row;
        row.source = "artcam";
        row.kernel = c.name + type_suffix;
        row.filter = std::string(filterName(f)) + (c.antialias ? "+aa" : "");
        row.threads = threads;
        row.ms = medianOf(times);
        row.cpu_ms = medianOf(cpu);
        row.mpix = mpix / (row.ms / 1000.0);
        row.max_err = err.max;
        row.rms_err = err.rms;
        row.newton_share = s.newton_pixels / (mpix * 1e6);
        row.certified_share = s.certified_share;
        printRow(row);
        rows.push_back(row);
      }
    }
  }
  if (args.has("--peer")) {
    for (const Row& r : runPeer(*args.value("--peer"), pixels, size, reps)) {
      printRow(r);
      rows.push_back(r);
    }
    if (type == PixelType::UInt8)
      pairedPeer(*args.value("--peer"), pixels, src, dst, size, makeCases(size)[4].camera, thread_counts);
  }
  if (files_only || !args.has("--no-suite")) {
    std::vector<SuiteCamera> suite = benchCameraSuite(size);
    if (files_only) {
      suite.resize(1);  // the homography, the yardstick
      for (SuiteCamera& f : files) suite.push_back(std::move(f));
    }
    for (const Row& r : runSuite(suite, pixels, size, thread_counts, reps)) rows.push_back(r);
  }
  if (!files_only && !args.has("--no-e2e")) endToEndJpeg(pixels, size, makeCases(size)[4].camera);
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  // The suite also holds the yardstick's own RGBA output beside each camera's (runSuite).
  std::fprintf(stderr, "peak_rss_mib=%.1f (image in + out: %.1f MiB%s)\n", usage.ru_maxrss / 1024.0,
               2.0 * static_cast<double>(pixels.size()) / (1024.0 * 1024.0),
               files_only || !args.has("--no-suite") ? ", plus the suite's yardstick output" : "");
  if (args.has("--plot")) drawPlot(rows, *args.value("--plot"));
  return 0;
}

}  // namespace artcam::cli
