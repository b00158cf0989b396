// SPDX-License-Identifier: Apache-2.0
// Reconstruction filters for the gather warp.
//
// Conventions: pixel (i, j) covers [i, i+1)×[j, j+1) and its value sits at its centre
// (i + 0.5, j + 0.5) (image.h, frames.h). A source point (sx, sy) in pixels is therefore read at
// the continuous index (sx − 0.5, sy − 0.5).
//
// Outside the source every channel, alpha included, is 0 — OpenImageIO's "black" wrap — so a
// bilinear or bicubic tap straddling the border fades in alpha; with EdgeMode::Extend a tap
// outside reads the nearest edge pixel instead (OpenImageIO's "clamp"). Colours are premultiplied
// (image.h), which is what makes mixing with transparent taps correct.
//
// The output has the source's channels, plus alpha appended when the source has none. That
// appended alpha is the filter's coverage: the sum of the weights of taps inside the image,
// 1 in the interior. Alpha is clamped to [0, 1]; colours are not (bicubic may ring, linear
// float keeps it, export clamps).
#pragma once

#include "core/model/image.h"
#include "core/sampling/filter.h"

namespace artcam {

// Throws std::invalid_argument unless `source` is a well-formed 1–4 channel image.
void checkSourceImage(const ImageF& source);

class Sampler {
 public:
  // `edge`: Extend reads the nearest edge pixel for taps outside (filter.h); Black is the
  // caller's (an opaque alpha afterwards) and reads as Transparent here.
  Sampler(const ImageF& source, Filter filter, EdgeMode edge = EdgeMode::Transparent);

  int outputChannels() const { return out_channels_; }
  int outputAlpha() const { return out_alpha_; }

  // Writes outputChannels() values at `out` for the source point (sx, sy) in pixels.
  void sample(double sx, double sy, float* out) const;
  // Writes a transparent pixel (all channels 0).
  void clear(float* out) const;

 private:
  void nearest(double fx, double fy, float* out) const;
  void bilinear(double fx, double fy, float* out) const;
  void bicubic(double fx, double fy, float* out) const;
  // Writes the accumulated sum and coverage as an output pixel.
  void finish(const float* sum, double coverage, float* out) const;

  const ImageF& source_;
  Filter filter_;
  bool extend_;
  int channels_;
  int out_channels_;
  int out_alpha_;
  bool append_alpha_;
};

// The Keys (1981) cubic convolution weights with a = −0.5 (Catmull–Rom) for the taps at
// offsets −1, 0, 1, 2 from floor(f), for the fraction t = f − floor(f). They sum to 1 and
// reproduce polynomials up to degree 2 exactly.
void cubicWeights(double t, double w[4]);

}  // namespace artcam
