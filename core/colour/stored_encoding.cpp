// SPDX-License-Identifier: Apache-2.0
#include "core/colour/stored_encoding.h"

#include "core/colour/icc_profile.h"
#include "core/util/parallel.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>
#include <vector>

namespace artcam {

// The curves on [0, 1] sampled at 16384 steps and read linearly in between: sRGB's encode has
// its largest curvature just above its linear toe, where the chord's error is about 1e-6 — a
// three-thousandth of an 8-bit step — against a pow per channel per pixel otherwise. Values
// below 1/64 (where a pure power curve's slope is unbounded: gamma 2.2 has no linear toe) and
// outside [0, 1] (float photos, overshooting filters) take the exact formula.
struct StoredEncoding::Tables {
  static constexpr int kSteps = 16384;
  std::array<float, kSteps + 1> encode{}, decode{};

  explicit Tables(const Transfer& t) {
    for (int i = 0; i <= kSteps; ++i) {
      const double v = static_cast<double>(i) / kSteps;
      encode[static_cast<size_t>(i)] = static_cast<float>(t.encode(v));
      decode[static_cast<size_t>(i)] = static_cast<float>(t.decode(v));
    }
  }
  static float read(const std::array<float, kSteps + 1>& table, float v) {
    const float at = v * kSteps;
    const int i = std::min(kSteps - 1, static_cast<int>(at));
    const float f = at - static_cast<float>(i);
    return table[static_cast<size_t>(i)] + f * (table[static_cast<size_t>(i) + 1] - table[static_cast<size_t>(i)]);
  }
};

StoredEncoding StoredEncoding::ofTransfer(const Transfer& transfer) {
  StoredEncoding e;
  e.transfer_ = transfer;
  if (transfer.kind != Transfer::Kind::Linear) e.tables_ = std::make_shared<const Tables>(transfer);
  return e;
}

StoredEncoding StoredEncoding::ofProfile(std::shared_ptr<const IccProfile> profile) {
  StoredEncoding e;
  e.icc_ = std::move(profile);
  return e;
}

std::string StoredEncoding::describe() const {
  if (icc_) return "ICC: " + icc_->description();
  return transfer_.colourSpaceName();
}

namespace {

constexpr float kTabledFrom = 1.0f / 64.0f;

// Divides the colour channels by alpha (premultiplied → straight), or multiplies them back.
void scaleColour(float* data, size_t pixels, int channels, int alpha, bool divide) {
  if (alpha < 0) return;
  for (size_t p = 0; p < pixels; ++p) {
    float* px = data + p * static_cast<size_t>(channels);
    const float a = px[alpha];
    for (int c = 0; c < channels; ++c) {
      if (c == alpha) continue;
      if (!divide) px[c] *= a;
      else px[c] = a > 0.0f ? px[c] / a : 0.0f;
    }
  }
}

// Through the profile: a grey profile over RGB pixels (a grey photo the renderer replicated to
// RGB) converts each channel as a grey value, which is what the replication means.
void throughProfile(const IccProfile& icc, bool to_working, float* data, size_t pixels,
                    int channels, int alpha) {
  const int colour = channels - (alpha >= 0 ? 1 : 0);
  const auto apply = [&](float* d, size_t n, int c, int a) {
    if (to_working) icc.toWorking(d, n, c, a);
    else icc.fromWorking(d, n, c, a);
  };
  if (colour == icc.colourChannels()) {
    apply(data, pixels, channels, alpha);
    return;
  }
  std::vector<float> grey(pixels);
  for (int c = 0; c < channels; ++c) {
    if (c == alpha) continue;
    for (size_t p = 0; p < pixels; ++p) grey[p] = data[p * static_cast<size_t>(channels) + static_cast<size_t>(c)];
    apply(grey.data(), pixels, 1, -1);
    for (size_t p = 0; p < pixels; ++p) data[p * static_cast<size_t>(channels) + static_cast<size_t>(c)] = grey[p];
  }
}

}  // namespace

void StoredEncoding::convertRange(float* data, size_t pixels, int channels, int alpha_channel,
                                  bool encoding) const {
  scaleColour(data, pixels, channels, alpha_channel, true);
  if (icc_) {
    throughProfile(*icc_, !encoding, data, pixels, channels, alpha_channel);
  } else {
    const auto& table = encoding ? tables_->encode : tables_->decode;
    for (size_t p = 0; p < pixels; ++p) {
      float* px = data + p * static_cast<size_t>(channels);
      for (int c = 0; c < channels; ++c) {
        if (c == alpha_channel) continue;
        const float v = px[c];
        if (v >= kTabledFrom && v <= 1.0f) px[c] = Tables::read(table, v);
        else px[c] = static_cast<float>(encoding ? transfer_.encode(v) : transfer_.decode(v));
      }
    }
  }
  scaleColour(data, pixels, channels, alpha_channel, false);
}

// A photo's worth of pixels on every core, in runs of kRun pixels (the curves and lcms2's
// uncached transforms are pure functions, safe to run side by side).
void StoredEncoding::inParallel(float* data, size_t pixels, int channels, int alpha_channel,
                                bool encoding) const {
  constexpr size_t kRun = 16384;
  const auto run = [&](size_t first, size_t count) {
    float* at = data + first * static_cast<size_t>(channels);
    convertRange(at, count, channels, alpha_channel, encoding);
  };
  if (pixels <= 4 * kRun) {
    run(0, pixels);
    return;
  }
  const int runs = static_cast<int>((pixels + kRun - 1) / kRun);
  ParallelOptions options;
  options.band_rows = 1;
  parallelForRows(runs, options, [&](int r0, int r1) {
    for (int r = r0; r < r1; ++r) {
      const size_t first = static_cast<size_t>(r) * kRun;
      run(first, std::min(kRun, pixels - first));
    }
  });
}

void StoredEncoding::encode(float* data, size_t pixels, int channels, int alpha_channel) const {
  if (!isLinear()) inParallel(data, pixels, channels, alpha_channel, true);
}

void StoredEncoding::decode(float* data, size_t pixels, int channels, int alpha_channel) const {
  if (!isLinear()) inParallel(data, pixels, channels, alpha_channel, false);
}

}  // namespace artcam
