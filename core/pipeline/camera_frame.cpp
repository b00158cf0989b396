// SPDX-License-Identifier: Apache-2.0
#include "core/pipeline/camera_frame.h"

#include "core/io/orientation.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <utility>
#include <vector>

namespace artcam {
namespace {

FrameSize transposed(FrameSize s) { return {s.height, s.width}; }

// The output-frame rule's aspect test (render.h): within a rounding pixel of the source
// frame's aspect.
bool sameAspect(FrameSize source, FrameSize photo) {
  const double expected_height = source.height * static_cast<double>(photo.width) / source.width;
  return std::abs(photo.height - expected_height) <= 1.0;
}

// A packed copy of `view` turned by `orientation` (orientation.h).
std::vector<std::uint8_t> turnedBytes(const ConstImageView& view, int orientation) {
  const size_t pixel = static_cast<size_t>(view.pixelBytes());
  const size_t packed_row = static_cast<size_t>(view.width) * pixel;
  std::vector<std::uint8_t> packed;
  const void* source = view.data;
  if (static_cast<size_t>(view.row_bytes) != packed_row) {
    packed.resize(packed_row * static_cast<size_t>(view.height));
    for (int y = 0; y < view.height; ++y)
      std::memcpy(packed.data() + packed_row * static_cast<size_t>(y), view.row(y), packed_row);
    source = packed.data();
  }
  std::vector<std::uint8_t> out(packed_row * static_cast<size_t>(view.height));
  reorientPixels(source, view.width, view.height, pixel, orientation, out.data());
  return out;
}

ImageF turnedImage(const ImageF& image, int orientation) {
  const bool swap = orientationSwapsAxes(orientation);
  ImageF out;
  out.width = swap ? image.height : image.width;
  out.height = swap ? image.width : image.height;
  out.channels = image.channels;
  out.alpha_channel = image.alpha_channel;
  out.data.resize(image.data.size());
  reorientPixels(image.data.data(), image.width, image.height,
                 sizeof(float) * static_cast<size_t>(image.channels), orientation, out.data.data());
  return out;
}

// The upright inputs turned back into the stored raster's frame, owning their pixels.
struct StoredFrameInputs {
  std::vector<std::uint8_t> photo;
  ImageF linear, depth, second;
  RenderInputs inputs;

  StoredFrameInputs(const RenderInputs& upright, int turn) {
    const int back = inverseOrientation(turn);
    const bool swap = orientationSwapsAxes(turn);
    inputs = upright;
    inputs.pyramid = nullptr;
    if (upright.linear) {
      linear = turnedImage(*upright.linear, back);
      inputs.linear = &linear;
    }
    if (upright.linear && upright.photo.data == upright.linear->data.data()) {
      inputs.photo = viewOf(std::as_const(linear));
    } else if (!upright.photo.empty()) {
      photo = turnedBytes(upright.photo, back);
      const int w = swap ? upright.photo.height : upright.photo.width;
      const int h = swap ? upright.photo.width : upright.photo.height;
      inputs.photo = packedView<const void>(photo.data(), w, h, upright.photo.channels,
                                            upright.photo.type, upright.photo.alpha_channel);
    }
    // A depth map and a second image lie over the photo as shown (any size, scaled to it).
    if (upright.depth) {
      depth = turnedImage(*upright.depth, back);
      inputs.depth = &depth;
    }
    if (upright.second) {
      second = turnedImage(*upright.second, back);
      inputs.second = &second;
    }
  }
};

RenderOptions storedFrameOptions(const RenderOptions& options, int turn) {
  RenderOptions turned = options;
  if (orientationSwapsAxes(turn)) std::swap(turned.warp.width, turned.warp.height);
  return turned;
}

}  // namespace

int turnAfterCamera(const Artcam& camera, FrameSize upright, int stored_orientation) {
  const int o = validOrientation(stored_orientation);
  if (o == 1) return 1;
  if (camera.frame) return *camera.frame == CameraFrame::Sensor ? o : 1;
  const FrameSize source = camera.sourceSize();
  if (!source.isImage() || !upright.isImage()) return 1;
  const FrameSize stored = orientationSwapsAxes(o) ? transposed(upright) : upright;
  return sameAspect(source, stored) && !sameAspect(source, upright) ? o : 1;
}

OutputFrame outputFrameTurned(const Artcam& camera, FrameSize upright, int turn, int width,
                              int height) {
  if (turn == 1) return outputFrameFor(camera, upright, width, height);
  const bool swap = orientationSwapsAxes(turn);
  OutputFrame frame = swap ? outputFrameFor(camera, transposed(upright), height, width)
                           : outputFrameFor(camera, upright, width, height);
  if (swap) frame.size = transposed(frame.size);
  return frame;
}

void renderTurned(const RenderInputs& inputs, const Artcam& camera, const RenderOptions& options,
                  int turn, const ImageView& out, RenderSummary* summary) {
  if (turn == 1) return render(inputs, camera, options, out, summary);
  const StoredFrameInputs stored(inputs, turn);
  const bool swap = orientationSwapsAxes(turn);
  const int w = swap ? out.height : out.width, h = swap ? out.width : out.height;
  const size_t pixel = static_cast<size_t>(out.pixelBytes());
  std::vector<std::uint8_t> rendered(static_cast<size_t>(w) * static_cast<size_t>(h) * pixel);
  const ImageView view =
      packedView<void>(rendered.data(), w, h, out.channels, out.type, out.alpha_channel);
  RenderSummary local;
  RenderSummary* s = summary ? summary : &local;
  render(stored.inputs, camera, storedFrameOptions(options, turn), view, s);
  if (s->cancelled) return;
  const size_t row = static_cast<size_t>(out.width) * pixel;
  if (static_cast<size_t>(out.row_bytes) == row) {
    reorientPixels(rendered.data(), w, h, pixel, turn, out.data);
  } else {
    const std::vector<std::uint8_t> upright = turnedBytes(
        packedView<const void>(rendered.data(), w, h, out.channels, out.type, out.alpha_channel),
        turn);
    for (int y = 0; y < out.height; ++y)
      std::memcpy(out.row(y), upright.data() + row * static_cast<size_t>(y), row);
  }
  s->size = {out.width, out.height};
}

ImageF renderTurned(const RenderInputs& inputs, const Artcam& camera, const RenderOptions& options,
                    int turn, RenderSummary* summary, ImageF* depth_out) {
  if (turn == 1) return render(inputs, camera, options, summary, depth_out);
  const StoredFrameInputs stored(inputs, turn);
  RenderSummary local;
  RenderSummary* s = summary ? summary : &local;
  ImageF depth;
  const ImageF image = render(stored.inputs, camera, storedFrameOptions(options, turn), s,
                              depth_out ? &depth : nullptr);
  if (image.empty()) return image;
  if (depth_out) *depth_out = depth.empty() ? ImageF() : turnedImage(depth, turn);
  ImageF out = turnedImage(image, turn);
  s->size = {out.width, out.height};
  return out;
}

}  // namespace artcam
