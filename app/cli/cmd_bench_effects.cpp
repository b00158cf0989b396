// SPDX-License-Identifier: Apache-2.0
// artcam bench effects: time against error for the effect renderers.
// - Depth of field: the fast blur stack against the exact per-pixel Gaussian (depth_of_field.h)
//   over blur strengths: PSNR on a crop (the exact blur costs O(σ²) per pixel), the time of
//   both on that crop, and the stack's time on the whole image.
// - Splat against gather on a geometry-only rational camera (attributed.h): PSNR where both
//   cover, and their times.
// Figures are medians of --reps runs; the image is the bundled photo upscaled (bilinear) in
// code to --size. A benchmark, not a test: no assertions, quote the load with the figures.
#include "app/cli/args.h"
#include "app/cli/commands.h"
#include "app/cli/memory.h"
#include "core/effects/depth_of_field.h"
#include "core/io/image_io.h"
#include "core/model/frames.h"
#include "core/render/attributed.h"
#include "core/render/warp.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <functional>
#include <string>
#include <vector>

namespace artcam::cli {

namespace {

// Process CPU time (all threads), ms: less sensitive than wall time to a shared, loaded machine.
double cpuMs() { return 1000.0 * static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

// Median wall time of `reps` runs; `cpu_ms` (optional) gets the median CPU time.
double medianMs(int reps, const std::function<void()>& run, double* cpu_ms = nullptr) {
  std::vector<double> ms, cpu;
  for (int r = 0; r < reps; ++r) {
    const double c0 = cpuMs();
    const auto t0 = std::chrono::steady_clock::now();
    run();
    ms.push_back(
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    cpu.push_back(cpuMs() - c0);
  }
  std::sort(ms.begin(), ms.end());
  std::sort(cpu.begin(), cpu.end());
  if (cpu_ms) *cpu_ms = cpu[cpu.size() / 2];
  return ms[ms.size() / 2];
}

double psnrRgb(const ImageF& a, const ImageF& b, bool covered_only) {
  double se = 0.0;
  long long n = 0;
  for (size_t p = 0; p + 3 < a.data.size(); p += 4) {
    if (covered_only && (a.data[p + 3] < 0.999f || b.data[p + 3] < 0.999f)) continue;
    for (int c = 0; c < 3; ++c) {
      const double d = a.data[p + static_cast<size_t>(c)] - b.data[p + static_cast<size_t>(c)];
      se += d * d;
      ++n;
    }
  }
  return n && se > 0 ? 10.0 * std::log10(static_cast<double>(n) / se) : 999.0;
}

// Bilinear resize of RGBA (pixel centres), for a photo-sized input made from the bundled one.
ImageF resize(const ImageF& src, int w, int h) {
  ImageF out(w, h, 4, 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const double fx = std::clamp((x + 0.5) * src.width / w - 0.5, 0.0, src.width - 1.0);
      const double fy = std::clamp((y + 0.5) * src.height / h - 0.5, 0.0, src.height - 1.0);
      const int x0 = static_cast<int>(fx), y0 = static_cast<int>(fy);
      const int x1 = std::min(x0 + 1, src.width - 1), y1 = std::min(y0 + 1, src.height - 1);
      const double tx = fx - x0, ty = fy - y0;
      for (int c = 0; c < 4; ++c)
        out.pixel(x, y)[c] = static_cast<float>(
            (1 - ty) * ((1 - tx) * src.pixel(x0, y0)[c] + tx * src.pixel(x1, y0)[c]) +
            ty * ((1 - tx) * src.pixel(x0, y1)[c] + tx * src.pixel(x1, y1)[c]));
    }
  return out;
}

ImageF crop(const ImageF& src, int x0, int y0, int w, int h) {
  ImageF out(w, h, src.channels, src.alpha_channel);
  for (int y = 0; y < h; ++y)
    std::copy(src.pixel(x0, y0 + y),
              src.pixel(x0, y0 + y) + static_cast<size_t>(w) * static_cast<size_t>(src.channels),
              out.pixel(0, y));
  return out;
}

// σ grows with a depth ramp left to right, 0 at the focus column a third of the way in, and a
// sharp foreground disc in the middle (where halos would show).
ImageF sigmaField(int w, int h, double max_sigma) {
  ImageF s(w, h, 1);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const double u = (x + 0.5) / w;
      double v = max_sigma * std::abs(u - 1.0 / 3.0) / (2.0 / 3.0);
      const double dx = x - 0.5 * w, dy = y - 0.5 * h;
      if (dx * dx + dy * dy < 0.04 * h * h) v = 0.0;
      s.pixel(x, y)[0] = static_cast<float>(v);
    }
  return s;
}

// Fast stack against the exact blur on a crop of the photo at its own resolution (an upscaled
// copy is smooth and flatters it), then the stack alone on the whole upscaled image.
void benchDepthOfField(const ImageF& native, const ImageF& rgba, int crop_side,
                       const std::vector<double>& sigmas, int reps, const BlurOptions& blur) {
  const int cw = std::min(crop_side, native.width), ch = std::min(crop_side, native.height);
  const ImageF rgba_crop = crop(native, (native.width - cw) / 2, (native.height - ch) / 2, cw, ch);
  std::printf(
      "bench,max_sigma_px,width,height,psnr_db,exact_ms,stack_ms,stack_full_ms,"
      "stack_full_cpu_ms,full_mpix\n");
  for (const double s : sigmas) {
    const ImageF sigma_crop = sigmaField(cw, ch, s);
    ImageF exact, fast;
    const double exact_ms = medianMs(1, [&] { exact = exactBlur(rgba_crop, sigma_crop, blur); });
    const double stack_ms = medianMs(reps, [&] { fast = stackBlur(rgba_crop, sigma_crop, blur); });
    const ImageF sigma_full = sigmaField(rgba.width, rgba.height, s);
    double full_cpu_ms = 0.0;
    const double full_ms = medianMs(
        reps, [&] { (void)stackBlur(rgba, sigma_full, blur); }, &full_cpu_ms);
    std::printf("dof,%g,%d,%d,%.2f,%.1f,%.1f,%.1f,%.1f,%.1f\n", s, cw, ch,
                psnrRgb(exact, fast, false), exact_ms, stack_ms, full_ms, full_cpu_ms,
                rgba.width * static_cast<double>(rgba.height) / 1e6);
    std::fflush(stdout);
  }
}

}  // namespace

const char* const kBenchEffectsUsage =
    "usage: artcam bench effects [--size WxH] [--crop N] [--sigmas LIST] [--reps N]\n"
    "                            [--threads N] [--image FILE] [--ratio R] [--shrink-from S]\n"
    "                            [--only dof|splat]\n\n"
    "Depth of field, fast stack (levels σ·R) vs exact: PSNR (dB) and time (ms) on an N×N crop\n"
    "of the photo at its own resolution for each maximum blur σ (pixels), and the stack's time\n"
    "on the whole WxH image; then splat vs gather on a rational geometry-only camera (PSNR\n"
    "where both cover, times). CSV on stdout.\n"
    "  --size WxH         the whole image the stack is timed on (default 6000x4000)\n"
    "  --crop N           side of the centre crop compared with the exact blur (default 384)\n"
    "  --sigmas LIST      maximum blur σ values, pixels (default 2,4,8,16)\n"
    "  --reps N           timed runs, the median is reported (default 3)\n"
    "  --threads N        worker threads (default 0: one per core)\n"
    "  --image FILE       the photo (default resources/coffee.png: run from the repository root)\n"
    "  --ratio R          ratio between the stack's blur levels (default √2 = 1.41421356237)\n"
    "  --only dof|splat   run one of the two benchmarks (default both)\n"
    "  --shrink-from S    blur levels from σ = S on are computed on a shrunk image (default 2)\n\n"
    "Example:\n"
    "  artcam bench effects --size 3000x2000 --sigmas 4,16 --reps 1\n";

int benchEffectsCommand(const std::vector<std::string>& argv) {
  const Args args(argv, {{"--size", "", true},
                         {"--crop", "", true},
                         {"--sigmas", "", true},
                         {"--reps", "", true},
                         {"--threads", "", true},
                         {"--image", "", true},
                         {"--ratio", "", true},
                         {"--shrink-from", "", true},
                         {"--only", "", true}});
  const FrameSize size = parseSize(args.valueOr("--size", "6000x4000"), "--size");
  checkImageMemory(size, "--size");
  // Refused, never clamped: a benchmark of other settings than asked would be silently wrong.
  const int crop_side = intOption(args, "--crop", 384, 8, 1000000);
  const int reps = intOption(args, "--reps", 3, 1, 1000);
  const std::vector<double> sigmas =
      parseNumberList(args.valueOr("--sigmas", "2,4,8,16"), "--sigmas", 0, kUnbounded);
  const std::string path = args.valueOr("--image", "resources/coffee.png");
  BlurOptions blur;
  blur.threads = intOption(args, "--threads", 0, 0, kMaxThreads);
  blur.level_ratio = numberOption(args, "--ratio", blur.level_ratio, 1, kUnbounded, Ends::OpenMin);
  blur.shrink_from_sigma =
      numberOption(args, "--shrink-from", blur.shrink_from_sigma, 0, kUnbounded, Ends::OpenMin);

  const auto photo = readImage(path);
  if (!photo) throw CommandError(photo.status.message);
  const ImageF native = rgbaFromImage(photo->image);
  const ImageF rgba = resize(native, size.width, size.height);

  const std::string only = args.valueOr("--only", "");
  if (!only.empty() && only != "dof" && only != "splat")
    throw UsageError("--only expects dof or splat");
  if (only != "splat") benchDepthOfField(native, rgba, crop_side, sigmas, reps, blur);
  if (only == "dof") return 0;

  // Splat vs gather on the same geometry-only camera: a mild rational lens (barrel-like terms
  // plus a little perspective), so both paths apply.
  Camera cam = Camera::identity({Block{BlockKind::Position, 3}}, size, size);
  cam.stages()[0].q[2](0, 0) = cam.stages()[0].q[2](1, 1) = 0.06;
  cam.stages()[0].q[2](0, 2) = cam.stages()[0].q[2](2, 0) = 0.02;
  AttributedOptions gather_options, splat_options;
  gather_options.warp.threads = splat_options.warp.threads = blur.threads;
  splat_options.force_path = "splat";
  AttributedImage g, sp;
  const double gather_ms =
      medianMs(reps, [&] { g = renderAttributed(rgba, nullptr, cam, gather_options); });
  const double splat_ms =
      medianMs(reps, [&] { sp = renderAttributed(rgba, nullptr, cam, splat_options); });
  std::printf("\nbench,width,height,psnr_db,gather_ms,splat_ms,splat_supersample\n");
  std::printf("splat_vs_gather,%d,%d,%.2f,%.1f,%.1f,%d\n", size.width, size.height,
              psnrRgb(g.colour, sp.colour, true), gather_ms, splat_ms,
              splat_options.splat_supersample);
  return 0;
}

}  // namespace artcam::cli
