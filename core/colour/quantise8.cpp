// SPDX-License-Identifier: Apache-2.0
#include "core/colour/quantise8.h"

#include <cmath>
#include <cstring>
#include <limits>

namespace artcam {

std::uint8_t Quantise8::exact(const Transfer& transfer, double linear) {
  const double e = static_cast<float>(transfer.encode(linear));
  return static_cast<std::uint8_t>(!(e > 0.0) ? 0.0 : e >= 1.0 ? 255.0 : std::floor(e * 255.0 + 0.5));
}

Quantise8::Quantise8(const Transfer& transfer) {
  // Positive doubles order as their bit patterns; q(0) = 0 and q(1) = 255 for every transfer
  // (encode(0) = 0, encode(1) = 1), so each threshold lies in (0, 1].
  const auto bits = [](double v) {
    std::uint64_t b;
    std::memcpy(&b, &v, sizeof b);
    return b;
  };
  const auto value = [](std::uint64_t b) {
    double v;
    std::memcpy(&v, &b, sizeof v);
    return v;
  };
  thresholds_[0] = -std::numeric_limits<double>::infinity();
  std::uint64_t lo = bits(0.0);
  for (int k = 1; k <= 255; ++k) {
    std::uint64_t hi = bits(1.0);  // q(hi) ≥ k; q(lo) < k (lo is the previous threshold's below)
    while (hi - lo > 1) {
      const std::uint64_t mid = lo + (hi - lo) / 2;
      if (exact(transfer, value(mid)) >= k) hi = mid;
      else lo = mid;
    }
    thresholds_[static_cast<size_t>(k)] = value(hi);
    // The next threshold is at or above this one; below it q < k + 1 holds too.
    lo = hi - 1;
  }
  for (int i = 0; i <= kGuessSteps; ++i) {
    const double l = static_cast<double>(i) / kGuessSteps;
    int k = 0;
    while (k < 255 && thresholds_[static_cast<size_t>(k) + 1] <= l) ++k;
    guess_[static_cast<size_t>(i)] = static_cast<std::uint8_t>(k);
  }
}

}  // namespace artcam
