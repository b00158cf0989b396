// SPDX-License-Identifier: Apache-2.0
// What the CPU offers, asked once per process. The build keeps the x86-64 baseline and every
// SIMD clone is picked at run time; the kernels that pick one ask here (false off x86-64).
// Inline, so a check inside a loop (the piecewise rasteriser asks once per row) costs a load
// and a branch, not a call.
#pragma once

namespace artcam {

#if defined(__x86_64__)
inline bool cpuHasAvx2() {
  static const bool has = __builtin_cpu_supports("avx2");
  return has;
}

inline bool cpuHasFma() {
  static const bool has = __builtin_cpu_supports("fma");
  return has;
}

inline bool cpuHasAvx512f() {
  static const bool has = __builtin_cpu_supports("avx512f");
  return has;
}

// AVX-512 with byte and word lanes and masked 128/256-bit stores (BW, VL): every AVX-512 CPU
// since Skylake-SP.
inline bool cpuHasAvx512bwvl() {
  static const bool has = __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") &&
                          __builtin_cpu_supports("avx512vl");
  return has;
}
#else
inline bool cpuHasAvx2() { return false; }
inline bool cpuHasFma() { return false; }
inline bool cpuHasAvx512f() { return false; }
inline bool cpuHasAvx512bwvl() { return false; }
#endif

}  // namespace artcam
