// SPDX-License-Identifier: Apache-2.0
// The render front door: one call that renders a photo (and its depth) through any camera value
// (core/model/artcam.h). The studio's preview and export, `artcam warp`, `batch`, `insert` and
// the effects panel all come through here, so a camera renders the same everywhere.
//
// The path follows from the camera's structure, analysed once (core/model/structure.h):
//   piecewise              the mesh warp of its patches (core/piecewise/piecewise_render.h)
//   layered or attributed  the attributed renderer (core/render/attributed.h): colour-only
//                          (identity geometry, no resampling), gather (geometry from position
//                          alone, eq 4), splat (geometry reading colour or depth, eq 8/9);
//                          compositing cameras (core/colour/composite.h) read the second
//                          image (RenderInputs::second) on colour-only and gather;
//                          layers summed (the paper's Fig 4); then, when the depth output is
//                          the blur variance, the depth-of-field blur stack
//   geometry only          the gather warp's kernels on the photo as stored (core/render/warp.h:
//                          identity … homography exactly, rational by certified Newton), or the
//                          mip level that matches the output scale when a pyramid is given
//
// Resampling (one rule, docs/architecture.md): the photo is interpolated as stored. The stored
// photo's paths do so directly; the paths that read the linear copy encode it back
// (RenderInputs::encoding), interpolate, and decode each sample before any colour arithmetic.
//
// The output frame (one rule for every caller): the photo scaled by target frame / source frame,
// per axis and rounded, so a camera of the photo's own size and aspect keeps the photo's exact
// size; a photo whose aspect differs from the camera's source frame by more than a rounding
// pixel is stretched per axis, and the plan says so (OutputFrame::warning). An explicit size
// overrides it (one side 0: the other from the target frame's aspect).
//
// Channels: the geometry paths keep the photo's channels and add alpha; dropOpaqueAlpha removes
// that alpha again where the photo had none and every output pixel has a preimage.
#pragma once

#include "core/colour/stored_encoding.h"
#include "core/model/artcam.h"
#include "core/model/image.h"
#include "core/model/image_view.h"
#include "core/sampling/mip_pyramid.h"
#include "core/render/warp.h"

#include <string>
#include <string_view>
#include <vector>

namespace artcam {

struct RenderInputs {
  // The photo read in place, any pixel type: what the geometry kernels sample.
  ConstImageView photo;
  // The photo as linear float (premultiplied): what the attributed and piecewise paths read.
  // Required for cameras where needsLinearPhoto() is true; may be a smaller copy (a preview).
  const ImageF* linear = nullptr;
  // How `linear` was decoded from the photo's stored values (core/colour/stored_encoding.h):
  // the paths that render from `linear` resample in that domain, as the stored photo's gather
  // warp does, so one camera gives the same pixels on every path. Null: `linear` is what is
  // stored (a float file, an image made in code).
  const StoredEncoding* encoding = nullptr;
  // Previews: geometry cameras sample the pyramid level that matches the output scale.
  const StoredMipPyramid* pyramid = nullptr;
  // The depth block's input: 1 channel (d) or 2 (coverage·d, coverage), any size.
  const ImageF* depth = nullptr;
  // The second-colour block's input, for compositing cameras (core/colour/composite.h): a second
  // image as linear float, premultiplied. It lies over the photo's frame: read at each source
  // point scaled to its own size (bilinear), so one of the photo's size is read texel for texel
  // and one of another size is stretched per axis to the photo's frame.
  const ImageF* second = nullptr;

  static RenderInputs of(const ImageF& linear_photo, const ImageF* depth = nullptr,
                         const StoredEncoding* encoding = nullptr);
};

struct RenderOptions {
  // Output size (0×0: the output-frame rule), filter, threads, progress/cancel, antialias and the
  // coordinate kernels' tolerances: every path takes them.
  WarpOptions warp;
  int splat_supersample = 3;  // cameras whose geometry reads colour or depth (splat.h)
  // Piecewise cameras' source lattice (piecewise_render.h); 0: chosen, within 1/256 px.
  double mesh_step_px = 0.0;
  std::string force_path;     // tests and benchmarks: "splat" or "gather"
};

enum class RenderPath { Geometry, Preview, ColourOnly, Gather, Splat, Layered, Piecewise };
std::string_view renderPathName(RenderPath path);

// "" when a second image (RenderInputs::second) of `second`'s size lies texel for texel over a
// photo of `photo`'s; else the warning every path gives: it is stretched to the photo's frame.
std::string secondImageSizeNote(FrameSize second, FrameSize photo);

struct RenderSummary {
  RenderPath path = RenderPath::Geometry;
  bool blurred = false;          // the depth-of-field blur stack ran after the layers
  std::string kernel;            // the coordinate kernel ("homography", "rational", "splat", …)
  FrameSize size;                // the output size
  long long transparent_pixels = 0;
  double render_ms = 0.0;
  bool cancelled = false;
  std::string note;              // e.g. the output-frame warning, a splat's dropped triangles
  // One line for users: "gather warp (homography), 0 transparent pixels".
  std::string describe() const;
};

struct OutputFrame {
  FrameSize size;
  std::string warning;  // non-empty when the photo's aspect differs from the source frame's
};
// The output-frame rule above, for a photo of `photo` pixels; width/height from options.warp.
OutputFrame outputFrameFor(const Artcam& camera, FrameSize photo, int width = 0, int height = 0);

// True when the camera renders from the linear float photo (RenderInputs::linear): layers,
// colour or depth blocks that change or steer geometry, depth of field, patches.
bool needsLinearPhoto(const Artcam& camera);
// True when the camera renders by the gather warp of one position camera on the photo as stored
// (warp.h's warpImage on camera.main()): no layers, patches, colour or depth. Those cameras
// also render band by band from a window of the photo's rows (streamed_warp.h).
bool rendersByGatherWarp(const Artcam& camera);

// Renders into `out`, which must have outputFrameFor's size and, for cameras that render from
// the stored photo, the photo's pixel type with its channels (+ alpha as warpImage allows);
// for cameras needing the linear photo `out` must be float RGBA (4 channels, alpha 3).
// Throws std::invalid_argument naming the cause for a broken contract (a missing input, an
// invalid camera, a wrong output shape). On cancel `out` is partial and summary->cancelled set.
// Unless cancelled, every pixel of `out` is written: it may be handed over uninitialised.
void render(const RenderInputs& inputs, const Artcam& camera, const RenderOptions& options,
            const ImageView& out, RenderSummary* summary = nullptr);

// The same, allocating the output: float, premultiplied, alpha last; the photo's channels + alpha
// on the geometry paths, RGBA on the others. Empty when cancelled. `depth_out` (may be null)
// receives the camera's depth output where it has one.
ImageF render(const RenderInputs& inputs, const Artcam& camera, const RenderOptions& options = {},
              RenderSummary* summary = nullptr, ImageF* depth_out = nullptr);

// The per-channel position cameras of a chromatic-aberration camera (the paper's Fig 4): three
// layers that each pass one colour channel (R, G, B) through a position camera and nothing
// else, in channel order; empty for any other camera. Those render by warpChannels on the photo
// as stored, and export-map writes one map per channel for them (source_maps.h).
std::vector<Camera> channelCameras(const Artcam& camera);

// Channels beyond the photo's (an EXR's depth, normals, AOVs) render through the same entry
// point, a group of 1..4 at a time as a photo of its own (RenderInputs::photo, no alpha) into
// an output of the photo's output size and the group's channels: the same camera, the same
// source position for every output pixel, pixels without a preimage 0 (as Nuke's STMap moves
// every channel). That holds for cameras rendered from the stored photo by one geometry
// (geometry-only and piecewise). Empty for those; else why not: per-channel cameras
// (chromatic aberration) move R, G and B differently, so no position is "the" source of an
// extra channel, and cameras on the linear photo change colour or depth or blur by depth,
// which has no meaning for data channels.
std::string extraChannelsUnsupported(const Artcam& camera);

// Drops the alpha channel (the last) when every pixel's alpha is full: returns the narrower view's
// channel count written in place (packed rows), or the old count when some pixel is not opaque.
int dropOpaqueAlpha(const ImageView& image);
bool dropOpaqueAlpha(ImageF& image);

}  // namespace artcam
