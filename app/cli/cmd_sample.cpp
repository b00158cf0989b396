// SPDX-License-Identifier: Apache-2.0
// artcam sample: the bundled environment-matting samples, made in code by ray tracing
// (the paper's Figs 7 and 8): a photo, its calibration-grid matches and a graphic to insert.
#include "app/cli/args.h"
#include "app/cli/commands.h"
#include "app/cli/memory.h"
#include "app/cli/outputs.h"
#include "app/cli/progress.h"
#include "app/cli/stdio_paths.h"
#include "core/colour/specular_pair.h"
#include "core/depth/stereo_house.h"
#include "core/io/atomic_file.h"
#include "core/io/image_io.h"
#include "core/io/matches_csv.h"
#include "core/piecewise/sample_scenes.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>

namespace artcam::cli {

const char* const kSampleUsage =
    "usage: artcam sample mirror-sphere|water-glass|glass-of-water|specular-pair|stereo-house\n"
    "                     -o DIR\n"
    "                     [--squares N]"
    " [--size WxH] [--overwrite]\n\n"
    "Ray traces a sample scene for `artcam insert` into DIR:\n"
    "  NAME.png        the photo: a chrome sphere on a table that carries a calibration\n"
    "                  checkerboard (mirror-sphere), or a glass of water in front of a\n"
    "                  checkerboard backdrop (water-glass; glass-of-water: a glass with its\n"
    "                  wall, filled to half its height, the paper's Fig 8 whole)\n"
    "  NAME-grid.csv   the checkerboard's corners seen in the reflection or refraction:\n"
    "                  src_x,src_y in the board's canonical view (512×512), dst_x,dst_y in\n"
    "                  the photo, exact to 1e-6 px\n"
    "  emblem.png      a 512×512 graphic with alpha to insert\n"
    "glass-of-water's NAME-grid.csv is the grid seen through the water; it also writes\n"
    "  glass-of-water-air-grid.csv  the grid seen through the air above the waterline\n"
    "  (insert the graphic through each: two refractions of one glass)\n"
    "mirror-sphere also writes what puts the graphic on the table too (the paper's Fig 7):\n"
    "  mirror-sphere-table.csv   grid corners seen directly on the table (canonical view →\n"
    "                            photo, the clicks that fix the board's homography)\n"
    "  mirror-sphere-region.csv  the sphere's outline in the photo (x,y), where it hides\n"
    "                            the table\n"
    "specular-pair renders the paper's Fig 6 instead, for colour calibration:\n"
    "  silver.png, green.png     a silver and a green reflector under the same lights, pixel\n"
    "                            for pixel (--size: the side, default 512)\n"
    "  specular-samples.csv      colour samples (linear RGB, silver → green) on a grid of\n"
    "                            the reflector (every side/64-th pixel), for\n"
    "                            artcam fit --block colour\n"
    "stereo-house renders a rectified stereo pair of a gabled house on a lawn (the scene of\n"
    "the paper's Fig 2), for artcam stereo:\n"
    "  house-left.png, house-right.png  the pair (the right eye 0.25 to the left eye's right)\n"
    "  house-depth.exr   the left view's true depth along the view axis (0: sky)\n"
    "  house-walls.csv   the walls the left view sees: wall,x,y rows, each wall's corners in\n"
    "                    the left image, in order\n"
    "  and prints the pair's baseline·focal for artcam stereo --baseline-focal\n"
    "options:\n"
    "  --squares N     squares along the board's side (default 24)\n"
    "  --size WxH      photo size (default 640x480)\n"
    "  -o, --output DIR  the folder to write into (required; created if missing)\n"
    "  --overwrite     replace the files if they exist (--force is the same)\n"
    "  -q, --quiet     no progress bar (drawn on stderr only when it is a terminal)\n"
    "Example:\n"
    "  artcam sample water-glass -o demo --squares 16 --size 800x600\n"
    "  artcam sample specular-pair -o fig6 && artcam fit --block colour \\\n"
    "      fig6/specular-samples.csv --size 512x512 -o relight.artcam && \\\n"
    "      artcam warp fig6/silver.png relight.artcam -o relit.png\n"
    "Then: artcam insert DIR/NAME.png DIR/emblem.png --matches DIR/NAME-grid.csv -o OUT.png\n"
    "  (mirror-sphere: add --table DIR/mirror-sphere-table.csv\n"
    "   --region DIR/mirror-sphere-region.csv for the table's copy too)\n";

namespace {

// The paper's Fig 6: the specular pair and its colour samples (core/colour/specular_pair.h).
int specularPairSample(const Args& args, const std::string& dir) {
  if (args.has("--squares")) throw UsageError("--squares is for mirror-sphere and water-glass");
  const FrameSize size = parseSize(args.valueOr("--size", "512x512"), "--size");
  if (size.width != size.height) throw UsageError("specular-pair is square: give --size NxN");
  if (size.width < 16 || size.width > 4096)
    throw UsageError("specular-pair's side must be between 16 and 4096");
  const std::filesystem::path base(dir);
  const std::string silver = (base / "silver.png").string();
  const std::string green = (base / "green.png").string();
  const std::string csv = (base / "specular-samples.csv").string();
  std::error_code ec;  // the folder first: checkOutputs checks every output's folder
  std::filesystem::create_directories(dir, ec);
  if (ec) throw CommandError(dir + ": cannot create the directory: " + ec.message());
  checkOutputs(args, {silver, green, csv}, {});
  return runJobStages("sample", args.has("--quiet"), [&](JobStages& job) {
    job.stage("rendering");
    const SpecularPair pair = makeSpecularPair(size.width);
    const std::vector<PointMatch> samples = specularSamples(pair, std::max(1, size.width / 64));
    WriteImageOptions write;
    write.progress = job.polled("writing silver.png");
    if (const Status s = writeImage(silver, pair.silver, nullptr, write); !s)
      throw CommandError(s.message);
    write.progress = job.polled("writing green.png");
    if (const Status s = writeImage(green, pair.green, nullptr, write); !s)
      throw CommandError(s.message);
    job.stage("writing specular-samples.csv");
    if (const Status s = writeColourSamplesCsv(csv, samples); !s) throw CommandError(s.message);
    job.finish();
    std::printf("wrote %s, %s, %s (%zu colour samples)\n", silver.c_str(), green.c_str(),
                csv.c_str(), samples.size());
    return 0;
  });
}

// The stereo pair of Figs 2 and 3 (core/depth/stereo_house.h), with its true depth and walls.
int stereoHouseSample(const Args& args, const std::string& dir) {
  if (args.has("--squares")) throw UsageError("--squares is for mirror-sphere and water-glass");
  const FrameSize size = parseSize(args.valueOr("--size", "640x480"), "--size");
  if (size.width < 64 || size.height < 48 || size.width > 4096 || size.height > 4096)
    throw UsageError("stereo-house's --size must be from 64x48 to 4096x4096");
  const std::filesystem::path base(dir);
  const std::string left = (base / "house-left.png").string();
  const std::string right = (base / "house-right.png").string();
  const std::string depth = (base / "house-depth.exr").string();
  const std::string walls = (base / "house-walls.csv").string();
  std::error_code ec;  // the folder first: checkOutputs checks every output's folder
  std::filesystem::create_directories(dir, ec);
  if (ec) throw CommandError(dir + ": cannot create the directory: " + ec.message());
  checkOutputs(args, {left, right, depth, walls}, {});
  return runJobStages("sample", args.has("--quiet"), [&](JobStages& job) {
    job.stage("ray tracing");
    StereoHouseScene scene;
    scene.focal_px *= size.width / 640.0;
    scene.width = size.width;
    scene.height = size.height;
    const StereoHousePair pair = renderStereoHouse(scene);
    WriteImageOptions write;
    write.progress = job.polled("writing house-left.png");
    if (const Status s = writeImage(left, pair.left, nullptr, write); !s)
      throw CommandError(s.message);
    write.progress = job.polled("writing house-right.png");
    if (const Status s = writeImage(right, pair.right, nullptr, write); !s)
      throw CommandError(s.message);
    WriteImageOptions exr;
    exr.pixel_type = "float";
    if (const Status s = writeImage(depth, pair.left_depth, nullptr, exr); !s)
      throw CommandError(s.message);
    std::string csv = "wall,x,y\n";
    char line[128];
    for (const HouseWall& w : pair.walls)
      for (const Eigen::Vector2d& p : w.left_px) {
        std::snprintf(line, sizeof line, "%s,%.17g,%.17g\n", w.name.c_str(), p.x(), p.y());
        csv += line;
      }
    if (const Status s = writeTextAtomically(walls, csv); !s) throw CommandError(s.message);
    job.finish();
    std::printf("wrote %s, %s, %s, %s\n", left.c_str(), right.c_str(), depth.c_str(),
                walls.c_str());
    std::printf("baseline-focal %.17g (artcam stereo %s %s --baseline-focal %.17g -o depth.exr)\n",
                scene.baselineFocal(), left.c_str(), right.c_str(), scene.baselineFocal());
    return 0;
  });
}

}  // namespace

int sampleCommand(const std::vector<std::string>& argv) {
  const Args args(argv, {{"--output", "-o", true},
                         {"--squares", "", true},
                         {"--size", "", true},
                         {"--overwrite", "", false},
                         {"--force", "", false},
                         {"--quiet", "-q", false}});
  args.expectPositional(1, "the sample's name");
  const auto dir = args.value("--output");
  if (!dir) throw UsageError("missing -o DIR");
  refuseStreamFolder(*dir, "sample's -o DIR");
  const int squares = intOption(args, "--squares", 24, 2, 256);
  const std::string& name = args.positional()[0];
  if (name != "mirror-sphere" && name != "water-glass" && name != "glass-of-water" &&
      name != "specular-pair" && name != "stereo-house")
    throw UsageError("unknown sample \"" + name +
                         "\" (mirror-sphere, water-glass, glass-of-water, specular-pair or "
                         "stereo-house)",
                     didYouMean(name, {"mirror-sphere", "water-glass", "glass-of-water",
                                       "specular-pair", "stereo-house"}));
  if (name == "specular-pair") return specularPairSample(args, *dir);
  if (name == "stereo-house") return stereoHouseSample(args, *dir);
  const FrameSize size = parseSize(args.valueOr("--size", "640x480"), "--size");
  checkImageMemory(size, "--size");
  const std::filesystem::path base(*dir);
  const std::string photo = (base / (name + ".png")).string();
  const std::string csv = (base / (name + "-grid.csv")).string();
  const std::string emblem = (base / "emblem.png").string();
  const bool sphere = name == "mirror-sphere";
  const bool glass = name == "glass-of-water";
  const std::string air_csv = (base / (name + "-air-grid.csv")).string();
  const std::string table_csv = (base / (name + "-table.csv")).string();
  const std::string region_csv = (base / (name + "-region.csv")).string();
  std::vector<std::string> outputs = {photo, csv, emblem};
  if (sphere) outputs.insert(outputs.end(), {table_csv, region_csv});
  if (glass) outputs.push_back(air_csv);
  std::error_code ec;  // the folder first: checkOutputs checks every output's folder
  std::filesystem::create_directories(*dir, ec);
  if (ec) throw CommandError(*dir + ": cannot create the directory: " + ec.message());
  checkOutputs(args, outputs, {});

  return runJobStages("sample", args.has("--quiet"), [&](JobStages& job) {
    // The scene makers have no progress hook: Ctrl-C while ray tracing exits at once (nothing
    // has been written yet); the image writes poll and cancel, removing their temporary.
    job.stage("ray tracing");
    SampleScene sample;
    if (sphere) {
      MirrorSphereScene scene;
      scene.focal_px = 0.9 * size.width;
      scene.floor_centre_z = 1.6;  // the board lies in front of the sphere, all of it reflected
      scene.photo_width = size.width;
      scene.photo_height = size.height;
      sample = makeMirrorSphereSample(scene, squares);
    } else if (glass) {
      GlassOfWaterScene scene;
      scene.focal_px = 0.9 * size.width;
      scene.backdrop_half = 0.75;
      scene.photo_width = size.width;
      scene.photo_height = size.height;
      sample = makeGlassOfWaterSample(scene, squares);
    } else {
      WaterGlassScene scene;
      scene.focal_px = 0.9 * size.width;
      scene.backdrop_half = 0.75;  // a small board, magnified by the water
      scene.photo_width = size.width;
      scene.photo_height = size.height;
      sample = makeWaterGlassSample(scene, squares);
    }
    WriteImageOptions write;
    write.progress = job.polled("writing " + name + ".png");
    if (const Status s = writeImage(photo, sample.photo, nullptr, write); !s)
      throw CommandError(s.message);
    job.stage("writing " + name + "-grid.csv");
    if (const Status s = writeMatchesCsv(csv, sample.grid_matches); !s)
      throw CommandError(s.message);
    if (sphere) {
      job.stage("writing " + name + "-table.csv");
      if (const Status s = writeMatchesCsv(table_csv, sample.table_matches); !s)
        throw CommandError(s.message);
      if (const Status s = writePointsCsv(region_csv, sample.region); !s)
        throw CommandError(s.message);
    }
    if (glass) {
      job.stage("writing " + name + "-air-grid.csv");
      if (const Status s = writeMatchesCsv(air_csv, sample.air_matches); !s)
        throw CommandError(s.message);
    }
    job.stage("drawing emblem.png");
    const ImageF graphic = makeEmblemGraphic(512);
    write.progress = job.polled("writing emblem.png");
    if (const Status s = writeImage(emblem, graphic, nullptr, write); !s)
      throw CommandError(s.message);
    job.finish();
    std::printf("wrote %s, %s (%zu grid corners), %s\n", photo.c_str(), csv.c_str(),
                sample.grid_matches.size(), emblem.c_str());
    if (glass)
      std::printf("wrote %s (%zu grid corners through the air)\n", air_csv.c_str(),
                  sample.air_matches.size());
    if (sphere)
      std::printf("wrote %s (%zu corners on the table), %s (%zu outline points)\n",
                  table_csv.c_str(), sample.table_matches.size(), region_csv.c_str(),
                  sample.region.size());
    return 0;
  });
}

}  // namespace artcam::cli
