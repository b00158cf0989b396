// SPDX-License-Identifier: Apache-2.0
// Gather warp of an image through a position camera: each output pixel looks up its source
// point through the inverse map, and positions are made and sampled in one pass (fused).
//
// For each output pixel centre (x + 0.5, y + 0.5) the source point is found through the
// inverse map: exact for identity/translation/affine/homography cameras (from the structure
// analysis), otherwise seeded by a fitted inverse camera, checked by one forward evaluation
// and refined by Newton only where the seed misses (coordinates.h). Positions are made span
// by span and sampled at once (span_sampler.h): no per-pixel map is stored. Pixels with no
// preimage (outside the source, folded, beyond the pole curve x Q_n xᵀ = 0) are transparent:
// all channels 0 and alpha 0. Never NaN. Whole-pixel translations (identity included) copy.
// Every pixel of the output is written, transparent ones too, so the output may be handed over
// uninitialised (pixel_buffer.h: its pages are then first touched by the render's threads).
//
// Frames: the camera's tensors are normalised, so the source image may be any resolution of
// the photo the camera was made on, and the output any resolution of its target frame.
#pragma once

#include "core/model/camera.h"
#include "core/model/image.h"
#include "core/model/image_view.h"
#include "core/model/structure.h"
#include "core/mapping/coordinates.h"
#include "core/sampling/filter.h"

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>
#include <string_view>

namespace artcam {

// What an interactive preview accepts as position error (source pixels of the level it
// samples): invisible at screen size, and it lets strong lenses skip the per-pixel check.
constexpr double kPreviewCertifyTolerancePx = 1.0 / 16.0;

struct WarpOptions {
  Filter filter = Filter::Bilinear;
  // What the filter reads past the source's edge (filter.h): every renderer that samples the
  // photo takes it from here, so warp, batch, export and the studio agree.
  EdgeMode edge = EdgeMode::Transparent;
  int width = 0;   // output size; 0×0: the camera's target frame size
  int height = 0;
  int threads = 0;  // 0: all cores
  // Called between tiles with the fraction done; return false to cancel.
  std::function<bool(double)> progress;
  // How the inverse map is found (Newton acceptance, seed check, certified cells, inverse-seed
  // fit, forcing the rational kernel, scalar code): the coordinate kernels' own options, nested
  // so every renderer that gathers passes the same set on.
  CoordinateOptions coordinates;
  // Anti-aliasing where the map minifies: each output pixel averages n × n taps over its
  // footprint, n = ⌈longest side of the footprint in source pixels⌉ (per span of pixels, from
  // the Jacobian), at most max_supersample. Off: one tap per pixel (the exact semantics above).
  bool antialias = false;
  int max_supersample = 4;
};

struct WarpSummary {
  bool cancelled = false;
  std::string kernel;          // "identity", "affine", "homography", "rational", …
  long long transparent_pixels = 0;
  long long newton_pixels = 0;  // rational kernel: pixels whose seed check failed (full Newton)
  double certified_share = 0.0;  // rational kernel: share of certified cells (no per-pixel check)
  double render_ms = 0.0;
  // Anything the caller may want to show, e.g. why the inverse seed could not be fitted.
  std::string note;
};

// The output size options.width × options.height asks for: 0×0 means the camera's target
// frame, and one of the two 0 follows the target frame's aspect ratio. Throws for negatives.
// The output size for a requested width × height (0 × 0: the camera's target frame; one side 0:
// the other from the target frame's aspect). Shared by every renderer that takes a size.
FrameSize outputSizeFor(const Camera& camera, int width, int height);
FrameSize warpOutputSize(const Camera& camera, const WarpOptions& options);

// The output has the source's channels, plus an alpha channel if the source had none.
// Size: options.width × options.height; 0×0 means the camera's target frame, and one of the
// two 0 follows the target frame's aspect ratio. Sampling: see sampling.h (pixel centres at
// i + 0.5, outside the source transparent).
//
// Errors: throws std::invalid_argument for a broken contract — an invalid camera or source,
// negative sizes, a camera without a 2D position block, a camera whose geometry depends on
// colour or depth (those need the splat renderer, splat.h), or one that also transforms
// colour/depth (not rendered here yet). A camera whose denominator is zero everywhere renders
// fully transparent (kernel "degenerate").
// Cancel: when options.progress returns false the render stops between bands of rows and
// returns an EMPTY image with summary->cancelled set; a partial image is never returned.
// The progress callback runs on the calling thread, never on a worker.
ImageF warpImage(const ImageF& source, const Camera& camera, const WarpOptions& options = {},
                 WarpSummary* summary = nullptr);
ImageF warpImage(const ImageF& source, const AnalysedCamera& camera, const WarpOptions& options = {},
                 WarpSummary* summary = nullptr);

// The same warp on typed, strided views (image_view.h): 8-bit, 16-bit or float, 1–4 channels,
// read in place. `out` gives the output size (options.width/height are ignored) and must have
// the source's pixel type and channels, or one more (alpha, last) when the source has none;
// without alpha the output is composited over black. On cancel, `out` holds a partial render
// and summary->cancelled is set; the caller discards it.
void warpImage(const ConstImageView& source, const Camera& camera, const ImageView& out,
               const WarpOptions& options = {}, WarpSummary* summary = nullptr);
// The same for a camera already analysed (AnalysedCamera, structure.h): what a render pipeline
// calls, having analysed its camera once.
void warpImage(const ConstImageView& source, const AnalysedCamera& camera, const ImageView& out,
               const WarpOptions& options = {}, WarpSummary* summary = nullptr);

// The gather warp prepared once (kernel chosen, rational cells solved) and rendered band by band
// from a window of source rows: for photos too big to hold whole, which are then decoded and
// encoded in bands (core/pipeline/streamed_warp.h). Each output row comes out byte for byte as
// warpImage writes it: the same kernel gives the same positions row by row (each row's spans
// left to right from a fresh RowState, coordinates.h), and the window always holds every row a
// filter tap reads, so no tap sees the window's edge where the photo has none.
class BandWarp {
 public:
  struct Rows {
    int first = 0, last = 0;  // source rows [first, last)
    bool empty() const { return last <= first; }
  };

  // Throws std::invalid_argument as warpImage does, and for antialias (its taps spread over
  // footprints the band's positions do not bound).
  BandWarp(const Camera& camera, FrameSize source_px, FrameSize out_px, const WarpOptions& options);
  ~BandWarp();
  BandWarp(const BandWarp&) = delete;
  BandWarp& operator=(const BandWarp&) = delete;

  const std::string& kernelName() const { return kernel_name_; }
  // The source rows that output rows [y0, y1) read, every filter tap included (empty: none,
  // the rows are transparent). Runs the coordinate kernel over the rows: about the cost of the
  // positions half of rendering them.
  // `inside` (may be null) is set to whether every pixel of the rows certainly has full
  // coverage: a whole-pixel copy from within the photo, or every position valid and 2.5 px
  // inside the photo's frame (no filter tap leaves it).
  Rows sourceRows(int y0, int y1, bool* inside = nullptr) const;
  // Output rows [y0, y1) into `out` (y1 − y0 rows; type and channels as warpImage's `out`)
  // from `window`, the source's rows [window_first, window_first + window.height) with the
  // source's full width; it must hold sourceRows(y0, y1). Returns the transparent pixels.
  long long render(const ConstImageView& window, int window_first, int y0, int y1,
                   const ImageView& out) const;

 private:
  struct State;
  std::unique_ptr<State> state_;
  std::string kernel_name_;
};

// EdgeMode::Black's half, after any render into `image`: premultiplied colours over opaque
// black, i.e. the alpha channel (if any) set full, so nothing of the output is transparent.
// Returns the transparent pixels left: 0 for Black, `transparent` for the other modes (the
// samplers themselves carry Transparent and Extend).
long long finishEdge(EdgeMode edge, const ImageView& image, long long transparent);

// Chromatic aberration the way the paper's Fig 4 builds it, on the photo as stored: channel k
// (k < channel_cameras.size() ≤ the source's colour channels) through its own position camera,
// each by the kernel its structure picks; an alpha channel (the source's, or appended) is the
// least coverage of the channels, so a channel moved inwards leaves no coloured frame. An
// output without alpha (a JPEG) gets those colours as they are, premultiplied: composited over
// black, as warpImage writes such an output. Same
// views, options and cancel contract as warpImage; summary->kernel joins the kernels' names.
void warpChannels(const ConstImageView& source, const std::vector<Camera>& channel_cameras,
                  const ImageView& out, const WarpOptions& options = {}, WarpSummary* summary = nullptr);
void warpChannels(const ConstImageView& source, const std::vector<AnalysedCamera>& channel_cameras,
                  const ImageView& out, const WarpOptions& options = {}, WarpSummary* summary = nullptr);

}  // namespace artcam
