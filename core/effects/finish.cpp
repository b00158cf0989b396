// SPDX-License-Identifier: Apache-2.0
#include "core/effects/finish.h"

#include "core/util/module_path.h"

#include <dlfcn.h>
#if defined(__SSE__)
#include <xmmintrin.h>
#endif

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <vector>

namespace artcam {
namespace {

// G'MIC holds the image as planar float, and its filters make a few copies of it.
constexpr double kMaxFinishPixels = 100e6;
constexpr const char* kModuleName = "libartcam_finish_gmic.so";

using Apply = unsigned (*)(const char*, int, float*, unsigned, unsigned, unsigned);

struct Module {
  Apply apply = nullptr;
  std::string why;  // when apply is null
};

// libgmic's load sets flush-to-zero and denormals-are-zero in this thread (finish_gmic.cpp says
// why): the float mode is put back as it was.
const Module& module() {
  static const Module loaded = [] {
    Module m;
    const char* forced = std::getenv("ARTCAM_FINISH_MODULE");
    const std::string path =
        forced && *forced ? std::string(forced) : engineModuleDirectory() + kModuleName;
#if defined(__SSE__)
    const unsigned mode = _mm_getcsr();
#endif
    void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
#if defined(__SSE__)
    _mm_setcsr(mode);
#endif
    if (!handle) {
      const char* error = dlerror();
      m.why = "the G'MIC module " + path + " cannot be loaded (" +
              (error ? error : "unknown error") + "); reinstall ARTcam Studio";
      return m;
    }
    m.apply = reinterpret_cast<Apply>(dlsym(handle, "artcam_gmic_apply"));
    if (!m.apply) m.why = "the G'MIC module " + path + " is from another build; reinstall it";
    return m;
  }();
  return loaded;
}

template <class T>
float sampleAt(const void* row, size_t i) {
  return static_cast<float>(static_cast<const T*>(row)[i]);
}

float sampleOf(const ImageView& image, const void* row, size_t i) {
  return image.type == PixelType::UInt8    ? sampleAt<uint8_t>(row, i)
         : image.type == PixelType::UInt16 ? sampleAt<uint16_t>(row, i)
                                           : sampleAt<float>(row, i);
}

}  // namespace

const std::vector<FinishInfo>& finishes() {
  // G'MIC 2.9's own filters, their defaults as its G'MIC-Qt dialogs set them.
  static const std::vector<FinishInfo> table = {
      {"pencil", "pencil strokes in grey (G'MIC sketchbw)", "srand 1 sketchbw", true},
      {"charcoal", "charcoal on paper (G'MIC fx_charcoal)",
       "fx_charcoal 65,70,170,0,1,0,50,70,255,255,255,0,0,0,0,0", false},
      {"painting", "painterly brush strokes (G'MIC fx_painting)", "fx_painting 3,1.5,2,0,0,0,0",
       false},
      {"cartoon", "flat colours and inked edges (G'MIC cartoon)", "cartoon", false},
  };
  return table;
}

const FinishInfo* finishByName(std::string_view name) {
  for (const FinishInfo& f : finishes())
    if (f.name == name) return &f;
  return nullptr;
}

Status applyFinishLinear(ImageF& linear, const StoredEncoding& encoding, std::string_view name) {
  const size_t pixels = static_cast<size_t>(linear.width) * static_cast<size_t>(linear.height);
  encoding.encode(linear.data.data(), pixels, linear.channels, linear.alpha_channel);
  const Status marked = applyFinish(viewOf(linear), name);
  encoding.decode(linear.data.data(), pixels, linear.channels, linear.alpha_channel);
  return marked;
}

Status applyFinish(const ImageView& image, std::string_view name) {
  const FinishInfo* finish = finishByName(name);
  if (!finish) {
    std::string names;
    for (const FinishInfo& f : finishes()) names += (names.empty() ? "" : ", ") + f.name;
    return Status::failure("unknown finish \"" + std::string(name) + "\" (" + names + ")");
  }
  if (image.empty()) return Status::failure("the image is empty");
  if (static_cast<double>(image.width) * image.height > kMaxFinishPixels)
    return Status::failure("the " + finish->name + " finish takes at most 100 megapixels");
  const Module& m = module();
  if (!m.apply) return Status::failure(m.why);
  const int colours = image.alpha_channel >= 0 ? image.channels - 1 : image.channels;
  const float full = pixelTypeFullScale(image.type);
  const size_t w = static_cast<size_t>(image.width), h = static_cast<size_t>(image.height);
  const size_t plane = w * h;
  std::vector<float> planes(plane * static_cast<size_t>(colours));
  // G'MIC's filters expect values 0…255, straight (not premultiplied) colour, planar.
  for (size_t y = 0; y < h; ++y) {
    const void* row = image.row(static_cast<int>(y));
    for (size_t x = 0; x < w; ++x) {
      const size_t i = x * static_cast<size_t>(image.channels);
      const float a =
          image.alpha_channel >= 0
              ? sampleOf(image, row, i + static_cast<size_t>(image.alpha_channel)) / full
              : 1.0f;
      for (int c = 0; c < colours; ++c)
        planes[plane * static_cast<size_t>(c) + y * w + x] =
            a > 0 ? std::clamp(sampleOf(image, row, i + static_cast<size_t>(c)) / full / a, 0.0f,
                               1.0f) *
                        255.0f
                  : 0.0f;
    }
  }
  if (m.apply(finish->gmic.c_str(), finish->random ? 1 : 0, planes.data(), static_cast<unsigned>(w),
              static_cast<unsigned>(h), static_cast<unsigned>(colours)) == 0)
    return Status::failure("the " + finish->name + " finish failed in G'MIC");
  for (size_t y = 0; y < h; ++y) {
    void* row = image.row(static_cast<int>(y));
    for (size_t x = 0; x < w; ++x) {
      const size_t i = x * static_cast<size_t>(image.channels);
      const float a =
          image.alpha_channel >= 0
              ? sampleOf(image, row, i + static_cast<size_t>(image.alpha_channel)) / full
              : 1.0f;
      for (int c = 0; c < colours; ++c) {
        const float v =
            std::clamp(planes[plane * static_cast<size_t>(c) + y * w + x] / 255.0f, 0.0f, 1.0f) * a;
        const size_t k = i + static_cast<size_t>(c);
        if (image.type == PixelType::UInt8)
          static_cast<uint8_t*>(row)[k] = static_cast<uint8_t>(std::lround(v * full));
        else if (image.type == PixelType::UInt16)
          static_cast<uint16_t*>(row)[k] = static_cast<uint16_t>(std::lround(v * full));
        else
          static_cast<float*>(row)[k] = v;
      }
    }
  }
  return Status::success();
}

}  // namespace artcam
