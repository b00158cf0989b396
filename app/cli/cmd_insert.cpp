// SPDX-License-Identifier: Apache-2.0
// artcam insert: a graphic rendered into a reflection or refraction and composited over the
// photo (the paper's §5, Figs 7 and 8).
#include "app/cli/args.h"
#include "app/cli/commands.h"
#include "app/cli/outputs.h"
#include "app/cli/progress.h"
#include "core/io/image_io.h"
#include "core/io/matches_csv.h"
#include "core/io/artcam_file.h"
#include "core/piecewise/piecewise_fit.h"
#include "core/piecewise/piecewise_render.h"
#include "core/pipeline/insert_graphic.h"

#include <cstdio>
#include <optional>

namespace artcam::cli {

const char* const kInsertUsage =
    "usage: artcam insert PHOTO GRAPHIC (--matches GRID.csv | --camera CAM.artcam) -o OUT\n"
    "                     [--table TABLE.csv [--grid-on-table]] [--region REGION.csv]\n"
    "                     [--max-error PX] [--save-camera FILE] [--mesh-step PX] [--overwrite]\n\n"
    "Renders GRAPHIC into the reflection or refraction seen in PHOTO and composites it over\n"
    "the photo with premultiplied alpha; with --table, also onto the table (or backdrop) the\n"
    "calibration grid lay on, as the paper's Fig 7 does.\n\n"
    "GRAPHIC stands in for the calibration grid: the matches' source points are pixels of the\n"
    "grid's canonical view, scaled to GRAPHIC's size; their targets are pixels of PHOTO.\n"
    "  --matches GRID.csv  fit a piecewise camera (src_x,src_y,dst_x,dst_y): patches are split\n"
    "                      until every patch's max error is under --max-error (default 0.5 px)\n"
    "  --camera CAM.artcam use a fitted camera (piecewise or single)\n"
    "  --canonical WxH     size of the grid's canonical view (default: GRAPHIC's size)\n"
    "  --table TABLE.csv   points of the board seen directly in PHOTO (canonical view → photo,\n"
    "                      at least 4, e.g. its corners): the board → photo homography (Fig 7b)\n"
    "                      puts GRAPHIC on the table under its reflection\n"
    "  --grid-on-table     GRID.csv's sources are photo pixels of the grid as seen on the table\n"
    "                      (Fig 7a); the --table homography takes them to the canonical view\n"
    "  --region REGION.csv the object's outline in PHOTO (x,y rows, a polygon): the reflection\n"
    "                      is kept inside it and the table's copy outside it, where the object\n"
    "                      does not hide the table\n"
    "  --save-camera FILE  also write the fitted piecewise camera\n"
    "  --mesh-step PX      lattice spacing of the mesh render, source pixels (default: a\n"
    "                      step from 64 (32 where the patches leave holes) down to 2 whose\n"
    "                      measured error is within 1/256 px)\n"
    "  -o, --output OUT    the composited image (required)\n"
    "  --overwrite         replace OUT (and FILE) if they exist (--force is the same)\n"
    "  -q, --quiet         no progress bar (drawn on stderr only when it is a terminal)\n"
    "OUT keeps PHOTO's format and metadata; it is written atomically. Neither OUT nor FILE is\n"
    "ever one of the inputs (PHOTO, GRAPHIC, the CSV files, CAM.artcam), even with --overwrite.\n\n"
    "Example:\n"
    "  artcam sample mirror-sphere -o demo && artcam insert demo/mirror-sphere.png \\\n"
    "      demo/emblem.png --matches demo/mirror-sphere-grid.csv \\\n"
    "      --table demo/mirror-sphere-table.csv --region demo/mirror-sphere-region.csv \\\n"
    "      -o inserted.png\n";

int insertCommand(const std::vector<std::string>& argv) {
  const Args args(argv, {{"--output", "-o", true},
                         {"--matches", "", true},
                         {"--camera", "", true},
                         {"--canonical", "", true},
                         {"--table", "", true},
                         {"--grid-on-table", "", false},
                         {"--region", "", true},
                         {"--max-error", "", true},
                         {"--save-camera", "", true},
                         {"--mesh-step", "", true},
                         {"--overwrite", "", false},
                         {"--force", "", false},
                         {"--quiet", "-q", false}});
  args.expectPositional(2, "PHOTO and GRAPHIC");
  const auto output = args.value("--output");
  if (!output) throw UsageError("missing -o OUT");
  if (args.has("--matches") == args.has("--camera"))
    throw UsageError("give exactly one of --matches GRID.csv and --camera CAM.artcam");
  if (args.has("--grid-on-table") && !(args.has("--table") && args.has("--matches")))
    throw UsageError("--grid-on-table needs --matches GRID.csv and --table TABLE.csv");
  const std::string& photo_path = args.positional()[0];
  {
    std::vector<std::string> outputs = {*output}, inputs = args.positional();
    if (const auto save = args.value("--save-camera")) outputs.push_back(*save);
    for (const char* read : {"--matches", "--camera", "--table", "--region"})
      if (const auto path = args.value(read)) inputs.push_back(*path);
    checkOutputs(args, outputs, inputs);
  }
  // Numbers and sizes are refused before any file is read.
  PiecewiseOptions fit_options;
  fit_options.max_error_px =
      numberOption(args, "--max-error", fit_options.max_error_px, 0, kUnbounded, Ends::OpenMin);
  RenderOptions render_options;  // mesh step 0: chosen by the renderer
  render_options.mesh_step_px =
      numberOption(args, "--mesh-step", render_options.mesh_step_px, 0, kUnbounded, Ends::OpenMin);
  std::optional<FrameSize> canonical_asked;
  if (const auto size = args.value("--canonical"))
    canonical_asked = parseSize(*size, "--canonical");

  // The image reads and the final write poll for Ctrl-C; the fit, the mesh render and the
  // camera file have no hook in core (a signal there exits at once, removing temporaries).
  return runJobStages("insert", args.has("--quiet"), [&](JobStages& job) {
    ReadImageOptions read;
    read.progress = job.polled("reading photo");
    auto photo = readImage(photo_path, read);
    if (!photo) throw CommandError(photo.status.message);
    read.progress = job.polled("reading graphic");
    const auto graphic = readImage(args.positional()[1], read);
    if (!graphic) throw CommandError(graphic.status.message);
    const FrameSize photo_size{photo->image.width, photo->image.height};
    const FrameSize canonical =
        canonical_asked.value_or(FrameSize{graphic->image.width, graphic->image.height});

    InsertionCameras cameras;
    std::string table_report;  // printed after the bar is gone
    std::optional<Camera> photo_to_board;  // --grid-on-table: the table homography's inverse
    if (const auto table_csv = args.value("--table")) {
      const auto table = readMatchesCsv(*table_csv, 2);
      if (!table) throw CommandError(table.status.message);
      job.stage("fitting the table's homography");
      const auto board_to_photo = fitBoardHomography(*table, canonical, photo_size);
      if (!board_to_photo.status) throw CommandError(*table_csv + ": " + board_to_photo.status.message);
      cameras.plane = board_to_photo.camera;
      table_report = "table homography: " + board_to_photo.report();
      if (args.has("--grid-on-table")) {
        const auto inverse = fitBoardFromPhoto(*table, canonical, photo_size);
        if (!inverse.status) throw CommandError(*table_csv + ": " + inverse.status.message);
        photo_to_board = inverse.camera;
      }
    }
    if (const auto region_csv = args.value("--region")) {
      const auto region = readPointsCsv(*region_csv);
      if (!region) throw CommandError(region.status.message);
      if (region->size() < 3)
        throw CommandError(*region_csv + ": a region needs at least 3 points, found " +
                           std::to_string(region->size()));
      cameras.region = *region;
    }

    PiecewiseCamera& camera = cameras.object;
    std::string fit_report;  // printed after the bar is gone
    if (args.has("--matches")) {
      const std::string csv = *args.value("--matches");
      auto matches = readMatchesCsv(csv, 2);
      if (!matches) throw CommandError(matches.status.message);
      if (photo_to_board) {
        for (size_t i = 0; i < matches->size(); ++i) {
          PointMatch& m = (*matches)[i];
          const auto board = targetPixelFromSourcePixel(*photo_to_board, m.source);
          if (!board)
            throw CommandError(csv + ": match " + std::to_string(i + 1) +
                               ": its grid point lies on the table homography's horizon");
          m.source = *board;
        }
      }
      job.stage("fitting");
      const PiecewiseSummary fit = fitPiecewise(*matches, canonical, photo_size, fit_options);
      if (!fit.status) throw CommandError(csv + ": " + fit.status.message);
      fit_report = fit.report();
      camera = fit.camera;
      if (const auto save = args.value("--save-camera")) {
        job.stage("writing " + *save);
        Artcam doc(camera.patches.front().camera);
        doc.matches = *matches;
        doc.pieces = camera;
        if (const Status s = writeArtcam(*save, doc); !s) throw CommandError(s.message);
      }
    } else {
      const std::string path = *args.value("--camera");
      const auto doc = readArtcam(path);
      if (!doc) throw CommandError(doc.status.message);
      for (const std::string& warning : cameraWarnings(*doc))
        std::fprintf(stderr, "artcam insert: warning: %s: %s\n", path.c_str(), warning.c_str());
      if (doc->pieces) {
        camera = *doc->pieces;
      } else {
        const Camera& single = doc->main();
        if (doc->layers.size() != 1 || single.blocks().size() != 1 || !single.sourceSize().isImage())
          throw CommandError(path + ": insert needs a 2D position camera");
        camera.source_size = single.sourceSize();
        camera.target_size = single.targetSize();
        CameraPatch whole;
        whole.rect = {0, 0, double(single.sourceSize().width), double(single.sourceSize().height)};
        whole.camera = single;
        whole.model = "single";
        camera.patches.push_back(std::move(whole));
      }
      if (camera.target_size != photo_size)
        throw CommandError(
            path + ": the camera's target frame is " + std::to_string(camera.target_size.width) +
            "x" + std::to_string(camera.target_size.height) + " but " + photo_path + " is " +
            std::to_string(photo_size.width) + "x" + std::to_string(photo_size.height));
    }

    if (cameras.plane && cameras.plane->sourceSize() != camera.source_size)
      throw CommandError(*args.value("--table") + ": the table's canonical view is " +
                         std::to_string(canonical.width) + "x" + std::to_string(canonical.height) +
                         " but the camera's source frame is " +
                         std::to_string(camera.source_size.width) + "x" +
                         std::to_string(camera.source_size.height) + " (set --canonical)");

    // One entry point with the studio's Insertion mode: the table's copy, then the reflection.
    job.stage("rendering");
    InsertSummary summary;
    ImageF composited;
    try {
      composited = insertGraphic(photo->image, graphic->image, cameras, render_options, &summary);
    } catch (const std::invalid_argument& e) {
      throw CommandError(std::string("cannot render the graphic: ") + e.what());
    }
    WriteImageOptions write;
    write.progress = job.polled("writing");
    if (const Status s = writeImage(*output, composited, &photo->info, write); !s)
      throw CommandError(s.message);
    job.finish();
    if (!table_report.empty()) std::printf("%s\n", table_report.c_str());
    if (!fit_report.empty()) std::printf("%s\n", fit_report.c_str());
    std::printf("wrote %s (%zu patches%s, render + composite %.1f ms)\n", output->c_str(),
                camera.patches.size(), cameras.plane ? " and the table" : "", summary.ms);
    return 0;
  });
}

}  // namespace artcam::cli
