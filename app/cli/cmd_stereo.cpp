// SPDX-License-Identifier: Apache-2.0
// artcam stereo: a depth map from a rectified stereo pair (core/depth/stereo_depth.h), for the
// depth block's effects (artcam warp --depth) and the studio's depth under painted planes.
#include "app/cli/args.h"
#include "app/cli/commands.h"
#include "app/cli/outputs.h"
#include "app/cli/stdio_paths.h"
#include "core/depth/stereo_depth.h"
#include "core/io/image_io.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>

namespace artcam::cli {

const char* const kStereoUsage =
    "usage: artcam stereo LEFT RIGHT -o DEPTH.exr --baseline-focal BF [--max-disparity N]\n"
    "                     [--block N] [--overwrite] [--json]\n\n"
    "Matches a rectified stereo pair (the right eye along the left's x axis, rows aligned) with\n"
    "OpenCV's semi-global matcher and writes the left image's depth, BF / disparity, as a\n"
    "one-channel float image (0 where nothing matched: occlusions, the left band the right eye\n"
    "does not see, textureless sky). Use it with artcam warp --depth DEPTH.exr or load it in\n"
    "the studio's depth panel. Prints the share of pixels matched and the depth range.\n\n"
    "options:\n"
    "  -o, --output DEPTH     the depth map: .exr, or .tif/.tiff (float)\n"
    "  --baseline-focal BF    the baseline in depth units times the focal length in pixels\n"
    "                         (required; artcam sample stereo-house prints its pair's)\n"
    "  --max-disparity N      disparities searched, 0 … N px, rounded up to a multiple of 16\n"
    "                         (default 0: a quarter of the width, at most 256)\n"
    "  --block N              the matcher's window, odd, 3 … 11 (default 5)\n"
    "  --overwrite            replace DEPTH if it exists (--force is the same)\n"
    "  --json                 {left, right, output, width, height, max_disparity,\n"
    "                         matched_share, min_depth, max_depth} on stdout\n\n"
    "Example:\n"
    "  artcam sample stereo-house -o house\n"
    "  artcam stereo house/house-left.png house/house-right.png --baseline-focal 140 \\\n"
    "      -o house/depth.exr\n";

int stereoCommand(const std::vector<std::string>& argv) {
  const Args args(argv, {{"--output", "-o", true},
                         {"--baseline-focal", "", true},
                         {"--max-disparity", "", true},
                         {"--block", "", true},
                         {"--overwrite", "", false},
                         {"--force", "", false},
                         {"--json", "", false}});
  args.expectPositional(2, "LEFT and RIGHT");
  const auto out = args.value("--output");
  if (!out) throw UsageError("missing -o DEPTH.exr");
  refuseStreamFolder(*out, "stereo's -o DEPTH");
  std::string ext = std::filesystem::path(*out).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  if (ext != ".exr" && ext != ".tif" && ext != ".tiff")
    throw UsageError(*out + ": a depth map is float: write .exr or .tif");
  if (!args.has("--baseline-focal"))
    throw UsageError("missing --baseline-focal BF (the baseline times the focal length in px)");
  StereoOptions options;
  options.baseline_focal =
      numberOption(args, "--baseline-focal", 0.0, 0.0, kUnbounded, Ends::OpenMin);
  options.max_disparity = intOption(args, "--max-disparity", 0, 0, 1024);
  options.block_size = intOption(args, "--block", 5, 3, 11);
  if (options.block_size % 2 == 0)
    throw UsageError("--block expects an odd number, got " + std::to_string(options.block_size));
  const std::string& left_path = args.positional()[0];
  const std::string& right_path = args.positional()[1];
  checkOutputs(args, {*out}, {left_path, right_path});
  auto left = readImage(left_path);
  if (!left) throw CommandError(left.status.message);
  auto right = readImage(right_path);
  if (!right) throw CommandError(right.status.message);
  StereoSummary summary;
  auto depth = depthFromStereo(left->image, right->image, options, &summary);
  if (!depth) throw CommandError(left_path + ", " + right_path + ": " + depth.status.message);
  WriteImageOptions write;
  write.pixel_type = "float";
  if (const Status s = writeImage(*out, *depth, nullptr, write); !s) throw CommandError(s.message);
  if (args.has("--json")) {
    const nlohmann::json j = {{"left", left_path},
                              {"right", right_path},
                              {"output", *out},
                              {"width", depth->width},
                              {"height", depth->height},
                              {"max_disparity", summary.max_disparity},
                              {"matched_share", summary.matched_share},
                              {"min_depth", summary.min_depth},
                              {"max_depth", summary.max_depth}};
    std::printf("%s\n", j.dump().c_str());
  } else {
    std::printf("wrote %s (%dx%d, %.1f%% matched right of the %d px band, depth %.4g … %.4g)\n",
                out->c_str(), depth->width, depth->height, 100.0 * summary.matched_share,
                summary.max_disparity, summary.min_depth, summary.max_depth);
  }
  return 0;
}

}  // namespace artcam::cli
