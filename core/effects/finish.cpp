// SPDX-License-Identifier: Apache-2.0
#include "core/effects/finish.h"

#include <gmic.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

// OpenMP's runtime calls (libgomp, which libgmic loads), declared here rather than through
// <omp.h> so core is not compiled with -fopenmp.
extern "C" {
int omp_get_max_threads();
void omp_set_num_threads(int threads);
}

namespace artcam {
namespace {

// One thread for G'MIC while it lives (the seeded finishes), then the count it had.
class OneOpenMpThread {
 public:
  explicit OneOpenMpThread(bool active) : active_(active), threads_(omp_get_max_threads()) {
    if (active_) omp_set_num_threads(1);
  }
  ~OneOpenMpThread() {
    if (active_) omp_set_num_threads(threads_);
  }
  OneOpenMpThread(const OneOpenMpThread&) = delete;
  OneOpenMpThread& operator=(const OneOpenMpThread&) = delete;

 private:
  bool active_;
  int threads_;
};

// G'MIC holds the image as planar float, and its filters make a few copies of it.
constexpr double kMaxFinishPixels = 100e6;

template <class T>
float sampleAt(const void* row, size_t i) {
  return static_cast<float>(static_cast<const T*>(row)[i]);
}

}  // namespace

const std::vector<FinishInfo>& finishes() {
  // G'MIC 2.9's own filters, their defaults as its G'MIC-Qt dialogs set them.
  static const std::vector<FinishInfo> table = {
      {"pencil", "pencil strokes in grey (G'MIC sketchbw)", "srand 1 sketchbw", true},
      {"charcoal", "charcoal on paper (G'MIC fx_charcoal)",
       "fx_charcoal 65,70,170,0,1,0,50,70,255,255,255,0,0,0,0,0"},
      {"painting", "painterly brush strokes (G'MIC fx_painting)", "fx_painting 3,1.5,2,0,0,0,0"},
      {"cartoon", "flat colours and inked edges (G'MIC cartoon)", "cartoon"},
  };
  return table;
}

const FinishInfo* finishByName(std::string_view name) {
  for (const FinishInfo& f : finishes())
    if (f.name == name) return &f;
  return nullptr;
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
  const int colours = image.alpha_channel >= 0 ? image.channels - 1 : image.channels;
  const float full = pixelTypeFullScale(image.type);
  const size_t w = static_cast<size_t>(image.width), h = static_cast<size_t>(image.height);
  gmic_list<float> images;
  gmic_list<char> names;
  images.assign(1);
  gmic_image<float>& planes = images[0];
  planes.assign(image.width, image.height, 1, static_cast<unsigned>(colours));
  // G'MIC's filters expect values 0…255, straight (not premultiplied) colour.
  for (size_t y = 0; y < h; ++y) {
    const void* row = image.row(static_cast<int>(y));
    for (size_t x = 0; x < w; ++x) {
      const size_t i = x * static_cast<size_t>(image.channels);
      auto at = [&](size_t k) {
        return image.type == PixelType::UInt8    ? sampleAt<uint8_t>(row, i + k)
               : image.type == PixelType::UInt16 ? sampleAt<uint16_t>(row, i + k)
                                                 : sampleAt<float>(row, i + k);
      };
      const float a =
          image.alpha_channel >= 0 ? at(static_cast<size_t>(image.alpha_channel)) / full : 1.0f;
      for (int c = 0; c < colours; ++c)
        planes(static_cast<unsigned>(x), static_cast<unsigned>(y), 0, static_cast<unsigned>(c)) =
            a > 0 ? std::clamp(at(static_cast<size_t>(c)) / full / a, 0.0f, 1.0f) * 255.0f : 0.0f;
    }
  }
  try {
    const OneOpenMpThread serial(finish->random);
    gmic(finish->gmic.c_str(), images, names, nullptr, true);
  } catch (...) {  // G'MIC's own message is not the user's
    return Status::failure("the " + finish->name + " finish failed in G'MIC");
  }
  if (images._width < 1 || images[0]._width != static_cast<unsigned>(image.width) ||
      images[0]._height != static_cast<unsigned>(image.height) || images[0]._spectrum < 1)
    return Status::failure("the " + finish->name + " finish changed the image's size");
  const gmic_image<float>& out = images[0];
  for (size_t y = 0; y < h; ++y) {
    void* row = image.row(static_cast<int>(y));
    for (size_t x = 0; x < w; ++x) {
      const size_t i = x * static_cast<size_t>(image.channels);
      float a = 1.0f;
      if (image.alpha_channel >= 0) {
        const size_t ia = i + static_cast<size_t>(image.alpha_channel);
        a = (image.type == PixelType::UInt8    ? sampleAt<uint8_t>(row, ia)
             : image.type == PixelType::UInt16 ? sampleAt<uint16_t>(row, ia)
                                               : sampleAt<float>(row, ia)) /
            full;
      }
      for (int c = 0; c < colours; ++c) {
        // A grey result (pencil) marks every colour channel alike.
        const unsigned from =
            static_cast<unsigned>(std::min<int>(c, static_cast<int>(out._spectrum) - 1));
        const float v =
            std::clamp(out(static_cast<unsigned>(x), static_cast<unsigned>(y), 0, from) / 255.0f,
                       0.0f, 1.0f) *
            a;
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
