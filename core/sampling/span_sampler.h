// SPDX-License-Identifier: Apache-2.0
// The sampling half of the fused warp: reconstruct a span of output pixels from their
// source positions, reading 8-bit, 16-bit or float pixels in place (image_view.h).
//
// Semantics are those of sampling.h, for every pixel type: pixel centres at i + 0.5, taps
// outside the source are 0 in every channel (OpenImageIO's "black"; or the nearest edge pixel,
// EdgeMode::Extend, filter.h), colours premultiplied so
// border taps fade correctly; an output alpha channel appended to a source without one holds
// the coverage (sum of the weights of taps inside); an existing alpha is clamped to [0, full];
// colours are clamped only when stored as integers (rounded to nearest). An output without an
// alpha channel is the premultiplied colour, i.e. composited over black.
//
// Anti-aliasing by supersampling where the map minifies: with a supersampling
// factor n > 1, each output pixel averages n × n filter taps spread over its footprint in the
// source, s + J · (δx, δy) for δ on an n × n grid in [−½, ½]², J = d source / d target.
#pragma once

#include "core/model/image_view.h"
#include "core/sampling/filter.h"

namespace artcam {

class SpanSampler {
 public:
  // dst must have src's type and either src's channels or src's channels + 1 (appended alpha,
  // last) when src has no alpha. Throws std::invalid_argument otherwise. `allow_simd`: take the
  // AVX2 clones where the CPU has it (runtime dispatch, bit-identical to the scalar code): the
  // 8-bit one-tap paths and bicubic (span_sampler_avx2.h, span_sampler_cubic.h), the 16-bit and
  // float one-tap nearest and bilinear of 3 or 4 channels (span_sampler_avx2_wide.h); false
  // keeps the portable scalar code.
  // `allow_avx512`: for RGB bilinear (8-bit, 16-bit, float), the AVX-512 clones
  // (span_sampler_avx512.h, also bit-identical) where the CPU has them; false stops at AVX2
  // (tests compare the two).
  // `edge`: what border taps read (filter.h); Extend clamps them to the edge in the border
  // paths only, so the interior code and its SIMD clones are the same for every mode. Black is
  // the caller's (an opaque alpha after the render): the sampler reads it as Transparent.
  SpanSampler(const ConstImageView& src, const ImageView& dst, Filter filter,
              bool allow_simd = true, bool allow_avx512 = true,
              EdgeMode edge = EdgeMode::Transparent);
  bool usesSimd() const { return simd_; }
  bool usesAvx512() const { return avx512_; }

  // Writes output pixels x0 … x0 + n − 1 of row y. `jacobian` (row-major 2×2, d source / d
  // target) is read only when supersample > 1. Returns the count of transparent pixels
  // written (alpha, or coverage when there is no alpha, ≤ 0).
  long long run(int y, int x0, int n, const float* sx, const float* sy, const unsigned char* valid,
                int supersample = 1, const float* jacobian = nullptr) const;

  // The colour channels of the span each from positions of its own, for cameras that move
  // each channel on its own (chromatic aberration): colour channel c from sx[k], sy[k] with
  // k = c < count ? c : 0, alpha full. 8-bit nearest or bilinear of a photo without alpha into
  // one with alpha appended, every pixel interior for every camera (valid, all taps inside):
  // there each channel gets exactly what run() would write from its camera's positions.
  // Returns how many of the span's first pixels it wrote: up to the first pixel (or, on the
  // AVX2 path, the first group of eight) that is not interior, which the caller writes another
  // way before calling again for the rest; −1 when the sampler is of another kind. The AVX2
  // path also writes groups of eight where some camera has no tap inside for any of them
  // (transparent, as the merge makes them), adding them to `transparent`. `out`, if given, is
  // where the span's first pixel goes (in dst's layout) instead of dst's pixel (x0, y).
  // `shift` (optional, `count` entries): for a camera k whose positions are whole pixels moved
  // by shift[k] (CoordinateKernel::wholePixelOffset, as lateral chromatic aberration leaves
  // green), its channel is read straight from the source row; its sx[k], sy[k] must still hold
  // those positions (the scalar tail reads them).
  struct ChannelShift {
    bool whole = false;
    int dx = 0, dy = 0;
  };
  int runChannelsInterior(int y, int x0, int n, int count, const float* const* sx,
                          const float* const* sy, const unsigned char* const* valid,
                          const ChannelShift* shift = nullptr, long long* transparent = nullptr,
                          unsigned char* out = nullptr) const;

  struct Context {
    const unsigned char* src = nullptr;
    std::ptrdiff_t src_row = 0;
    int width = 0, height = 0;
    int src_alpha = -1;     // alpha index in the source, or -1
    int out_channels = 0;
    int out_alpha = -1;     // alpha index in the output, or -1
    bool append_alpha = false;
    float full = 1.0f;      // the value of alpha 1
    bool extend = false;    // border taps read the nearest edge pixel (EdgeMode::Extend)
  };
  using SpanFn = long long (*)(const Context&, unsigned char* out, int n, const float* sx,
                               const float* sy, const unsigned char* valid, int supersample,
                               const float* jacobian);

 private:
  Context context_;
  ImageView dst_;
  SpanFn fn_ = nullptr;
  Filter filter_ = Filter::Bilinear;
  bool u8_ = false;
  bool simd_ = false;
  bool avx512_ = false;
};

}  // namespace artcam
