// SPDX-License-Identifier: Apache-2.0
// The G'MIC module, libartcam_finish_gmic.so: the one file that links libgmic, loaded by
// finish.cpp on the first finish. Why a module: Debian's libgmic is built with -ffast-math, so
// loading it sets flush-to-zero and denormals-are-zero in the loading thread's MXCSR (from
// crtfastmath's constructor); linked into the engine, that would change every float result of
// every program using it. The loader restores the mode around dlopen, and G'MIC's own work runs
// in the mode of whoever calls it.
#include <gmic.h>

#include <algorithm>

extern "C" {
// OpenMP's runtime (libgomp, which libgmic itself loads).
int omp_get_max_threads();
void omp_set_num_threads(int threads);

// Runs `pipeline` on one image of `channels` planes of width × height floats (0…255), in place:
// the result's first `channels` planes (a result with fewer repeats its first). Returns the
// result's own channel count, or 0 when G'MIC failed or changed the size. `single_thread`: on one
// OpenMP thread (filters that draw random strokes repeat only so).
__attribute__((visibility("default"))) unsigned artcam_gmic_apply(const char* pipeline,
                                                                  int single_thread, float* planes,
                                                                  unsigned width, unsigned height,
                                                                  unsigned channels) {
  const int threads = omp_get_max_threads();
  if (single_thread) omp_set_num_threads(1);
  unsigned result = 0;
  try {
    gmic_list<float> images;
    gmic_list<char> names;
    images.assign(1);
    images[0].assign(planes, width, height, 1, channels, false);  // a copy: G'MIC reallocates it
    gmic(pipeline, images, names, nullptr, true);
    const gmic_image<float>& out = images[0];
    if (images._width >= 1 && out._width == width && out._height == height && out._spectrum >= 1) {
      const size_t plane = static_cast<size_t>(width) * height;
      for (unsigned c = 0; c < channels; ++c) {
        const float* from = out._data + plane * std::min(c, out._spectrum - 1);
        std::copy(from, from + plane, planes + plane * c);
      }
      result = out._spectrum;
    }
  } catch (...) {
    result = 0;
  }
  if (single_thread) omp_set_num_threads(threads);
  return result;
}
}
