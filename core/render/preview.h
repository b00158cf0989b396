// SPDX-License-Identifier: Apache-2.0
// Screen-sized previews through a mip pyramid (core/sampling/mip_pyramid.h): the level whose
// pixels match the map's scale at the target centre, then the gather warp (warp.h) on it.
#pragma once

#include "core/model/camera.h"
#include "core/model/image.h"
#include "core/model/image_view.h"
#include "core/render/warp.h"
#include "core/sampling/mip_pyramid.h"

#include <vector>

namespace artcam {

// A screen-sized preview into `out` (the pyramid's pixel type and channels, or RGB → RGBA):
// the level matching the map's scale at the target centre (one Newton solve there), and the
// rational kernel's certified cells trusted to kPreviewCertifyTolerancePx. Same contract as
// warpImage on views; the summary's note names the level.
void warpPreview(const StoredMipPyramid& pyramid, const Camera& camera, const ImageView& out,
                 const WarpOptions& options = {}, WarpSummary* summary = nullptr);
// The same for one camera per colour channel (warpChannels); the level from the first's scale.
void warpPreview(const StoredMipPyramid& pyramid, const std::vector<Camera>& channel_cameras,
                 const ImageView& out, const WarpOptions& options = {}, WarpSummary* summary = nullptr);
// The same two for cameras already analysed (AnalysedCamera, structure.h).
void warpPreview(const StoredMipPyramid& pyramid, const AnalysedCamera& camera, const ImageView& out,
                 const WarpOptions& options = {}, WarpSummary* summary = nullptr);
void warpPreview(const StoredMipPyramid& pyramid, const std::vector<AnalysedCamera>& channel_cameras,
                 const ImageView& out, const WarpOptions& options = {}, WarpSummary* summary = nullptr);

// Warps through the level that matches the map's scale at the target frame centre (the
// footprint of one output pixel there, in source pixels). Same contract as warpImage; the
// summary's note names the level used.
ImageF warpPreview(const MipPyramid& pyramid, const Camera& camera, const WarpOptions& options = {},
                   WarpSummary* summary = nullptr);

}  // namespace artcam
