// SPDX-License-Identifier: Apache-2.0
// artcam bench fit: time against error for every fitting method. A benchmark, not a
// test: medians of repeated fits on matches made in code from a known rational camera, the
// error measured against that true map on a dense grid (target pixels).
#include "app/cli/args.h"
#include "app/cli/commands.h"
#include "app/cli/outputs.h"
#include "core/colour/colour_difference.h"
#include "core/fit/fit_colour.h"
#include "core/fit/fit_image.h"
#include "core/io/image_io.h"
#include "core/model/frames.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <random>
#include <string>
#include <vector>

namespace artcam::cli {

const char* const kBenchFitUsage =
    "usage: artcam bench fit [--counts LIST] [--noise LIST] [--methods LIST] [--plot OUT.png]\n"
    "                        [--seconds S] [--colour] [--overwrite]\n\n"
    "Fits cameras to matches made from a known rational lens on a 6000x4000 frame, for each\n"
    "method (raw-dlt: no conditioning; dlt: conditioned; refine: + Levenberg-Marquardt;\n"
    "robust: + MSAC/LO-RANSAC with 20 % gross outliers added; auto: the model ladder), match\n"
    "count (default 9,30,100,1000,10000,100000) and noise level in px (default 0,0.5,2).\n"
    "Prints CSV: method,matches,noise_px,median_us,median_cpu_us,reps,rms_err_px,max_err_px\n"
    "where median_us is wall time and median_cpu_us the fitting thread's CPU time (fits are\n"
    "single-threaded, so on a shared, loaded machine the CPU time is the figure that measures\n"
    "the work; the wall time adds the waits for a core), and the error is against the true map\n"
    "over the frame. --methods picks some of raw-dlt,dlt,refine,robust,auto. --plot writes a\n"
    "PNG of time (x, log) against error (y, log): the Pareto view. --seconds bounds each\n"
    "cell's timing (0.3). An existing --plot file is replaced only with --overwrite (--force).\n"
    "--colour adds colour calibration (fit --block colour): auto and robust auto on 24, 100\n"
    "and 1000 samples of a rational colour map (10 % wrong samples for robust) with noise\n"
    "sigma 0, 0.002, 0.01 in linear RGB, as a second CSV:\n"
    "colour_method,samples,noise_rgb,median_us,median_cpu_us,reps,chosen,mean_de,max_de\n"
    "where the dE00 is against the true map on a 9^3 grid of the unit cube.\n";

namespace {

const FrameSize kFrame{6000, 4000};

struct Method {
  const char* name;
  FitOptions options;
  bool outliers;
};

Camera lensCamera() {
  // A pincushion lens with a little perspective: 1 - k r² in the denominator (normalised).
  Camera c = Camera::identity({Block{BlockKind::Position, 3}}, kFrame, kFrame);
  c.stages()[0].q[2](0, 0) = -0.08;
  c.stages()[0].q[2](1, 1) = -0.08;
  c.stages()[0].q[2](0, 2) = c.stages()[0].q[2](2, 0) = 0.02;
  c.stages()[0].q[0](0, 1) = c.stages()[0].q[0](1, 0) = 0.03;
  return c;
}

std::vector<PointMatch> makeMatches(const Camera& truth, int count, double noise, bool outliers,
                                    std::mt19937_64& rng) {
  std::uniform_real_distribution<double> ux(0, kFrame.width), uy(0, kFrame.height);
  std::normal_distribution<double> gauss(0.0, noise > 0 ? noise : 1.0);
  std::vector<PointMatch> m;
  for (int k = 0; k < count; ++k) {
    const Eigen::Vector2d s(ux(rng), uy(rng));
    Eigen::Vector2d t = *targetPixelFromSourcePixel(truth, s);
    if (noise > 0) t += Eigen::Vector2d(gauss(rng), gauss(rng));
    if (outliers && k % 5 == 0) t = Eigen::Vector2d(ux(rng), uy(rng));
    m.push_back({s, t, true});
  }
  return m;
}

void mapError(const Camera& fit, const Camera& truth, double& rms, double& max) {
  double sum = 0.0;
  max = 0.0;
  int n = 0;
  for (int j = 0; j <= 40; ++j)
    for (int i = 0; i <= 40; ++i, ++n) {
      const Eigen::Vector2d p(kFrame.width * i / 40.0, kFrame.height * j / 40.0);
      const auto a = targetPixelFromSourcePixel(fit, p), b = targetPixelFromSourcePixel(truth, p);
      const double e = a && b ? (*a - *b).norm() : 1e9;
      sum += e * e;
      max = std::max(max, e);
    }
  rms = std::sqrt(sum / n);
}

struct Row {
  std::string method;
  int matches;
  double noise, median_us, median_cpu_us, rms, max;
};

// CPU time of the calling thread, µs.
double threadCpuMicroseconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) * 1e6 + static_cast<double>(t.tv_nsec) * 1e-3;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

// Time (x) against error (y), both log scale, one colour per method.
void plot(const std::vector<Row>& rows, const std::vector<Method>& methods, const std::string& path) {
  const int w = 800, h = 600, margin = 50;
  ImageF img(w, h, 3);
  std::fill(img.data.begin(), img.data.end(), 1.0f);
  const auto axis = [&](int x0, int y0, int x1, int y1) {
    for (int t = 0; t <= 1000; ++t) {
      const int x = x0 + (x1 - x0) * t / 1000, y = y0 + (y1 - y0) * t / 1000;
      float* p = img.pixel(x, y);
      p[0] = p[1] = p[2] = 0.0f;
    }
  };
  axis(margin, h - margin, w - margin, h - margin);
  axis(margin, margin, margin, h - margin);
  const float colours[][3] = {{0.8f, 0.1f, 0.1f}, {0.1f, 0.5f, 0.1f}, {0.1f, 0.2f, 0.8f},
                              {0.7f, 0.5f, 0.0f}, {0.5f, 0.0f, 0.6f}};
  // x: log10(µs) in [0, 6]; y: log10(px) in [-10, 3].
  for (const Row& r : rows) {
    const size_t mi = static_cast<size_t>(
        std::find_if(methods.begin(), methods.end(), [&](const Method& m) { return r.method == m.name; }) -
        methods.begin());
    const double lx = std::clamp(std::log10(std::max(r.median_us, 1.0)) / 6.0, 0.0, 1.0);
    const double ly = std::clamp((std::log10(std::max(r.rms, 1e-10)) + 10.0) / 13.0, 0.0, 1.0);
    const int cx = margin + static_cast<int>(lx * (w - 2 * margin));
    const int cy = h - margin - static_cast<int>(ly * (h - 2 * margin));
    const int radius = 2 + static_cast<int>(std::log10(r.matches));
    for (int dy = -radius; dy <= radius; ++dy)
      for (int dx = -radius; dx <= radius; ++dx)
        if (dx * dx + dy * dy <= radius * radius && cx + dx >= 0 && cx + dx < w && cy + dy >= 0 && cy + dy < h)
          std::copy(colours[mi % 5], colours[mi % 5] + 3, img.pixel(cx + dx, cy + dy));
  }
  if (const Status s = writeImage(path, img); !s) throw CommandError(s.message);
}

// A rational colour map (highlights stay near white while mid-tones shift, the paper's Fig 6).
Eigen::Vector3d colourTruth(const Eigen::Vector3d& c) {
  const double w = 1.0 + 0.6 * c.squaredNorm() - 0.3 * c.x() * c.z();
  return Eigen::Vector3d(0.9 * c.x() + 0.4 * c.x() * c.x() + 0.2 * c.y() * c.z() + 0.05,
                         0.3 * c.y() + 1.1 * c.y() * c.y() + 0.2 * c.x() * c.y(),
                         0.5 * c.z() + 0.8 * c.z() * c.z() + 0.3 * c.x() * c.x() + 0.1) /
         w;
}

void benchColour(double seconds) {
  std::printf("colour_method,samples,noise_rgb,median_us,median_cpu_us,reps,chosen,mean_de,max_de\n");
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(0.02, 0.98);
  for (const bool robust : {false, true})
    for (int count : {24, 100, 1000})
      for (double noise : {0.0, 0.002, 0.01}) {
        std::normal_distribution<double> gauss(0.0, noise > 0 ? noise : 1.0);
        std::vector<PointMatch> samples;
        for (int k = 0; k < count; ++k) {
          const Eigen::Vector3d c(unit(rng), unit(rng), unit(rng));
          Eigen::Vector3d d = colourTruth(c);
          if (noise > 0) d += Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng));
          if (robust && k % 10 == 3) d = Eigen::Vector3d(unit(rng), unit(rng), unit(rng));
          samples.push_back({c, d, true});
        }
        ColourFitOptions options;
        options.robust = robust;
        std::vector<double> times, cpu_times;
        ColourFitSummary fit;
        const auto begin = std::chrono::steady_clock::now();
        do {
          const double c0 = threadCpuMicroseconds();
          const auto t0 = std::chrono::steady_clock::now();
          fit = fitColourSamples(samples, options);
          times.push_back(std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count());
          cpu_times.push_back(threadCpuMicroseconds() - c0);
        } while (times.size() < 3 ||
                 (times.size() < 200 &&
                  std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count() < seconds));
        double sum = 0.0, worst = 0.0;
        int n = 0;
        for (int i = 0; i < 9 && fit.status; ++i)
          for (int j = 0; j < 9; ++j)
            for (int k = 0; k < 9; ++k, ++n) {
              const Eigen::Vector3d c(0.05 + 0.1125 * i, 0.05 + 0.1125 * j, 0.05 + 0.1125 * k);
              const auto y = fit.map.apply(c);
              const double de = y ? deltaE2000(colourTruth(c), *y) : 1e9;
              sum += de;
              worst = std::max(worst, de);
            }
        std::printf("%s,%d,%g,%.1f,%.1f,%zu,%s,%.3g,%.3g\n", robust ? "robust-auto" : "auto", count,
                    noise, median(times), median(cpu_times), times.size(),
                    fit.status ? std::string(colourModelName(fit.map.model)).c_str() : "failed",
                    n ? sum / n : -1.0, n ? worst : -1.0);
        std::fflush(stdout);
      }
}

}  // namespace

int benchFitCommand(const std::vector<std::string>& argv) {
  const Args args(argv, {{"--counts", "", true}, {"--noise", "", true}, {"--plot", "", true},
                         {"--seconds", "", true}, {"--methods", "", true}, {"--colour", "", false},
                         {"--overwrite", "", false}, {"--force", "", false}});
  args.expectPositional(0, "");
  if (const auto plot = args.value("--plot")) checkOutputs(args, {*plot}, {});
  // A run that measures nothing is a usage mistake, not an empty table: every count is a whole
  // number of matches the quadratic can be fitted to (9) up to a million, noise is a finite
  // non-negative px, and each row gets a positive time budget of at most an hour.
  const std::vector<long long> counts = parseIntegerList(
      args.valueOr("--counts", "9,30,100,1000,10000,100000"), "--counts", 9, 1000000);
  const std::vector<double> noises =
      parseNumberList(args.valueOr("--noise", "0,0.5,2"), "--noise", 0, kUnbounded);
  const double seconds = numberOption(args, "--seconds", 0.3, 0, 3600, Ends::OpenMin);
  const std::string only = args.valueOr("--methods", "raw-dlt,dlt,refine,robust,auto");
  for (size_t p = 0; p <= only.size();) {
    const size_t comma = std::min(only.find(',', p), only.size());
    const std::string name = only.substr(p, comma - p);
    const std::vector<std::string> known = {"raw-dlt", "dlt", "refine", "robust", "auto"};
    if (std::find(known.begin(), known.end(), name) == known.end())
      throw UsageError("--methods: unknown method \"" + name + "\" (raw-dlt, dlt, refine, robust, auto)",
                       didYouMean(name, known));
    p = comma + 1;
  }
  const auto wanted = [&](const std::string& name) {
    return ("," + only + ",").find("," + name + ",") != std::string::npos;
  };

  std::vector<Method> methods(5);
  methods[0] = {"raw-dlt", {}, false};
  methods[0].options.condition = false;
  methods[1] = {"dlt", {}, false};
  methods[2] = {"refine", {}, false};
  methods[3] = {"robust", {}, true};
  methods[4] = {"auto", {}, false};
  for (int i = 0; i < 4; ++i) methods[i].options.model = ModelClass::Quadratic;
  for (Method& m : methods) m.options.diagnostics = false;
  methods[0].options.refine = methods[1].options.refine = false;
  methods[3].options.robust = true;
  methods[3].options.robust_threshold_px = 6.0;

  const Camera truth = lensCamera();
  std::mt19937_64 rng(42);
  std::vector<Row> rows;
  std::printf("method,matches,noise_px,median_us,median_cpu_us,reps,rms_err_px,max_err_px\n");
  for (const Method& method : methods)
    for (const long long count : counts) {
      if (!wanted(method.name)) continue;
      for (double noise : noises) {
        const int n = static_cast<int>(count);
        if ((method.outliers || method.options.model == ModelClass::Auto) && n > 10000) continue;
        const std::vector<PointMatch> matches = makeMatches(truth, n, noise, method.outliers, rng);
        std::vector<double> times, cpu_times;
        FitSummary fit;
        const auto begin = std::chrono::steady_clock::now();
        do {
          const double c0 = threadCpuMicroseconds();
          const auto t0 = std::chrono::steady_clock::now();
          fit = fitImageCamera(matches, kFrame, kFrame, method.options);
          times.push_back(std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count());
          cpu_times.push_back(threadCpuMicroseconds() - c0);
        } while (times.size() < 3 ||
                 (times.size() < 200 &&
                  std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count() < seconds));
        Row row{method.name, n, noise, median(times), median(cpu_times), -1, -1};
        if (fit.status) mapError(fit.camera, truth, row.rms, row.max);
        std::printf("%s,%d,%g,%.1f,%.1f,%zu,%.3g,%.3g\n", method.name, n, noise, row.median_us,
                    row.median_cpu_us, times.size(), row.rms, row.max);
        std::fflush(stdout);
        if (fit.status) rows.push_back(row);
      }
    }
  if (const auto path = args.value("--plot")) plot(rows, methods, *path);
  if (args.has("--colour")) benchColour(seconds);
  return 0;
}

}  // namespace artcam::cli
