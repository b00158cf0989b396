// SPDX-License-Identifier: Apache-2.0
#include "ui/photo.h"

#include "ui/image_convert.h"

#include "core/colour/transfer.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <future>
#include <vector>

namespace artcam::ui {

namespace {

// The live preview's 8-bit mip pyramid over `base` (premultiplied RGBA8), kept with the photo.
void buildPyramid(Photo& photo, QImage base) {
  photo.pyramid_base = std::move(base);
  const QImage& b = photo.pyramid_base;
  ConstImageView view = packedView<const void>(b.constBits(), b.width(), b.height(), 4,
                                               PixelType::UInt8, /*alpha_channel=*/3);
  view.row_bytes = b.bytesPerLine();
  photo.pyramid = std::make_shared<const StoredMipPyramid>(view);
}

// boxDownscale (image_convert.h) of 8-bit sRGB pixels of `stride` bytes, their first
// `channels` samples each decoded through readImage's table (the exact sRGB curve) and summed
// in linear light: the float preview without a float copy of the whole raster.
ImageF boxDownscaleSrgb8(const std::uint8_t* bytes, int w, int h, int stride, int channels,
                         int max_side) {
  static const std::array<float, 256> table = [] {
    std::array<float, 256> t{};
    const Transfer srgb = Transfer::srgb();
    for (int v = 0; v < 256; ++v)
      t[static_cast<size_t>(v)] = static_cast<float>(srgb.decode(static_cast<double>(v) / 255));
    return t;
  }();
  const int longest = std::max(w, h);
  const int f = longest <= max_side ? 1 : (longest + max_side - 1) / max_side;
  const int ow = (w + f - 1) / f, oh = (h + f - 1) / f;
  ImageF out(ow, oh, channels);
  // One output row's sums at a time (at most f² ≤ a few hundred terms: float is plenty).
  std::vector<float> sums(static_cast<size_t>(ow) * static_cast<size_t>(channels));
  const size_t row = static_cast<size_t>(w) * static_cast<size_t>(stride);
  for (int oy = 0; oy < oh; ++oy) {
    std::fill(sums.begin(), sums.end(), 0.0f);
    const int y1 = std::min(h, (oy + 1) * f);
    for (int y = oy * f; y < y1; ++y) {
      const std::uint8_t* in = bytes + static_cast<size_t>(y) * row;
      for (int ox = 0; ox < ow; ++ox) {
        float* sum = sums.data() + static_cast<size_t>(ox) * static_cast<size_t>(channels);
        const int x1 = std::min(w, (ox + 1) * f);
        for (int x = ox * f; x < x1; ++x) {
          const std::uint8_t* p = in + static_cast<size_t>(x) * static_cast<size_t>(stride);
          for (int c = 0; c < channels; ++c) sum[c] += table[p[c]];
        }
      }
    }
    for (int ox = 0; ox < ow; ++ox) {
      const float n = static_cast<float>((y1 - oy * f) * (std::min(w, (ox + 1) * f) - ox * f));
      for (int c = 0; c < channels; ++c)
        out.pixel(ox, oy)[c] = sums[static_cast<size_t>(ox * channels + c)] / n;
    }
  }
  return out;
}

}  // namespace

PhotoPtr makePhoto(QString path, LoadedImage loaded) {
  auto photo = std::make_shared<Photo>();
  photo->path = std::move(path);
  photo->full_size = {loaded.image.width, loaded.image.height};
  photo->full = std::move(loaded);
  photo->preview = boxDownscale(photo->full.image, kPreviewMaxSide);
  photo->display = qimageFromLinear(boxDownscale(photo->full.image, kDisplayMaxSide));
  if (!photo->display.isNull())
    buildPyramid(*photo, photo->display.convertToFormat(QImage::Format_RGBA8888_Premultiplied));
  return photo;
}

PhotoPtr makeFirstLookPhoto(QString path, FirstLook look) {
  auto photo = std::make_shared<Photo>();
  photo->path = std::move(path);
  photo->reduced_by = look.reduced_by;
  photo->full_size = {look.full_width, look.full_height};
  photo->full.info = std::move(look.image.info);  // full.image stays empty (photo.h)
  const int w = look.image.width, h = look.image.height, ch = look.image.channels;
  const auto* bytes = static_cast<const std::uint8_t*>(look.image.bytes.data());
  // The float copy on a second thread while this one makes the picture and its pyramid: the
  // two are the whole wait before the first preview, and the decode left the other core idle.
  // `bytes` stays alive until get() below: in `look` (grey) or in the picture (colour).
  std::future<ImageF> preview = std::async(std::launch::async, [bytes, w, h, ch] {
    return boxDownscaleSrgb8(bytes, w, h, ch, ch == 4 ? 3 : 1, kPreviewMaxSide);
  });
  // Colour comes as opaque RGBA (first_look.h): the picture is the decoded raster itself, no
  // copy; the QImage owns it from here. Grey is spread into RGBA.
  QImage base;
  if (ch == 4) {
    auto* owned = new StoredImage(std::move(look.image));
    base = QImage(static_cast<uchar*>(owned->bytes.data()), w, h, static_cast<qsizetype>(w) * 4,
                  QImage::Format_RGBA8888_Premultiplied,
                  [](void* image) { delete static_cast<StoredImage*>(image); }, owned);
  } else {
    base = QImage(w, h, QImage::Format_RGBA8888_Premultiplied);
    for (int y = 0; !base.isNull() && y < h; ++y) {
      const std::uint8_t* in = bytes + static_cast<size_t>(y) * static_cast<size_t>(w);
      std::uint8_t* out = base.scanLine(y);
      for (int x = 0; x < w; ++x, out += 4) {
        out[0] = out[1] = out[2] = in[x];
        out[3] = 255;
      }
    }
  }
  if (!base.isNull()) {  // else allocation failed: no picture until the full photo
    photo->display = base;  // shares the pixels
    buildPyramid(*photo, std::move(base));
  }
  photo->preview = preview.get();  // before `look`'s pixels (grey) go
  return photo;
}

FrameSize livePreviewSize(const Photo& photo) {
  const FrameSize full = photo.size();
  const double scale = std::min({1.0, static_cast<double>(kLivePreviewMaxWidth) / full.width,
                                 static_cast<double>(kLivePreviewMaxHeight) / full.height});
  if (scale >= 1.0) return full;
  return {std::max(1, static_cast<int>(std::lround(full.width * scale))),
          std::max(1, static_cast<int>(std::lround(full.height * scale)))};
}

}  // namespace artcam::ui
