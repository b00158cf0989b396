// SPDX-License-Identifier: Apache-2.0
// Rendering ARTcams that change colour or depth: three strategies chosen from the structure
// analysis (structure.h), plus layered cameras. Callers go through core/pipeline/render.h.
//
// Conventions:
// - Images are ImageF (image.h): linear light, premultiplied alpha, pixel centres at i + 0.5.
// - The input point of pixel p is x = [position | colour | depth] (eq 4): position is the
//   source pixel centre in the source's NORMALISED frame (frames.h), colour the premultiplied
//   RGBA sample (alpha is the homogeneous weight; a source without alpha has alpha 1, a grey
//   source is replicated to RGB), depth (d, 1) from the depth image, and for compositing cameras
//   (core/colour/composite.h) the second image's premultiplied RGBA at the same place of the
//   source frame (the second-colour block; the second image is scaled to the source's size,
//   bilinear, so a second image of the photo's size is read texel for texel).
// - Outputs follow eq 5: colour = z_c / z_a with output alpha clamp(z_a, 0, 1), written
//   premultiplied; depth = z_d / z_dh. A pixel whose colour weight is not positive, or whose
//   outputs are not finite, is transparent (all channels 0): never NaN.
//
// Paths (AttributedPath):
// - ColourOnly: the geometry is the identity and the output has the source's size: every pixel
//   keeps its place and the colour/depth block is evaluated on its own value; no resampling.
// - Gather: positions depend on position only (pp), colour/depth may change (cc, pc, cp parts
//   that feed the attribute outputs): the output pixel's source point comes from the existing
//   gather kernels (coordinates.h) run on the camera's position-only part, the source is
//   sampled there (sampling.h) and the whole camera is evaluated at [source point | sample].
// - Splat: positions depend on colour or depth (pc/cp coupling into the position outputs, e.g.
//   the paper's eq 8/9): splat.h.
// - Geometry: a camera without attribute changes goes to warpImage unchanged (the colour then
//   passes through; its alpha is the filter's coverage).
//
// Layers: the paper's Fig 4 makes chromatic aberration from three cameras, one per colour layer.
// A layered render sums the layers' premultiplied colours (each layer selects its channel with
// its cc part) and takes the largest alpha: the layers are parts of one picture, not stacked
// sheets, so "over" would be wrong.
#pragma once

#include "core/colour/stored_encoding.h"
#include "core/model/compiled_camera.h"
#include "core/model/camera.h"
#include "core/model/image.h"
#include "core/model/structure.h"
#include "core/render/warp.h"

#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace artcam {

enum class AttributedPath { Geometry, ColourOnly, Gather, Splat };
std::string_view attributedPathName(AttributedPath path);

struct AttributedOptions {
  // Output size (0×0: the camera's target frame), filter, threads, progress and the coordinate
  // kernels' options: the geometry and gather paths use them exactly as warpImage does. The
  // progress callback reports and cancels every path (the result is then empty and
  // summary->cancelled is set).
  WarpOptions warp;
  // Splat: sub-samples per output pixel side (splat.h); more costs S² but smooths minified
  // regions (no moiré).
  int splat_supersample = 3;
  // Force a path (tests and the benchmark compare splat and gather); empty: from the structure.
  std::string force_path;
  // Also hand back the depth input's coverage per output pixel (AttributedImage::depth_coverage)
  // for an effect applied after the render: the depth-of-field blur (depth_coverage.h).
  bool depth_coverage = false;
};

struct AttributedSummary {
  bool cancelled = false;
  AttributedPath path = AttributedPath::Geometry;
  std::string kernel;  // the gather kernel's name, or "splat"
  long long transparent_pixels = 0;
  double render_ms = 0.0;
  std::string note;
};

struct AttributedImage {
  ImageF colour;  // RGBA premultiplied, alpha channel 3
  ImageF depth;   // 1 channel, the camera's depth output (0 where transparent); empty if the
                  // camera has no depth block
  // 1 channel, the coverage c of the depth input where each output pixel's depth was read (0
  // where nothing was), for the effects faded after the render (depth_coverage.h); only with
  // AttributedOptions::depth_coverage, on the colour-only and gather paths (and layered
  // renders of them): empty otherwise, which the blur takes as "no fade".
  ImageF depth_coverage;
};

// The images the camera's blocks read: the colour source, and where the camera has those
// blocks, the depth image (1 channel (d), or 2 channels (coverage·d, coverage) with
// alpha_channel 1 as core/depth/depth_raster.h makes) and the second image (any channels as the
// source, linear premultiplied). Both may have any size: they are read at the source point
// scaled to their size.
// `encoding`: how `colour` was decoded from the photo's stored values; the paths that resample
// the photo (gather, geometry) interpolate in that domain and decode each sample before the
// camera reads it (core/colour/stored_encoding.h). Null: `colour` is what is stored.
struct AttributedSources {
  const ImageF& colour;
  const ImageF* depth = nullptr;
  const ImageF* second = nullptr;
  const StoredEncoding* encoding = nullptr;
};

// Which path renders `camera` from a source of `source_px` to an output of `out_px`.
AttributedPath chooseAttributedPath(const Camera& camera, const CameraStructure& structure,
                                    FrameSize source_px, FrameSize out_px);

// `depth` (may be null) gives the depth block's input: 1 channel (d), or 2 channels
// (coverage·d, coverage) with alpha_channel 1 as core/depth/depth_raster.h makes; any size
// (sampled at the source point scaled to its size). Throws std::invalid_argument naming the
// cause for a broken contract: an invalid camera, a camera without a 2D position block, a
// camera that reads depth but no depth image, one that reads a second image but none given (or
// whose geometry reads attributes: the splat path has no second image), a bad source.
AttributedImage renderAttributed(const AttributedSources& sources, const Camera& camera,
                                 const AttributedOptions& options = {},
                                 AttributedSummary* summary = nullptr);
// The same for a camera already analysed (AnalysedCamera, structure.h).
AttributedImage renderAttributed(const AttributedSources& sources, const AnalysedCamera& camera,
                                 const AttributedOptions& options = {},
                                 AttributedSummary* summary = nullptr);
inline AttributedImage renderAttributed(const ImageF& source, const ImageF* depth,
                                        const Camera& camera,
                                        const AttributedOptions& options = {},
                                        AttributedSummary* summary = nullptr) {
  return renderAttributed({source, depth}, camera, options, summary);
}

// Every layer rendered as above and combined: the picture is the sum of the layers' colours
// (each layer carries its own colour channel, the paper's Fig 4), and a pixel is covered only as
// far as EVERY layer covers it: alpha is the smallest layer coverage, and each layer's colour is
// taken at that alpha (unpremultiplied by its own coverage, premultiplied by the smallest). So
// where one layer shrinks away from the frame's edge the pixel becomes transparent instead of
// keeping the other layers' channels as a frame of the complementary colour. The depth is that
// of the layer with the largest alpha. All layers must share the output size.
AttributedImage renderLayers(const AttributedSources& sources, const std::vector<Camera>& layers,
                             const AttributedOptions& options = {},
                             AttributedSummary* summary = nullptr);
AttributedImage renderLayers(const AttributedSources& sources, const std::vector<AnalysedCamera>& layers,
                             const AttributedOptions& options = {},
                             AttributedSummary* summary = nullptr);
inline AttributedImage renderLayers(const ImageF& source, const ImageF* depth,
                                    const std::vector<Camera>& layers,
                                    const AttributedOptions& options = {},
                                    AttributedSummary* summary = nullptr) {
  return renderLayers({source, depth}, layers, options, summary);
}

// One camera compiled for per-pixel evaluation (CompiledCamera: no allocation per call), with
// the block bookkeeping every path shares.
class AttributeEvaluator {
 public:
  explicit AttributeEvaluator(const Camera& camera);

  bool readsDepth() const { return depth_ >= 0; }
  // Whether the colour outputs depend on the depth input (through any stage: a depth-coupled
  // element taints its whole block at each re-homogenisation). Aerial perspective's do.
  bool colourReadsDepth() const { return colour_reads_depth_; }
  bool hasColour() const { return colour_ >= 0; }
  // The camera has a second-colour block: a compositing camera (core/colour/composite.h).
  bool readsSecond() const { return second_ >= 0; }
  // Which inputs the position outputs read, by the same taint rule: colour element k (0..3:
  // premultiplied r, g, b and alpha) and depth. The splat tears its mesh only where these jump.
  bool geometryReadsColour(int k) const { return geometry_reads_colour_[k]; }
  bool geometryReadsDepth() const { return geometry_reads_depth_; }

  struct Output {
    double position[2] = {0, 0};  // target, normalised frame (eq 5)
    double position_weight = 0;   // q_h before division: its sign tells the pole side
    float rgba[4] = {0, 0, 0, 0}; // premultiplied, alpha = clamp(z_a, 0, 1)
    float depth = 0;
    bool position_valid = false;  // finite position with q_h != 0
    bool attributes_valid = false;  // finite colour/depth with positive colour weight
  };
  // x = [(u_n, v_n, 1) | rgba (premultiplied) | (d, 1) | second (premultiplied) | (0, 1)]
  // through the camera (the last is the shading block, which the camera computes itself). Without a
  // colour block the input colour passes through; `second` (4 floats) is read only by cameras with
  // a second-colour block, and null reads as transparent.
  void evaluate(double u_n, double v_n, const float* rgba, double depth, Output& out,
                const float* second = nullptr) const;

 private:
  CompiledCamera compiled_;
  // Element offsets, -1: none.
  int position_ = -1, colour_ = -1, depth_ = -1, second_ = -1, shading_ = -1;
  bool colour_reads_depth_ = false;
  bool geometry_reads_colour_[4] = {false, false, false, false};
  bool geometry_reads_depth_ = false;
};

// The depth image read at source pixel point (sx, sy) given in pixels of a source of size
// `source_px` (bilinear, as the sampler reads colour); NaN-free: depth 0 where nothing covers.
// Coverage is the bilinear mix of the texels' coverage (the 2-channel form's second channel;
// for a 1-channel image 1 where the depth is positive and finite, 0 in holes, depth_file.h's
// "no depth"), over the texels inside the image; depth is the covered texels' mean.
struct DepthSample {
  double depth = 0.0;
  double coverage = 1.0;
};
DepthSample sampleDepthCoverage(const ImageF& depth, FrameSize source_px, double sx, double sy);
double sampleDepth(const ImageF& depth, FrameSize source_px, double sx, double sy);

// Pixels without depth are untouched: where the depth input's coverage c is 0 a pixel keeps
// its sampled colour (and depth output 0, "none"), as a camera that reads depth has nothing to
// act on there — aerial perspective must not haze the sky nobody gave a depth; where
// 0 < c < 1 the colour is c·(camera's colour) + (1 − c)·(sampled colour), so a soft mask edge
// fades the effect in without a seam: the depth-coverage rule of depth_coverage.h. Applied on
// the colour-only and gather paths, to cameras whose colour reads depth (colourReadsDepth); the
// depth output's c = 0 rule to every camera that reads depth (a blur variance of 0 leaves the
// pixel sharp); the blur after the render fades by the same rule from depth_coverage.

// The source as 4-channel premultiplied RGBA float (alpha channel 3).
ImageF rgbaFromImage(const ImageF& source);

// The camera's position-only part: the pp blocks of the position tensors of every stage.
// Exact for cameras whose position outputs read position only.
Camera positionPart(const Camera& camera);

}  // namespace artcam
