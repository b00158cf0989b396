// SPDX-License-Identifier: Apache-2.0
// The warp of one image split into its three stages, shared by `artcam warp` (one after the
// other) and `artcam batch` (a pipeline that overlaps them across files):
//   decodeForWarp → renderForWarp → encodeWarp.
// Each stage takes a progress callback that may cancel (interrupt.h); a cancelled or failed
// stage throws CommandError naming the file, and no output file is left (atomic saves).
//
// Every render goes through core's front door (core/pipeline/render.h) with the camera value
// read once (core/io/artcam_file.h), so warp and batch render every camera kind the same way.
//
// Memory: where the camera renders from the stored photo and the output format stores the
// input's kind of sample, the image stays in its stored pixel type (core/io/stored_image.h:
// decode and encode in bands of rows, no float copy), and renderForWarp drops the input as soon
// as the output exists, so a warp peaks at input + output and a pipeline at the images it
// holds in flight.
#pragma once

#include "app/cli/args.h"
#include "app/cli/write_args.h"
#include "core/io/artcam_file.h"
#include "core/io/image_io.h"
#include "core/io/stored_image.h"
#include "core/pipeline/render.h"
#include "core/pipeline/streamed_warp.h"

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace artcam::cli {

// A camera file read once for any number of images.
struct WarpCameraFile {
  std::string path;
  Artcam camera;
  bool linear = false;  // renders from the linear float photo (needsLinearPhoto)
};
WarpCameraFile loadWarpCamera(const std::string& path);

// A file read with the request (--depth, --second), for the command's report. Parsing prints
// nothing: the command says these with its result, on the stream its report goes to (stderr
// for -o -) or in its JSON object, so standard output carries only the image or that object.
struct RequestInput {
  struct DepthRange {
    double min = 0.0, max = 0.0;  // over the pixels with depth
    long long holes = 0;
  };
  std::string role;  // "depth" or "second" (the JSON key)
  std::string path;
  int width = 0;
  int height = 0;
  std::optional<DepthRange> depth;  // the depth map's
  std::string describe() const;     // "depth D.exr: 96x64, 1..9.5, 0 holes"
};

struct WarpRequest {
  RenderOptions options;  // filter, threads; width × height 0: the output-frame rule per input
  std::optional<ImageF> depth;  // --depth FILE, read once for every input
  std::optional<ImageF> second;  // --second FILE, linear premultiplied, for compositing cameras
  WriteImageOptions write;      // --quality, --bit-depth (write_args.h); progress unset
  std::string colour_space_in;  // --colourspace-in NAME (write_args.h); empty: as files say
  bool stats = false;
  std::string finish;  // --finish NAME: marks after the render (core/effects/finish.h); "": none
  std::vector<RequestInput> inputs;  // the depth map and second image read, in that order
};

// --size WxH, --filter, --threads, --quality, --bit-depth (and the attributed renderer's
// --depth, --depth-scale, --disparity and --second when `args` has them): the options warp and
// batch share. Writes nothing to stdout.
WarpRequest parseWarpRequest(const Args& args);

using Progress = std::function<bool(double)>;

struct DecodedInput {
  std::string input;
  std::string output;
  std::optional<StoredImage> stored;  // the stored-type path
  std::optional<LoadedImage> loaded;  // linear float (re-encoding, piecewise, attributed)
  // Too big for the stored path's memory budget: opened, not decoded; encodeWarp streams it
  // (core/pipeline/streamed_warp.h).
  std::shared_ptr<StoredImageReader> streamed;
  // Channels beyond colour and alpha (image_io.h, "Channels"): read when the output's format holds
  // them and the camera renders them (extraChannelsUnsupported), else named in left_out with the
  // reason.
  ExtraChannels extra;
  std::vector<ImagePart> parts;  // a multi-part EXR's later parts, read where the output keeps them
  std::vector<std::string> left_out;
  std::string left_out_reason;  // "out.png's format holds at most four channels"
  double megapixels() const;
};
// The stored-type path is taken only where it writes what was asked: the output format keeps
// the input's kind of sample and --bit-depth, if given, is the input's integer type. There, a
// photo whose decode and output would not fit the memory budget together is streamed instead
// when its camera is a gather warp (streamableCamera); otherwise the budget refuses it.
DecodedInput decodeForWarp(const WarpCameraFile& camera, const WarpRequest& request,
                           const std::string& input, const std::string& output,
                           const Progress& progress);

struct RenderedOutput {
  std::string output;
  std::optional<StoredImage> stored;
  std::optional<ImageF> image;
  std::shared_ptr<StoredImageReader> streamed;  // rendered while encodeWarp writes
  ImageInfo like;        // the input's format and metadata, written back
  int width = 0;
  int height = 0;
  double render_ms = 0.0;
  std::string description;  // "gather warp (homography), 12 transparent pixels"
  std::string warning;      // the output-frame rule's aspect warning, if any
  ExtraChannels extra;      // the input's extra channels, warped (written after the image's)
  std::vector<std::string> extra_names;  // their names (kept after encodeWarp frees them)
  std::vector<std::string> left_out;  // extra channels not warped (DecodedInput's)
  std::string left_out_reason;
  std::vector<ImagePart> parts;  // the input's later parts, warped (written after the image)
  bool parts_written = false;    // encodeWarp wrote them (kept after it frees them)
};
// Consumes the input (freed before returning).
RenderedOutput renderForWarp(const WarpCameraFile& camera, DecodedInput&& input,
                             const WarpRequest& request, const Progress& progress);

// Writes the output (a streamed input is rendered here, band by band, through `camera`).
void encodeWarp(RenderedOutput& output, const WarpRequest& request, const Progress& progress,
                const WarpCameraFile& camera);

// The one-line warning for extra channels left out ("IN: channels beyond colour and alpha (Z) are
// not warped and are left out of OUT: REASON"), or "" when none were.
std::string leftOutWarning(const RenderedOutput& output, const std::string& input_name,
                           const std::string& output_name);
// The one-line warning for an embedded profile dropped on read (ImageInfo::profile_dropped:
// "IN: REASON: not applied, and OUT carries no profile"), or "" when none was.
std::string droppedProfileWarning(const RenderedOutput& output, const std::string& input_name,
                                  const std::string& output_name);

}  // namespace artcam::cli
