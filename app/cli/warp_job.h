// The warp of one image split into its three stages, shared by `artcam warp` (one after the
// other) and `artcam batch` (a pipeline that overlaps them across files):
//   decodeForWarp → renderForWarp → encodeWarp.
// Each stage takes a progress callback that may cancel (interrupt.h); a cancelled or failed
// stage throws CommandError naming the file, and no output file is left (atomic saves).
//
// Memory (issue 9, "big images"): where the output format stores the input's kind of sample
// the image stays in its stored pixel type (core/io/stored_image.h: decode and encode in bands
// of rows, no float copy), and renderForWarp drops the input as soon as the output exists, so
// a warp peaks at input + output and a pipeline at the images it holds in flight.
#pragma once

#include "app/cli/args.h"
#include "core/io/artcam_file.h"
#include "core/io/image_io.h"
#include "core/io/stored_image.h"
#include "core/model/piecewise_camera.h"
#include "core/render/warp.h"

#include <functional>
#include <optional>
#include <string>

namespace artcam::cli {

// A camera file read once for any number of images.
struct WarpCameraFile {
  std::string path;
  ArtcamEffectFile effect;                // the camera (document.camera) and its layers
  bool attributed = false;                // colour/depth/layers: the attributed renderer
  std::optional<PiecewiseCamera> pieces;  // a piecewise camera: its mesh warp
  const Camera& camera() const { return effect.document.camera; }
};
WarpCameraFile loadWarpCamera(const std::string& path);

struct WarpRequest {
  WarpOptions options;  // filter, threads; width × height 0: scaled from each input (below)
  std::optional<std::string> depth_path;  // attributed cameras that read depth
  double depth_scale = 1.0;
  double baseline_focal = 0.0;
  bool stats = false;
};

// --size WxH, --filter, --threads (and the attributed renderer's --depth, --depth-scale,
// --disparity when `args` has them): the options warp and batch share.
WarpRequest parseWarpRequest(const Args& args);

using Progress = std::function<bool(double)>;

struct DecodedInput {
  std::string input;
  std::string output;
  std::optional<StoredImage> stored;  // the stored-type path
  std::optional<LoadedImage> loaded;  // linear float (re-encoding, piecewise, attributed)
  double megapixels() const;
};
DecodedInput decodeForWarp(const WarpCameraFile& camera, const std::string& input,
                           const std::string& output, const Progress& progress);

struct RenderedOutput {
  std::string output;
  std::optional<StoredImage> stored;
  std::optional<ImageF> image;
  ImageInfo like;        // the input's format and metadata, written back
  bool written = false;  // the attributed renderer writes its own output
  int width = 0;
  int height = 0;
  double render_ms = 0.0;
  std::string description;  // "kernel homography, 12 transparent pixels"
};
// Consumes the input (freed before returning).
RenderedOutput renderForWarp(const WarpCameraFile& camera, DecodedInput&& input,
                             const WarpRequest& request, const Progress& progress);

void encodeWarp(RenderedOutput& output, const Progress& progress);

// True when `output` names the same existing file as `input` (hard links and different
// spellings included: std::filesystem::equivalent, not a string compare).
bool sameFile(const std::string& input, const std::string& output);

}  // namespace artcam::cli
