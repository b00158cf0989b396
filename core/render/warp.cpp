// SPDX-License-Identifier: Apache-2.0
// The fused gather warp: pick the cheapest exact kernel once per camera
// from the structure analysis, then fill bands of output rows in parallel, one span of
// kSpanPixels at a time: source positions (coordinates.h) straight into the sampler
// (span_sampler.h), so no per-pixel map ever reaches memory.
#include "core/render/warp.h"

#include "core/model/analysed_cameras.h"
#include "core/model/frames.h"
#include "core/model/structure.h"
#include "core/mapping/coordinates.h"
#include "core/util/parallel.h"
#include "core/sampling/sampling.h"
#include "core/sampling/span_sampler.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>
#include <stdexcept>
#include <type_traits>
#include <vector>

namespace artcam {

FrameSize outputSizeFor(const Camera& camera, int width, int height) {
  if (width < 0 || height < 0) throw std::invalid_argument("output size must not be negative");
  const FrameSize target = camera.targetSize();
  if (width > 0 && height > 0) return {width, height};
  if (width == 0 && height == 0) return target;
  // One side given: keep the target frame's aspect ratio.
  const double aspect = static_cast<double>(target.height) / target.width;
  if (width > 0) return {width, std::max(1, static_cast<int>(std::lround(width * aspect)))};
  return {std::max(1, static_cast<int>(std::lround(height / aspect))), height};
}

FrameSize warpOutputSize(const Camera& camera, const WarpOptions& options) {
  return outputSizeFor(camera, options.width, options.height);
}

namespace {

void checkCamera(const Camera& camera, const CameraStructure& structure) {
  const BlockLayout& layout = camera.layout();
  const int p = layout.find(BlockKind::Position);
  if (p < 0 || layout.blocks[p].size != 3)
    throw std::invalid_argument("warpImage needs a camera with a 2D image position block");
  if (structure.geometry_depends_on_attributes)
    throw std::invalid_argument(
        "this camera's geometry depends on colour or depth (pc/cp coupling): the gather warp "
        "cannot invert it; it needs the splat renderer");
  if (structure.attributes_change)
    throw std::invalid_argument(
        "this camera also transforms colour or depth; warpImage renders position maps only, the "
        "per-pixel attribute transform is not implemented yet");
}

// Rows of a whole-pixel translation (identity included): sampling at pixel centres would
// reproduce the source exactly for every filter (weights 1 and 0, coverage 1), so copy.
// Row `out_row` of `out` from row `sy` of `src` (outside it: transparent), shifted by offset_x.
long long copyRow(const ConstImageView& src, int sy, const ImageView& out, int out_row, int offset_x) {
  const std::array<int, 2> offset{offset_x, 0};
  const int pixel_in = src.pixelBytes(), pixel_out = out.pixelBytes();
  unsigned char* row = static_cast<unsigned char*>(out.row(out_row));
  if (sy < 0 || sy >= src.height) {
    std::memset(row, 0, static_cast<size_t>(out.width) * static_cast<size_t>(pixel_out));
    return out.width;
  }
  const unsigned char* in = static_cast<const unsigned char*>(src.row(sy));
  const int x_begin = std::clamp(-offset[0], 0, out.width);
  const int x_end = std::clamp(src.width - offset[0], x_begin, out.width);
  std::memset(row, 0, static_cast<size_t>(x_begin) * static_cast<size_t>(pixel_out));
  std::memset(row + static_cast<std::ptrdiff_t>(x_end) * pixel_out, 0,
              static_cast<size_t>(out.width - x_end) * static_cast<size_t>(pixel_out));
  long long transparent = out.width - (x_end - x_begin);
  const unsigned char* first = in + static_cast<std::ptrdiff_t>(x_begin + offset[0]) * pixel_in;
  unsigned char* dst = row + static_cast<std::ptrdiff_t>(x_begin) * pixel_out;
  const int n = x_end - x_begin;
  if (pixel_in == pixel_out) {
    std::memcpy(dst, first, static_cast<size_t>(n) * static_cast<size_t>(pixel_in));
  } else {
    // Appended alpha: full coverage inside.
    const int size = pixelTypeSize(src.type);
    for (int x = 0; x < n; ++x) {
      std::memcpy(dst + x * pixel_out, first + x * pixel_in, static_cast<size_t>(pixel_in));
      unsigned char* alpha = dst + x * pixel_out + pixel_in;
      if (src.type == PixelType::UInt8) *alpha = 255;
      else if (src.type == PixelType::UInt16) { const std::uint16_t v = 65535; std::memcpy(alpha, &v, 2); }
      else { const float v = 1.0f; std::memcpy(alpha, &v, static_cast<size_t>(size)); }
    }
  }
  if (src.alpha_channel >= 0) {
    // A transparent source pixel stays transparent: count it like the sampling kernels do.
    const int size = pixelTypeSize(src.type);
    for (int x = 0; x < n; ++x) {
      const unsigned char* p = dst + x * pixel_out + src.alpha_channel * size;
      bool zero = false;
      if (src.type == PixelType::UInt8) zero = *p == 0;
      else if (src.type == PixelType::UInt16) { std::uint16_t v; std::memcpy(&v, p, 2); zero = v == 0; }
      else { float v; std::memcpy(&v, p, 4); zero = !(v > 0.0f); }
      transparent += zero;
    }
  }
  return transparent;
}

constexpr int kBandRows = 16;

// The supersampling factor for a span: the footprint's longest side in source pixels.
int supersampleFactor(const Eigen::Matrix2d& j, int max_factor) {
  const double side = std::max(j.col(0).norm(), j.col(1).norm());
  if (!(side > 1.0)) return 1;
  return static_cast<int>(std::min<double>(max_factor, std::ceil(side - 1e-9)));
}

// The footprint varies slowly: one Jacobian per span, at a pixel with a preimage. Returns the
// supersampling factor and fills jac (row-major d source / d target).
int spanFootprint(const CoordinateKernel& kernel, int y, int x0, int n, const float* sx, const float* sy,
                  const unsigned char* valid, int max_ss, float jac[4]) {
  for (int i = n / 2, tries = 0; tries < n; ++tries, i = (i + 1) % n) {
    if (!valid[i]) continue;
    Eigen::Matrix2d j;
    if (!kernel.sourceJacobian(Eigen::Vector2d(x0 + i + 0.5, y + 0.5), Eigen::Vector2d(sx[i], sy[i]), j))
      return 1;
    jac[0] = static_cast<float>(j(0, 0));
    jac[1] = static_cast<float>(j(0, 1));
    jac[2] = static_cast<float>(j(1, 0));
    jac[3] = static_cast<float>(j(1, 1));
    return supersampleFactor(j, max_ss);
  }
  return 1;
}

void checkOptions(const WarpOptions& options) {
  if (!(options.coordinates.residual_tolerance_px > 0.0) || !std::isfinite(options.coordinates.residual_tolerance_px))
    throw std::invalid_argument("warp residual tolerance must be a positive number of pixels");
  if (!(options.coordinates.seed_tolerance_px > 0.0) || !std::isfinite(options.coordinates.seed_tolerance_px))
    throw std::invalid_argument("warp seed tolerance must be a positive number of pixels");
  if (!(options.coordinates.certify_tolerance_px >= 0.0) || !std::isfinite(options.coordinates.certify_tolerance_px))
    throw std::invalid_argument("warp certify tolerance must be a number of pixels ≥ 0");
  if (options.threads < 0) throw std::invalid_argument("warp thread count must not be negative");
}

// Channel c's premultiplied sample v_c came with its own alpha a_c; the pixel's alpha is the
// least of them, a, and the colour is premultiplied by that: v_c · a / a_c (the attributed
// renderer's layer rule, so no channel shows beyond the others at the frame's edge).
template <class T>
T rescale(T v, T a, T a_c) {
  if constexpr (std::is_floating_point_v<T>) {
    return a_c > T(0) ? v * (a / a_c) : T(0);
  } else {
    if (a_c == 0) return 0;
    const std::uint64_t num = static_cast<std::uint64_t>(v) * a + a_c / 2;
    return static_cast<T>(std::min<std::uint64_t>(num / a_c, std::numeric_limits<T>::max()));
  }
}

// Out's pixels from the channels' spans: colour channel c from span c (the first span for a
// channel without a camera), alpha the least of the spans' alphas. Typed, so the compiler
// keeps the samples in registers instead of calling memcpy per sample.
template <class T>
long long mergeChannels(const unsigned char* const* spans, int count, int channels, unsigned char* dst, int n) {
  const int alpha = channels - 1;
  long long transparent = 0;
  const T* from[4];
  for (int c = 0; c < 4; ++c) from[c] = reinterpret_cast<const T*>(spans[c < count ? c : 0]);
  T* out = reinterpret_cast<T*>(dst);
  for (int i = 0; i < n; ++i) {
    const int p = i * channels;
    T least = from[0][p + alpha];
    for (int k = 1; k < count; ++k) least = std::min(least, from[k][p + alpha]);
    for (int c = 0; c < alpha; ++c) {
      const T a_c = from[c][p + alpha];
      out[p + c] = a_c == least ? from[c][p + c] : rescale(from[c][p + c], least, a_c);
    }
    out[p + alpha] = least;
    transparent += !(least > T(0));
  }
  return transparent;
}

}  // namespace

void warpChannels(const ConstImageView& source, const std::vector<Camera>& channel_cameras,
                  const ImageView& out, const WarpOptions& options, WarpSummary* summary) {
  const AnalysedCameras analysed(channel_cameras);
  warpChannels(source, analysed.cameras(), out, options, summary);
}

void warpChannels(const ConstImageView& source, const std::vector<AnalysedCamera>& channel_cameras,
                  const ImageView& out, const WarpOptions& options, WarpSummary* summary) {
  const auto start = std::chrono::steady_clock::now();
  WarpSummary local;
  WarpSummary& report = summary ? *summary : local;
  report = WarpSummary{};
  checkOptions(options);
  const int colour_channels = source.alpha_channel >= 0 ? source.channels - 1 : source.channels;
  const int count = static_cast<int>(channel_cameras.size());
  if (count < 1 || count > colour_channels || (source.alpha_channel >= 0 && source.alpha_channel != source.channels - 1))
    throw std::invalid_argument("warpChannels needs one camera per colour channel, at most the photo's " +
                                std::to_string(colour_channels) + ", and alpha (if any) last");
  const bool out_alpha = out.alpha_channel >= 0;
  if (out_alpha ? out.channels != colour_channels + 1 || out.alpha_channel != colour_channels
                : out.channels != colour_channels)
    throw std::invalid_argument("warpChannels writes the photo's colour channels, and alpha last if any");
  // Each channel's kernel samples into a span of its own, laid out like `merged`: out's colour
  // channels and an alpha last. Without an alpha in `out`, each span is merged into a scratch
  // span of that layout and its colours copied: the premultiplied colour, composited over
  // black, as warpImage writes such an output.
  ImageView merged = out;
  merged.channels = colour_channels + 1;
  merged.alpha_channel = colour_channels;
  const int pixel_bytes = merged.pixelBytes();
  const int sample_bytes = pixel_bytes / merged.channels;
  std::vector<std::unique_ptr<CoordinateKernel>> kernels;
  std::string names;
  const FrameSize source_px{source.width, source.height}, out_px{out.width, out.height};
  for (const AnalysedCamera& analysed : channel_cameras) {
    const Camera& camera = analysed.camera;
    const CameraStructure& structure = analysed.structure;
    camera.validate();
    checkCamera(camera, structure);
    if (structure.degenerate) throw std::invalid_argument("a channel's camera has a zero position denominator");
    KernelChoice choice = makeCoordinateKernel(camera, structure, source_px, out_px, options.coordinates, options.threads);
    names += (names.empty() ? "" : "+") + choice.name;
    if (!choice.note.empty()) report.note += (report.note.empty() ? "" : "; ") + choice.note;
    kernels.push_back(std::move(choice.kernel));
  }
  report.kernel = "per-channel " + names;
  const int max_ss = std::max(1, options.max_supersample);
  std::atomic<long long> transparent{0}, newton{0};
  ParallelOptions po;
  po.threads = options.threads;
  po.progress = options.progress;
  po.band_rows = kBandRows;
  // Where every channel's position is interior, each colour channel is sampled alone straight
  // into `out` (SpanSampler::runChannelsInterior: the same integers the channel's full sample
  // gives) and alpha is full, which is what the merge gives there: a third of the taps and no
  // merge. Only for 8-bit photos without alpha (an alpha would rescale the colours).
  // Without an alpha in `out` the direct sampler writes into the band's scratch span (its
  // view here only fixes the layout; runChannelsInterior is given where to write).
  std::vector<unsigned char> layout_only;
  ImageView direct_view = out;
  if (!out_alpha) {
    layout_only.assign(static_cast<size_t>(kSpanPixels) * static_cast<size_t>(pixel_bytes), 0);
    direct_view = merged;
    direct_view.data = layout_only.data();
    direct_view.width = kSpanPixels;
    direct_view.height = 1;
    direct_view.row_bytes = static_cast<std::ptrdiff_t>(kSpanPixels) * pixel_bytes;
  }
  const SpanSampler direct(source, direct_view, options.filter, !options.coordinates.scalar_only,
                           options.coordinates.allow_avx512, options.edge);
  SpanSampler::ChannelShift shifts[4];
  for (int k = 0; k < count; ++k)
    if (const auto offset = kernels[static_cast<size_t>(k)]->wholePixelOffset())
      shifts[k] = {true, (*offset)[0], (*offset)[1]};
  const bool direct_ok = out.type == PixelType::UInt8 && source.alpha_channel < 0 && options.filter != Filter::Bicubic;
  const bool finished = parallelForRows(out_px.height, po, [&](int y0, int y1) {
    long long band_transparent = 0, band_newton = 0;
    alignas(32) float sx[4][kSpanPixels], sy[4][kSpanPixels];
    unsigned char valid[4][kSpanPixels];
    int ss[4] = {1, 1, 1, 1};
    float jac[4][4];
    // One span per channel, in merged's layout; each channel's sampler writes its own.
    std::vector<unsigned char> scratch(static_cast<size_t>(count) * kSpanPixels * static_cast<size_t>(pixel_bytes));
    std::vector<SpanSampler> band_samplers;
    std::vector<unsigned char> merged_span(out_alpha ? 0 : static_cast<size_t>(kSpanPixels) * static_cast<size_t>(pixel_bytes));
    for (int k = 0; k < count; ++k) {
      ImageView span = merged;
      span.data = scratch.data() + static_cast<size_t>(k) * kSpanPixels * static_cast<size_t>(pixel_bytes);
      span.width = kSpanPixels;
      span.height = 1;
      span.row_bytes = static_cast<std::ptrdiff_t>(kSpanPixels) * pixel_bytes;
      band_samplers.emplace_back(source, span, options.filter, !options.coordinates.scalar_only,
                                 options.coordinates.allow_avx512, options.edge);
    }
    std::vector<RowState> states(static_cast<size_t>(count) * kBandRows);
    const unsigned char* spans[4] = {nullptr, nullptr, nullptr, nullptr};
    for (int k = 0; k < count; ++k) spans[k] = scratch.data() + static_cast<size_t>(k) * kSpanPixels * static_cast<size_t>(pixel_bytes);
    for (int x0 = 0; x0 < out_px.width; x0 += kSpanPixels) {
      const int n = std::min(kSpanPixels, out_px.width - x0);
      for (int y = y0; y < y1; ++y) {
        bool one_tap = true;
        for (int k = 0; k < count; ++k) {
          const CoordinateKernel& kernel = *kernels[static_cast<size_t>(k)];
          band_newton += kernel.span(y, x0, n, sx[k], sy[k], valid[k], states[static_cast<size_t>(k) * kBandRows + static_cast<size_t>(y - y0)]);
          ss[k] = 1;
          std::fill(jac[k], jac[k] + 4, 0.0f);
          jac[k][0] = jac[k][3] = 1.0f;
          if (options.antialias) ss[k] = spanFootprint(kernel, y, x0, n, sx[k], sy[k], valid[k], max_ss, jac[k]);
          one_tap = one_tap && ss[k] == 1;
        }
        // Where the span's pixel i goes in `merged`'s layout: out's row, or the scratch span.
        unsigned char* const merged_row =
            out_alpha ? static_cast<unsigned char*>(out.row(y)) + static_cast<std::ptrdiff_t>(x0) * pixel_bytes
                      : merged_span.data();
        // Pixels at + 0 … at + m − 1 of the span: each channel's own sample, then the merge.
        const auto sampleAndMerge = [&](int at, int m) {
          for (int k = 0; k < count; ++k)
            band_samplers[static_cast<size_t>(k)].run(0, 0, m, sx[k] + at, sy[k] + at, valid[k] + at, ss[k], jac[k]);
          unsigned char* dst = merged_row + static_cast<std::ptrdiff_t>(at) * pixel_bytes;
          if (out.type == PixelType::UInt8) band_transparent += mergeChannels<std::uint8_t>(spans, count, merged.channels, dst, m);
          else if (out.type == PixelType::UInt16) band_transparent += mergeChannels<std::uint16_t>(spans, count, merged.channels, dst, m);
          else band_transparent += mergeChannels<float>(spans, count, merged.channels, dst, m);
        };
        int at = 0;
        if (direct_ok && one_tap) {
          // The interior pixels directly, and groups a channel leaves wholly (a strong
          // aberration's margins: transparent); only a group of eight with a pixel on the
          // frame's edge takes the merge.
          while (at < n) {
            const float* xs[4] = {sx[0] + at, sx[1] + at, sx[2] + at, sx[3] + at};
            const float* ys[4] = {sy[0] + at, sy[1] + at, sy[2] + at, sy[3] + at};
            const unsigned char* vs[4] = {valid[0] + at, valid[1] + at, valid[2] + at, valid[3] + at};
            const int done = direct.runChannelsInterior(y, x0 + at, n - at, count, xs, ys, vs, shifts,
                                                        &band_transparent,
                                                        merged_row + static_cast<std::ptrdiff_t>(at) * pixel_bytes);
            if (done < 0) break;
            at += done;
            if (at == n) break;
            const int m = std::min(8, n - at);
            sampleAndMerge(at, m);
            at += m;
          }
        }
        if (at < n) sampleAndMerge(0, n);
        if (!out_alpha) {
          unsigned char* o = static_cast<unsigned char*>(out.row(y)) + static_cast<std::ptrdiff_t>(x0) * out.pixelBytes();
          const size_t colour_bytes = static_cast<size_t>(colour_channels) * static_cast<size_t>(sample_bytes);
          for (int i = 0; i < n; ++i, o += colour_bytes)
            std::memcpy(o, merged_span.data() + static_cast<size_t>(i) * static_cast<size_t>(pixel_bytes), colour_bytes);
        }
      }
    }
    transparent += band_transparent;
    newton += band_newton;
  });
  report.transparent_pixels = transparent.load();
  report.newton_pixels = newton.load();
  report.render_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  report.cancelled = !finished;
}

void warpImage(const ConstImageView& source, const Camera& camera, const ImageView& out,
               const WarpOptions& options, WarpSummary* summary) {
  const CameraStructure structure = validatedStructure(camera);
  warpImage(source, AnalysedCamera{camera, structure}, out, options, summary);
}

void warpImage(const ConstImageView& source, const AnalysedCamera& analysed, const ImageView& out,
               const WarpOptions& options, WarpSummary* summary) {
  const Camera& camera = analysed.camera;
  const CameraStructure& structure = analysed.structure;
  const auto start = std::chrono::steady_clock::now();
  WarpSummary local;
  WarpSummary& report = summary ? *summary : local;
  report = WarpSummary{};

  camera.validate();
  checkOptions(options);
  const SpanSampler sampler(source, out, options.filter, !options.coordinates.scalar_only,
                            options.coordinates.allow_avx512,
                            options.edge);  // validates both images
  checkCamera(camera, structure);

  const FrameSize source_px{source.width, source.height};
  const FrameSize out_px{out.width, out.height};
  const auto finishTiming = [&] {
    report.render_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  };
  if (structure.degenerate) {
    for (int y = 0; y < out.height; ++y)
      std::memset(out.row(y), 0, static_cast<size_t>(out.width) * static_cast<size_t>(out.pixelBytes()));
    report.kernel = "degenerate";
    report.transparent_pixels = static_cast<long long>(out_px.width) * out_px.height;
    report.note = "the camera's position denominator is zero everywhere";
    finishTiming();
    return;
  }

  const KernelChoice choice =
      makeCoordinateKernel(camera, structure, source_px, out_px, options.coordinates, options.threads);
  report.kernel = choice.name;
  report.note = choice.note;
  report.certified_share = choice.kernel->certifiedShare();
  const CoordinateKernel& kernel = *choice.kernel;
  const std::optional<std::array<int, 2>> offset = kernel.wholePixelOffset();
  if (offset && report.kernel != "identity") report.kernel = "translation-copy";
  const int max_ss = std::max(1, options.max_supersample);

  std::atomic<long long> transparent{0}, newton{0};
  ParallelOptions po;
  po.threads = options.threads;
  po.progress = options.progress;
  // Tiles of one span × band rows: a rotated or curved map reads a source region of about the
  // tile's size, which then stays in L1/L2 and in the TLB; a whole 6000-pixel output row
  // would sweep hundreds of source rows (several times slower even for a small rotation).
  po.band_rows = kBandRows;
  const bool finished = parallelForRows(out_px.height, po, [&](int y0, int y1) {
    long long band_transparent = 0, band_newton = 0;
    alignas(32) float sx[kSpanPixels], sy[kSpanPixels];
    unsigned char valid[kSpanPixels];
    if (offset) {
      for (int y = y0; y < y1; ++y)
        band_transparent += copyRow(source, y + (*offset)[1], out, y, (*offset)[0]);
      transparent += band_transparent;
      return;
    }
    RowState row_states[kBandRows];  // each row's spans still go left to right (coordinates.h)
    // Span-major: one span column goes down the band's rows, then the next.
    // No software prefetch here (source lines extrapolated from the last rows, or output lines
    // a few rows down): with the AVX2 samplers it costs more than it saves. The 8-bit bilinear
    // samplers prefetch instead, from the taps they have just read, the same lines a few rows
    // down (span_sampler_avx2.h, prefetchRowsAhead): exact addresses, no extrapolation.
    for (int x0 = 0; x0 < out_px.width; x0 += kSpanPixels) {
      const int n = std::min(kSpanPixels, out_px.width - x0);
      for (int y = y0; y < y1; ++y) {
        RowState& row_state = row_states[y - y0];
        band_newton += kernel.span(y, x0, n, sx, sy, valid, row_state);
        int ss = 1;
        float jac[4] = {1, 0, 0, 1};
        if (options.antialias) ss = spanFootprint(kernel, y, x0, n, sx, sy, valid, max_ss, jac);
        band_transparent += sampler.run(y, x0, n, sx, sy, valid, ss, jac);
      }
    }
    transparent += band_transparent;
    newton += band_newton;
  });
  report.transparent_pixels = transparent.load();
  report.newton_pixels = newton.load();
  finishTiming();
  report.cancelled = !finished;
}

// How far beyond the photo's rows a position can still reach it through a filter's taps, and
// the margin a banded warp's window keeps around the rows its positions fall in.
constexpr float kReach = 4.0f;

struct BandWarp::State {
  FrameSize source_px, out_px;
  WarpOptions options;
  bool degenerate = false;
  std::unique_ptr<CoordinateKernel> kernel;
  std::optional<std::array<int, 2>> offset;  // whole-pixel translation: rows are copied
};

BandWarp::BandWarp(const Camera& camera, FrameSize source_px, FrameSize out_px,
                   const WarpOptions& options)
    : state_(std::make_unique<State>()) {
  camera.validate();
  checkOptions(options);
  if (options.antialias)
    throw std::invalid_argument("a banded warp does not anti-alias (its taps leave the band's rows)");
  if (source_px.width < 1 || source_px.height < 1 || out_px.width < 1 || out_px.height < 1)
    throw std::invalid_argument("a banded warp needs non-empty source and output frames");
  const CameraStructure structure = analyseStructure(camera);
  checkCamera(camera, structure);
  State& st = *state_;
  st.source_px = source_px;
  st.out_px = out_px;
  st.options = options;
  if (structure.degenerate) {
    st.degenerate = true;
    kernel_name_ = "degenerate";
    return;
  }
  KernelChoice choice =
      makeCoordinateKernel(camera, structure, source_px, out_px, options.coordinates, options.threads);
  kernel_name_ = choice.name;
  st.kernel = std::move(choice.kernel);
  st.offset = st.kernel->wholePixelOffset();
  if (st.offset && kernel_name_ != "identity") kernel_name_ = "translation-copy";
}

BandWarp::~BandWarp() = default;

BandWarp::Rows BandWarp::sourceRows(int y0, int y1, bool* inside) const {
  const State& st = *state_;
  y0 = std::max(y0, 0);
  y1 = std::min(y1, st.out_px.height);
  if (inside) *inside = false;
  if (st.degenerate || y1 <= y0) return {};
  const int height = st.source_px.height;
  if (st.offset) {
    const int dx = (*st.offset)[0], dy = (*st.offset)[1];
    const int first = std::max(0, y0 + dy), last = std::min(height, y1 + dy);
    if (inside)
      *inside = y0 + dy >= 0 && y1 + dy <= height && dx >= 0 && st.out_px.width + dx <= st.source_px.width;
    return first < last ? Rows{first, last} : Rows{};
  }
  const float x_min = 2.5f, y_min = 2.5f, x_max = static_cast<float>(st.source_px.width) - 2.5f,
              y_max = static_cast<float>(height) - 2.5f;
  std::atomic<bool> all_inside{true};
  // A tap reads rows floor(sy − ½) − 1 … floor(sy − ½) + 2 (bicubic; bilinear and nearest
  // fewer): positions further than kReach beyond the frame read nothing, and the window keeps
  // kReach rows of margin around the rest.
  std::atomic<int> lowest{std::numeric_limits<int>::max()}, highest{std::numeric_limits<int>::min()};
  ParallelOptions po;
  po.threads = st.options.threads;
  po.band_rows = kBandRows;
  parallelForRows(y1 - y0, po, [&](int r0, int r1) {
    alignas(32) float sx[kSpanPixels], sy[kSpanPixels];
    unsigned char valid[kSpanPixels];
    float lo = std::numeric_limits<float>::infinity(), hi = -lo;
    for (int y = y0 + r0; y < y0 + r1; ++y) {
      RowState state;
      for (int x0 = 0; x0 < st.out_px.width; x0 += kSpanPixels) {
        const int n = std::min(kSpanPixels, st.out_px.width - x0);
        st.kernel->span(y, x0, n, sx, sy, valid, state);
        bool span_inside = true;
        for (int i = 0; i < n; ++i) {
          if (valid[i] && sy[i] >= -kReach && sy[i] <= static_cast<float>(height) + kReach)
            lo = std::min(lo, sy[i]), hi = std::max(hi, sy[i]);
          span_inside = span_inside && valid[i] && sx[i] >= x_min && sx[i] <= x_max &&
                        sy[i] >= y_min && sy[i] <= y_max;
        }
        if (!span_inside) all_inside = false;
      }
    }
    if (!(lo <= hi)) return;
    const int first = static_cast<int>(std::floor(lo)) - static_cast<int>(kReach);
    const int last = static_cast<int>(std::floor(hi)) + static_cast<int>(kReach) + 1;
    for (int v = lowest.load(); first < v && !lowest.compare_exchange_weak(v, first);) {}
    for (int v = highest.load(); last > v && !highest.compare_exchange_weak(v, last);) {}
  });
  if (inside) *inside = all_inside.load();
  const int first = std::max(0, lowest.load()), last = std::min(height, highest.load());
  return first < last ? Rows{first, last} : Rows{};
}

long long BandWarp::render(const ConstImageView& window, int window_first, int y0, int y1,
                           const ImageView& out) const {
  const State& st = *state_;
  if (out.width != st.out_px.width || out.height != y1 - y0 || y0 < 0 || y1 > st.out_px.height ||
      window.width != st.source_px.width || window_first < 0 ||
      window_first + window.height > st.source_px.height)
    throw std::invalid_argument("BandWarp::render: the band or the window does not fit the frames");
  const size_t row_bytes = static_cast<size_t>(out.width) * static_cast<size_t>(out.pixelBytes());
  if (st.degenerate) {
    for (int y = 0; y < out.height; ++y) std::memset(out.row(y), 0, row_bytes);
    return finishEdge(st.options.edge, out, static_cast<long long>(out.width) * out.height);
  }
  // The window's edges that are not the photo's: a tap beyond them would read a row the
  // window does not hold, so the render refuses rather than sample black there.
  const int window_end = window_first + window.height;
  const bool open_top = window_first > 0, open_bottom = window_end < st.source_px.height;
  if (window.height == 0) {
    // No row read: every position lies beyond the photo's reach (sourceRows was empty), where
    // the sampler writes 0 in every channel.
    for (int y = 0; y < out.height; ++y) std::memset(out.row(y), 0, row_bytes);
    return finishEdge(st.options.edge, out, static_cast<long long>(out.width) * out.height);
  }
  const SpanSampler sampler(window, out, st.options.filter, !st.options.coordinates.scalar_only,
                            st.options.coordinates.allow_avx512, st.options.edge);
  std::atomic<long long> transparent{0};
  ParallelOptions po;
  po.threads = st.options.threads;
  po.band_rows = kBandRows;
  parallelForRows(y1 - y0, po, [&](int r0, int r1) {
    long long band_transparent = 0;
    alignas(32) float sx[kSpanPixels], sy[kSpanPixels];
    unsigned char valid[kSpanPixels];
    const float shift = static_cast<float>(window_first);
    for (int r = r0; r < r1; ++r) {
      const int y = y0 + r;
      if (st.offset) {
        band_transparent += copyRow(window, y + (*st.offset)[1] - window_first, out, r, (*st.offset)[0]);
        continue;
      }
      RowState state;
      for (int x0 = 0; x0 < st.out_px.width; x0 += kSpanPixels) {
        const int n = std::min(kSpanPixels, st.out_px.width - x0);
        st.kernel->span(y, x0, n, sx, sy, valid, state);
        for (int i = 0; i < n; ++i) {
          if (valid[i] && (open_top || open_bottom)) {
            const float tap = std::floor(sy[i] - 0.5f);  // bicubic reads tap − 1 … tap + 2
            if ((open_top && tap - 1.0f < shift && sy[i] > -kReach) ||
                (open_bottom && tap + 2.0f >= static_cast<float>(window_end) &&
                 sy[i] < static_cast<float>(st.source_px.height) + kReach))
              throw std::invalid_argument("BandWarp::render: the window does not hold the rows the band reads");
          }
          // Exact in float: sy and the shift are multiples of sy's ulp (|sy| < 2²⁴).
          sy[i] -= shift;
        }
        band_transparent += sampler.run(r, x0, n, sx, sy, valid);
      }
    }
    transparent += band_transparent;
  });
  return finishEdge(st.options.edge, out, transparent.load());
}

long long finishEdge(EdgeMode edge, const ImageView& image, long long transparent) {
  if (edge != EdgeMode::Black || image.alpha_channel < 0)
    return edge == EdgeMode::Black ? 0 : transparent;
  const int size = pixelTypeSize(image.type);
  const std::size_t pixel = static_cast<std::size_t>(image.pixelBytes());
  const std::size_t at =
      static_cast<std::size_t>(image.alpha_channel) * static_cast<std::size_t>(size);
  const float full = pixelTypeFullScale(image.type);
  for (int y = 0; y < image.height; ++y) {
    auto* row = static_cast<unsigned char*>(image.row(y)) + at;
    for (int x = 0; x < image.width; ++x, row += pixel) switch (image.type) {
        case PixelType::UInt8:
          *row = 255;
          break;
        case PixelType::UInt16: {
          const std::uint16_t v = 65535;
          std::memcpy(row, &v, 2);
          break;
        }
        case PixelType::Float:
          std::memcpy(row, &full, 4);
          break;
      }
  }
  return 0;
}

ImageF warpImage(const ImageF& source, const Camera& camera, const WarpOptions& options,
                 WarpSummary* summary) {
  const CameraStructure structure = validatedStructure(camera);
  return warpImage(source, AnalysedCamera{camera, structure}, options, summary);
}

ImageF warpImage(const ImageF& source, const AnalysedCamera& analysed, const WarpOptions& options,
                 WarpSummary* summary) {
  const Camera& camera = analysed.camera;
  checkSourceImage(source);
  camera.validate();
  const FrameSize out_px = warpOutputSize(camera, options);
  const int channels = source.alpha_channel >= 0 ? source.channels : source.channels + 1;
  const int alpha = source.alpha_channel >= 0 ? source.alpha_channel : source.channels;
  ImageF out(out_px.width, out_px.height, channels, alpha);
  WarpSummary local;
  WarpSummary& report = summary ? *summary : local;
  warpImage(viewOf(source), analysed, viewOf(out), options, &report);
  if (report.cancelled) return ImageF{};
  return out;
}

}  // namespace artcam
