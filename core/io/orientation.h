// SPDX-License-Identifier: Apache-2.0
// EXIF orientation (TIFF tag 274, 1..8): how a stored raster is turned to show the photo
// upright. Cameras store a portrait photo as a landscape raster and tag it 6 or 8; every reader
// of the engine (image_io.h, stored_image.h) hands over the upright photo, so cameras are
// fitted, points placed and warps rendered on what the user sees, and outputs are written
// upright with orientation 1.
//
// Pixels are packed rows, pixel (0, 0) top-left (docs/architecture.md, "Frames and pixels").
// Value v: the stored row 0 / column 0 show as the upright photo's
//   1 top / left, 2 top / right, 3 bottom / right, 4 bottom / left,
//   5 left / top, 6 right / top, 7 right / bottom, 8 left / bottom.
// Values outside 1..8 are taken as 1 (as most viewers do).
// The turn is done here rather than with OpenImageIO's ImageBufAlgo::reorient: OpenImageIO 2.4
// swaps 5 and 7 (transverses 5, transposes 7), and reorient works on an ImageBuf copy while
// the stored-type reader turns its own pixel buffer (one extra buffer, not two).
#pragma once

#include <cstddef>

namespace artcam {

// `value` if it is 1..8, else 1.
int validOrientation(int value);
// Whether the upright photo is the stored raster's transpose in size (5..8).
bool orientationSwapsAxes(int orientation);
// The orientation that turns the upright photo back into the stored raster: 6 and 8 (a quarter
// turn each way) undo each other, the others (mirrors, the half turn, transposes) themselves.
int inverseOrientation(int orientation);

// Copies the stored raster (`width` x `height` pixels of `pixel_bytes` each) into `upright`
// (height x width pixels for 5..8, else width x height). The two must not overlap.
void reorientPixels(const void* stored, int width, int height, size_t pixel_bytes, int orientation,
                    void* upright);

}  // namespace artcam
