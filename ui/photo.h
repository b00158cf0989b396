// SPDX-License-Identifier: Apache-2.0
// A loaded photograph and the two reduced copies the GUI needs. Immutable once made (shared
// between the GUI thread and the render worker through shared_ptr<const Photo>).
//
// Frames: `full` is the original resolution; pairs and the canvas work in its PIXELS (centres
// at i + 0.5). `preview` is a box-downscaled copy with (nearly) the same aspect, rendered
// through the same camera: cameras live in normalised frames, so that is correct.
#pragma once

#include "core/io/first_look.h"
#include "core/io/image_io.h"
#include "core/model/camera.h"
#include "core/model/image.h"
#include "core/sampling/mip_pyramid.h"

#include <QImage>
#include <QMetaType>
#include <QString>

#include <memory>

namespace artcam::ui {

inline constexpr int kPreviewMaxSide = 1024;  // float preview copy (effects, insertion)
// The live preview fits a 1080p screen: at most 1920×1080, aspect kept.
inline constexpr int kLivePreviewMaxWidth = 1920;
inline constexpr int kLivePreviewMaxHeight = 1080;
inline constexpr int kDisplayMaxSide = 4096;  // canvas picture; bounds GUI memory for huge photos

struct Photo {
  QString path;
  // The whole photo, except in a quick first look (reduced_by > 1): then `image` is EMPTY and
  // only `info` (the file's format, metadata, orientation) is set. What reads photo pixels
  // (export, edge-aware depth painting, snapping, colour samples) checks hasFullImage() and
  // waits for, or does without, the full photo: it never takes the reduced pixels for them.
  LoadedImage full;
  // 1: made from the whole photo. n > 1: a first look (core/io/first_look.h): display, preview
  // and pyramid were made from libjpeg's 1/n decode; the full photo replaces this one
  // (Document::refinePhoto) with the same size(), so pairs, edits and the camera carry over.
  int reduced_by = 1;
  FrameSize full_size;  // the upright photo's size in pixels, from the start
  ImageF preview;
  // 8-bit sRGB of `full`, downscaled to kDisplayMaxSide. A first look's shares pyramid_base's
  // pixels (no copy; QPainter draws either format).
  QImage display;
  // The live preview's source: the display copy as premultiplied
  // RGBA8 and its 8-bit mip pyramid (levels view pyramid_base, which must not change), built
  // once per photo on the loader thread, so an edit re-renders a screen-sized preview from
  // the level that matches its scale.
  QImage pyramid_base;
  std::shared_ptr<const StoredMipPyramid> pyramid;

  FrameSize size() const { return full_size; }
  bool hasFullImage() const { return reduced_by == 1; }
};

using PhotoPtr = std::shared_ptr<const Photo>;

// The live preview's size: the photo's, shrunk (never enlarged) to fit 1920×1080, aspect kept
// to the nearest pixel.
FrameSize livePreviewSize(const Photo& photo);

// Builds the reduced copies; runs on a worker thread (ImageLoader), never in paintEvent.
PhotoPtr makePhoto(QString path, LoadedImage loaded);
// A first look's photo: the same copies made straight from its 8-bit sRGB samples (the float
// preview through the sRGB table readImage uses), no full pixels kept. The stage before the
// first preview, so it stays in 8 bits: no float copy of the raster.
PhotoPtr makeFirstLookPhoto(QString path, FirstLook look);

}  // namespace artcam::ui

Q_DECLARE_METATYPE(artcam::ui::PhotoPtr)
