// SPDX-License-Identifier: Apache-2.0
// Linear light to 8-bit stored values through a transfer function, without evaluating it per
// sample: the exact integer that rounding the encoded value gives,
//   q(l) = 0 where !(e > 0), 255 where e ≥ 1, else ⌊255 e + ½⌋, with e = float(encode(l)),
// which is what the writers quantised (image writing's per-sample pow was a quarter of
// `artcam export`'s time on a 24 MP photo). q is monotone in l (every transfer here is), so it is
// the number of thresholds T_k = min{ l : q(l) ≥ k } at or below l; the 255 thresholds are
// found once per transfer by bisecting the doubles' bit patterns against q itself, so the table
// agrees with the formula at every double, NaN and ±∞ included (NaN → 0, +∞ → 255).
#pragma once

#include "core/colour/transfer.h"

#include <algorithm>
#include <array>
#include <cstdint>

namespace artcam {

class Quantise8 {
 public:
  explicit Quantise8(const Transfer& transfer);

  std::uint8_t operator()(double linear) const {
    if (!(linear >= thresholds_[1])) return 0;  // NaN too
    if (linear >= thresholds_[255]) return 255;
    // A first guess from a uniform table over [0, 1], then the exact thresholds either side.
    // linear is in (0, 1) here; the clamp only tells the compiler so.
    int k = guess_[static_cast<size_t>(std::clamp(static_cast<int>(linear * kGuessSteps), 0, kGuessSteps))];
    while (linear >= thresholds_[static_cast<size_t>(k) + 1]) ++k;
    while (linear < thresholds_[static_cast<size_t>(k)]) --k;
    return static_cast<std::uint8_t>(k);
  }

  // The reference: what the table must give, evaluated through the transfer.
  static std::uint8_t exact(const Transfer& transfer, double linear);

 private:
  static constexpr int kGuessSteps = 4096;
  std::array<double, 256> thresholds_{};  // [0] = −∞; [k] the least l with q(l) ≥ k
  std::array<std::uint8_t, kGuessSteps + 1> guess_{};
};

}  // namespace artcam
