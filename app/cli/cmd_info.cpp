// SPDX-License-Identifier: Apache-2.0
// artcam info: what a camera file holds, for every camera kind: blocks, structure, frames,
// layers, patches, outputs, tensors and the fit report. A file that is not a camera is named
// for what it looks like.
#include "app/cli/args.h"
#include "app/cli/commands.h"
#include "core/fit/poles.h"
#include "core/io/artcam_file.h"
#include "core/io/image_checks.h"
#include "core/io/text_input.h"
#include "core/model/structure.h"
#include "core/piecewise/piecewise_fit.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>

namespace artcam::cli {

const char* const kInfoUsage =
    "usage: artcam info CAM.artcam [--json]\n\n"
    "Prints what the camera is (single, chained, attributed, layered or piecewise), its\n"
    "blocks, its structure (which parts are zero; geometry identity, translation, affine,\n"
    "homography or rational), its frames, its layers and what its depth output means, its\n"
    "patches (count, largest fit error, seam continuity: the largest gap between neighbouring\n"
    "patches along shared edges), its tensors (normalised frame) and the fit report it came\n"
    "from, if any. A file that is not a camera is refused, saying what it looks like.\n\n"
    "options:\n"
    "  --json    the same as one JSON object (tensors left out)\n\n"
    "Example:\n"
    "  artcam info lens.artcam\n";

namespace {

// A few bytes are enough to tell the user what they gave us instead of a camera.
std::string lookalike(const std::string& path) {
  // Only a regular file is opened: a named pipe would block the open (readArtcam refused it).
  if (!image_checks::regularFile(path)) return "";
  std::ifstream in(path, std::ios::binary);
  char head[512] = {};
  in.read(head, sizeof head);
  const std::string whole(head, static_cast<size_t>(in.gcount()));
  if (const std::string movie = image_checks::movieContainer(whole); !movie.empty())
    return "a movie (" + movie + ")";
  const std::string h = whole.substr(0, 16);
  const auto starts = [&](const char* magic, size_t n) { return h.compare(0, n, magic, n) == 0; };
  if (starts("\x89PNG", 4)) return "a PNG image";
  if (starts("\xff\xd8\xff", 3)) return "a JPEG image";
  if (starts("II*\0", 4) || starts("MM\0*", 4)) return "a TIFF image";
  if (starts("\x76\x2f\x31\x01", 4)) return "an OpenEXR image";
  if (starts("GIF8", 4)) return "a GIF image";
  if (starts("ply", 3)) return "a PLY point cloud";
  if (h.find("src_x") != std::string::npos || h.find("src_r") != std::string::npos)
    return "a CSV table (matches or colour samples)";
  if (!h.empty() && h[0] == '{') return "";  // JSON: the reader's message says what is wrong
  for (const char c : h)
    if (static_cast<unsigned char>(c) < 9 || (c > 13 && c < 32)) return "a binary file";
  return "";
}

// A number for a message or JSON: never "nan" (a NaN becomes null / "n/a").
nlohmann::json finiteOrNull(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(); }

}  // namespace

int infoCommand(const std::vector<std::string>& argv) {
  const Args args(argv, {{"--json", "", false}});
  args.expectPositional(1, "CAM.artcam");
  const std::string& path = args.positional()[0];
  const auto read = readArtcam(path);
  if (!read) {
    const std::string looks = lookalike(path);
    if (!looks.empty())
      throw CommandError(path + ": not an ARTcam camera: it looks like " + looks);
    throw CommandError(read.status.message);
  }
  const Artcam& artcam = *read;
  const Camera& camera = artcam.main();
  const CameraStructure structure = analyseStructure(camera);
  const PoleCheck poles = checkPoles(camera);

  nlohmann::json j;
  j["file"] = textInputName(path);
  j["kind"] = std::string(artcamKindName(artcam.kind()));
  nlohmann::json blocks = nlohmann::json::array();
  for (const Block& b : camera.blocks())
    blocks.push_back({{"kind", std::string(blockKindName(b.kind))}, {"size", b.size}});
  j["blocks"] = blocks;
  j["structure"] = structure.summary;
  j["frames"] = {{"source", {camera.sourceSize().width, camera.sourceSize().height}},
                 {"target", {camera.targetSize().width, camera.targetSize().height}}};
  j["stages"] = camera.stages().size();
  j["layers"] = artcam.layers.size();
  j["depth_output"] = std::string(depthOutputName(artcam.depth_output));
  if (artcam.frame) j["frame"] = std::string(cameraFrameName(*artcam.frame));
  j["poles"] = poles.describe();
  if (artcam.pieces) {
    const PiecewiseCamera& p = *artcam.pieces;
    double max_px = 0.0, worst_rms = 0.0;
    int matches = 0, outside = 0;
    for (const CameraPatch& patch : p.patches) {
      if (std::isfinite(patch.max_px)) max_px = std::max(max_px, patch.max_px);
      if (std::isfinite(patch.rms_px)) worst_rms = std::max(worst_rms, patch.rms_px);
      matches += patch.matches;
      outside += patch.within_tolerance ? 0 : 1;
    }
    j["patches"] = {{"count", p.patches.size()},
                    {"matches", matches},
                    {"max_fit_error_px", finiteOrNull(max_px)},
                    {"worst_patch_rms_px", finiteOrNull(worst_rms)},
                    {"seam_gap_px", finiteOrNull(measureSeamGap(p))},
                    {"support_margin_px", p.support_margin_px}};
    if (p.patch_frame)  // a homography composed before the patches (core/model/compose.h)
      j["patches"]["patch_frame"] = {p.patch_frame->size.width, p.patch_frame->size.height};
  }
  if (artcam.fit) {
    const FitRecord& f = *artcam.fit;
    j["fit"] = {{"model", f.model}, {"matches", f.matches}, {"rms_px", finiteOrNull(f.rms_px)},
                {"max_px", finiteOrNull(f.max_px)}, {"reason", f.reason}};
  }
  j["matches"] = artcam.matches.size();
  if (args.has("--json")) {
    std::printf("%s\n", j.dump().c_str());
    return 0;
  }

  std::printf("file:      %s\n", textInputName(path).c_str());
  std::printf("kind:      %s\n", std::string(artcamKindName(artcam.kind())).c_str());
  std::printf("blocks:   ");
  for (const Block& b : camera.blocks())
    std::printf(" %s(%d)", std::string(blockKindName(b.kind)).c_str(), b.size);
  std::printf("\nstructure: %s\n", structure.summary.c_str());
  std::printf("frames:    source %dx%d, target %dx%d (tensors in the normalised frames)\n",
              camera.sourceSize().width, camera.sourceSize().height, camera.targetSize().width,
              camera.targetSize().height);
  if (artcam.frame)
    std::printf("made for:  the %s\n", *artcam.frame == CameraFrame::Sensor
                                           ? "sensor's raster (applied before the EXIF turn)"
                                           : "upright photo (applied after the EXIF turn)");
  std::printf("poles:     %s\n", poles.describe().c_str());
  if (artcam.layers.size() > 1)
    std::printf("layers:    %zu (the picture is the sum of the layers' colours)\n",
                artcam.layers.size());
  if (camera.layout().find(BlockKind::SecondColour) >= 0)
    std::printf("inputs:    a second image composited with the photo (artcam warp --second FILE)\n");
  if (camera.layout().find(BlockKind::Depth) >= 0)
    std::printf("outputs:   depth block holds %s\n",
                artcam.depth_output == DepthOutput::BlurVariance
                    ? "the blur variance σ² (depth of field)"
                    : "a depth");
  if (artcam.pieces) {
    const auto& p = j["patches"];
    const auto num = [](const nlohmann::json& v) { return v.is_null() ? std::string("n/a") : std::to_string(v.get<double>()); };
    std::printf("patches:   %zu, %d matches, largest fit error %s px, worst patch RMS %s px, "
                "seam gap %s px\n",
                artcam.pieces->patches.size(), p["matches"].get<int>(),
                num(p["max_fit_error_px"]).c_str(), num(p["worst_patch_rms_px"]).c_str(),
                num(p["seam_gap_px"]).c_str());
    if (artcam.pieces->patch_frame)
      std::printf("           rectangles in a %dx%d patch frame, reached through the homography "
                  "composed before them\n",
                  artcam.pieces->patch_frame->size.width, artcam.pieces->patch_frame->size.height);
  }
  if (structure.geometry != GeometryClass::Rational && structure.homography.size() > 0) {
    std::printf("homography (target_from_source, normalised, column form):\n");
    for (Eigen::Index r = 0; r < structure.homography.rows(); ++r) {
      std::printf("  ");
      for (Eigen::Index c = 0; c < structure.homography.cols(); ++c)
        std::printf(" %14.8g", structure.homography(r, c));
      std::printf("\n");
    }
  }
  for (size_t l = 0; l < artcam.layers.size(); ++l) {
    const Camera& layer = artcam.layers[l];
    for (size_t s = 0; s < layer.stages().size(); ++s)
      for (size_t i = 0; i < layer.stages()[s].q.size(); ++i) {
        const Eigen::MatrixXd& q = layer.stages()[s].q[i];
        if (artcam.layers.size() > 1) std::printf("layer %zu ", l + 1);
        std::printf("stage %zu Q_%zu:\n", s + 1, i + 1);
        for (Eigen::Index r = 0; r < q.rows(); ++r) {
          std::printf("  ");
          for (Eigen::Index c = 0; c < q.cols(); ++c) std::printf(" %14.8g", q(r, c));
          std::printf("\n");
        }
      }
  }
  if (artcam.fit) {
    const FitRecord& f = *artcam.fit;
    std::printf("fit:       %s, %d matches, RMS %.4g px, max %.4g px\n", f.model.c_str(), f.matches,
                f.rms_px, f.max_px);
    if (!f.reason.empty()) std::printf("           %s\n", f.reason.c_str());
  }
  std::printf("matches:   %zu stored\n", artcam.matches.size());
  return 0;
}

}  // namespace artcam::cli
