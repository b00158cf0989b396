// A loaded photograph and the two reduced copies the GUI needs. Immutable once made (shared
// between the GUI thread and the render worker through shared_ptr<const Photo>).
//
// Frames: `full` is the original resolution; pairs and the canvas work in its PIXELS (centres
// at i + 0.5). `preview` is a box-downscaled copy with (nearly) the same aspect, rendered
// through the same camera: cameras live in normalised frames, so that is correct (DESIGN §1).
#pragma once

#include "core/io/image_io.h"
#include "core/model/camera.h"
#include "core/model/image.h"

#include <QImage>
#include <QMetaType>
#include <QString>

#include <memory>

namespace artcam::ui {

inline constexpr int kPreviewMaxSide = 1024;  // live preview source
inline constexpr int kDisplayMaxSide = 4096;  // canvas picture; bounds GUI memory for huge photos

struct Photo {
  QString path;
  LoadedImage full;
  ImageF preview;
  QImage display;  // 8-bit sRGB of `full`, downscaled to kDisplayMaxSide

  FrameSize size() const { return {full.image.width, full.image.height}; }
};

using PhotoPtr = std::shared_ptr<const Photo>;

// Builds the reduced copies; runs on a worker thread (ImageLoader), never in paintEvent.
PhotoPtr makePhoto(QString path, LoadedImage loaded);

}  // namespace artcam::ui

Q_DECLARE_METATYPE(artcam::ui::PhotoPtr)
