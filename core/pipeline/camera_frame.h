// SPDX-License-Identifier: Apache-2.0
// The frame a camera is applied in, one rule for `warp`, `batch`, `export` and the studio.
//
// Every reader hands over the photo upright (core/io/orientation.h). A portrait shot is a
// landscape sensor raster tagged Orientation 6 or 8, and a lens distorts that raster: its
// centre and its radial model (the lens camera, core/lens/lens_camera.h) are in the sensor's
// frame, however the camera was held. Stretching a landscape lens camera onto the upright
// portrait photo corrects the wrong pixels. So a camera made for the stored raster is applied
// to the stored pixels and the result is turned upright afterwards; the output is upright either
// way (written with Orientation 1, photo_metadata.h).
//
// Which frame (Artcam::frame, the file's "frame"):
//   sensor   the stored raster (lens cameras write it)
//   upright  the photo as shown (what a camera fitted to points on the shown photo is)
//   unset    a file that does not say: the stored raster when the camera's source frame has
//            the stored raster's aspect and not the upright photo's (within a rounding pixel,
//            the output-frame rule's test, render.h), else upright. For a photo not turned
//            by a quarter (Orientation 1..4) the two frames have one aspect: upright, as
//            before the field existed.
// A photo stored as shown (Orientation 1) has one frame: nothing changes for it.
//
// The render turns the upright inputs back into the stored frame (an exact pixel permutation:
// orientation.h's turn by the inverse orientation), renders there, and turns the output by the
// photo's orientation: the same pixels as correcting the stored raster, then turning. It costs
// a copy of the photo and of the output; photos stored as shown take render() directly.
#pragma once

#include "core/model/artcam.h"
#include "core/pipeline/render.h"

namespace artcam {

// The EXIF orientation (orientation.h) the render turns the camera's output by: the photo's
// stored orientation when `camera` is applied to the stored raster, else 1 (no turn). `upright`
// is the photo's size as read (turned upright), `stored_orientation` ImageInfo's.
int turnAfterCamera(const Artcam& camera, FrameSize upright, int stored_orientation);

// outputFrameFor (render.h) of the photo in the frame the camera is applied in, then turned:
// the upright output's size. An explicit width/height is the upright output's.
OutputFrame outputFrameTurned(const Artcam& camera, FrameSize upright, int turn, int width = 0,
                              int height = 0);

// render() with `inputs` upright (the photo, its linear copy, depth and second image as read) and
// the camera applied in its frame: for `turn` 1 exactly render(); else the inputs are turned
// back to the stored frame, rendered, and the result turned by `turn`. `out` has
// outputFrameTurned's size; options' width/height are the upright output's. Pyramids are left
// out of a turned render (they hold the upright photo).
void renderTurned(const RenderInputs& inputs, const Artcam& camera, const RenderOptions& options,
                  int turn, const ImageView& out, RenderSummary* summary = nullptr);
ImageF renderTurned(const RenderInputs& inputs, const Artcam& camera, const RenderOptions& options,
                    int turn, RenderSummary* summary = nullptr, ImageF* depth_out = nullptr);

}  // namespace artcam
