// SPDX-License-Identifier: Apache-2.0
// How a photo's stored values relate to the engine's linear light: the transfer curve or ICC
// profile its reader decoded (core/io/image_io.h says which a file gets).
//
// Why it is here: every render resamples the photo AS STORED (docs/architecture.md, "One
// resampling rule"). The gather warp interpolates the stored 8/16-bit numbers directly; a
// render that holds the photo as linear float (colour and depth effects, layers, `export`, a
// change of pixel type) encodes it back into the stored domain first, interpolates there with
// the same filter, and decodes each sample before any colour arithmetic. So one camera and one
// filter give the same pixels on every path, to the output's quantisation step.
//
// Conventions: interleaved float pixels, premultiplied alpha at `alpha_channel` (-1: none),
// every other channel a colour channel (1 grey or 3 RGB). Premultiplication is kept in the
// domain the values are in, as the stored reader does: encoded = encode(linear / a) · a.
// Pixels with alpha 0 stay 0.
#pragma once

#include "core/colour/transfer.h"

#include <cstddef>
#include <memory>
#include <string>

namespace artcam {

class IccProfile;  // icc_profile.h

class StoredEncoding {
 public:
  // Linear: stored values are linear light (float files, images made in code).
  StoredEncoding() = default;
  static StoredEncoding ofTransfer(const Transfer& transfer);
  // The profile the reader converted through (wins over any transfer).
  static StoredEncoding ofProfile(std::shared_ptr<const IccProfile> profile);

  bool isLinear() const { return !icc_ && transfer_.kind == Transfer::Kind::Linear; }
  std::string describe() const;

  // In place, `pixels` interleaved pixels of `channels` floats; large images on every core.
  void encode(float* data, size_t pixels, int channels, int alpha_channel) const;
  void decode(float* data, size_t pixels, int channels, int alpha_channel) const;

 private:
  void convertRange(float* data, size_t pixels, int channels, int alpha_channel, bool encoding) const;
  void inParallel(float* data, size_t pixels, int channels, int alpha_channel, bool encoding) const;

  struct Tables;
  Transfer transfer_ = Transfer::linear();
  std::shared_ptr<const IccProfile> icc_;
  std::shared_ptr<const Tables> tables_;  // the transfer's curves sampled, for speed
};

}  // namespace artcam
