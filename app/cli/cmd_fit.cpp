// SPDX-License-Identifier: Apache-2.0
// artcam fit: matches CSV → .artcam (paper §4).
#include "app/cli/args.h"
#include "app/cli/commands.h"
#include "app/cli/fit_input.h"
#include "app/cli/outputs.h"
#include "app/cli/progress.h"
#include "app/cli/reports.h"
#include "app/cli/stdio_paths.h"
#include "core/colour/colour_map.h"
#include "core/fit/fit_colour.h"
#include "core/fit/fit_image.h"
#include "core/io/artcam_file.h"
#include "core/io/matches_csv.h"
#include "core/io/stmap_file.h"
#include "core/io/text_input.h"

#include <nlohmann/json.hpp>

#include <cstdio>

namespace artcam::cli {

const char* const kFitUsage =
    "usage: artcam fit MATCHES.csv -o CAM.artcam --size WxH [--target-size WxH]\n"
    "                  [--model auto|translation|similarity|affine|homography|quadratic] [--json]\n"
    "                  [--no-refine] [--robust [--threshold PX]] [--allow-poles]\n"
    "       artcam fit --piecewise MATCHES.csv -o CAM.artcam --size WxH [--target-size WxH]\n"
    "                  [--max-error PX] [--model quadratic|homography|affine] [--json]\n"
    "       artcam fit --stmap MAP.exr -o CAM.artcam [--size WxH] [--layer NAME] [--piecewise]\n"
    "                  [--model …]\n"
    "       artcam fit --lines LINES.csv [MATCHES.csv] -o CAM.artcam --size WxH\n"
    "                  [--target-size WxH] [--model auto|radial|quadratic] [--json]\n"
    "       artcam fit --flat-field FLAT.tif -o CAM.artcam [--cells N] [--json]\n"
    "       artcam fit --dim 3 MATCHES.csv -o CAM.artcam [--model …] [--json]\n"
    "       artcam fit --block colour SAMPLES.csv -o CAM.artcam --size WxH [--srgb]\n"
    "                  [--model auto|linear|affine|quadratic]\n"
    "                  [--robust [--threshold DE]] [--json]\n\n"
    "Fits a camera to point matches. MATCHES.csv has the header src_x,src_y,dst_x,dst_y\n"
    "(pixels, centres at i + 0.5). --size is the source image size; --target-size the target's\n"
    "(default: the same). --model auto (default) picks the simplest model whose held-out error\n"
    "a richer one does not beat; a named model is fitted exactly as that class (a homography\n"
    "stays a homography). The quadratic model needs at least 9 well-spread matches.\n"
    "Prints the model, match count, RMS and max residual (px); --json prints one JSON object\n"
    "{model, matches, rms_px, max_px, residuals_px, singular_values, reason, output}.\n"
    "The .artcam file keeps the matches and the fit report.\n"
    "The quadratic is refined by Levenberg–Marquardt on the reprojection error (--no-refine\n"
    "keeps the algebraic SVD solution). A camera whose denominator vanishes inside the source\n"
    "frame (a pole) is refused, after retrying from the homography and affine fits, unless\n"
    "--allow-poles. --robust samples minimal sets (MSAC with local optimisation) and fits the\n"
    "matches within --threshold px (default 3); the inlier indices are printed and stored.\n"
    "--piecewise splits the region the matches cover into patches (a quadtree) and fits one\n"
    "camera per patch (default quadratic) until every patch's max residual is under --max-error\n"
    "(default 0.5 px), at its matches and held out (each fifth of a patch's matches predicted\n"
    "by the patch fitted without them: the error between matches); neighbours share the\n"
    "matches near their edges so they agree at the seams. Matches outside --size are refused;\n"
    "the outer patches reach the frame's edges. Prints per-patch errors, the seam gap and the\n"
    "single-camera floor; --json prints {piecewise: true, patches, matches, rms_px, max_px,\n"
    "held_out_max_px, seam_gap_px, converged, max_error_px, single_rms_px, single_max_px,\n"
    "patch_list: [{rect: [x0, y0, x1, y1], model, matches, rms_px, max_px, held_out_max_px,\n"
    "within_tolerance}], output}. The file holds\n"
    "the single camera at its top level and the patches beside it (artcam insert reads them).\n"
    "--stmap MAP.exr fits the camera to an ST map made elsewhere (a Nuke lens-distortion STMap,\n"
    "or artcam export-map's): the map is sampled on a grid (every Nth pixel, at most 4000\n"
    "samples) where alpha > 0 (or alpha 0 with a position beyond the photo's edge: export-map's\n"
    "pixels that read nothing but still have a preimage), each sample a match from its source\n"
    "position to its pixel centre, and fitted as MATCHES.csv would be (also with --piecewise).\n"
    "A layered map (export-map of a per-channel camera) needs --layer R, G or B. The map is the "
    "target\n"
    "frame; the source size is --size, else the map's artcam:source_width/height, else the\n"
    "map's own size. R = x / W, G = 1 - y / H; a map with artcam:convention opencv holds\n"
    "cv::remap pixels (-1: none). Maps without R and G channels are refused.\n"
    "--lines LINES.csv calibrates a lens from straight edges: LINES.csv has the header line,x,y\n"
    "(one point per row, pixels, centres at i + 0.5; the rows with one label are one edge, at\n"
    "least 3 points each). The camera maps the photo to one in which every edge is straight;\n"
    "lines stay lines under a homography, so that freedom is fixed as the least change at the\n"
    "centre (centre kept, identity Jacobian there, no perspective tilt), unless MATCHES.csv is\n"
    "given too, whose pairs then fix it. --model radial fits u' = u / (1 - k r^2) about the\n"
    "centre, quadratic the full ratio of quadratics; auto (default) keeps the quadratic only\n"
    "when it straightens the edges clearly better. Prints each line's remaining bow (largest\n"
    "distance from its own straight line, px) before and after; --json prints {model, lines:\n"
    "[{line, points, bow_px, rms_px, bow_before_px}], rms_bow_px, max_bow_px, pairs, reason,\n"
    "radial_k, pair_rms_px, pair_max_px, pair_residuals_px, output}.\n"
    "--flat-field FLAT.tif fits the camera that corrects a lens's vignetting from a flat-field\n"
    "photo (a grey card or a white wall filling the frame, evenly lit, out of focus; decoded\n"
    "to linear light from its colour space as every input is, so an sRGB JPEG or a linear EXR\n"
    "both do, with no tone curve applied): the photo is averaged over --cells N cells\n"
    "along its longer side (default 48), each cell's gain is the axis's level over its own, and\n"
    "a radial gain (a ratio of quadratics in r², its centre found from the photo) is fitted to\n"
    "them. The camera's geometry is the identity, its frame the sensor's raster (a portrait\n"
    "flat field is turned back), its size the photo's; it composes before a lens camera\n"
    "(artcam compose). Prints the darkest cell (in percent of the axis and in EV), the axis and\n"
    "the fit's max and RMS error in percent; --json prints {flat_field, size, cells, centre_px,\n"
    "darkest, rational, max_percent, rms_percent, output}. A flat field with a black or\n"
    "non-finite region is refused, naming where.\n"
    "--dim 3 fits an object-space camera (position block (X, Y, Z, 1)) to 3D matches with the\n"
    "header src_x,src_y,src_z,dst_x,dst_y,dst_z; no sizes; the quadratic needs 13 matches.\n"
    "--block colour fits the colour block to colour samples: SAMPLES.csv has the header\n"
    "src_r,src_g,src_b,dst_r,dst_g,dst_b, LINEAR-light RGB (sRGB primaries, D65, 1 = white);\n"
    "--srgb reads sRGB-encoded values (0..1) instead. auto compares linear 3x3, affine,\n"
    "root-polynomial (degree 2) and the rational quadratic by held-out CIEDE2000 dE and keeps\n"
    "the simplest adequate one; root-polynomial is not a quadratic form, so when it wins the\n"
    "camera holds the best representable model (and --model root-polynomial is refused).\n"
    "Prints dE00 per sample, mean, median and max. --size is the size of the photos the camera\n"
    "will recolour (its geometry is the identity); --threshold is in dE00 (default 3).\n\n"
    "-o/--output names the camera file (required; written atomically). An existing one is\n"
    "refused unless --overwrite (--force is the same); it is never MATCHES.csv.\n"
    "-q/--quiet shows no progress bar (drawn on stderr only when it is a terminal).\n\n"
    "Examples:\n"
    "  artcam fit matches.csv -o lens.artcam --size 6000x4000\n"
    "  artcam fit matches.csv -o mirror.artcam --size 640x480 --piecewise --max-error 0.3\n"
    "  artcam fit --stmap lens-undistort.exr -o lens.artcam\n"
    "  artcam fit --lines edges.csv -o lens.artcam --size 6000x4000\n"
    "  artcam fit --flat-field grey-card.tif -o vignetting.artcam\n";

int fitPiecewiseCommand(const Args& args, const std::string& output, FrameSize source,
                        FrameSize target, const MatchInput& input);  // cmd_fit_piecewise.cpp
int fitLinesCommand(const Args& args, const std::string& lines_path);  // cmd_fit_lines.cpp
int fitFlatFieldCommand(const Args& args, const std::string& flat_path);  // cmd_fit_flat.cpp

namespace {

int fitColourCommand(const Args& args, const std::string& output) {
  if (args.has("--dim") || args.has("--no-refine") || args.has("--allow-poles") ||
      args.has("--target-size"))
    throw UsageError("--dim, --no-refine, --allow-poles and --target-size do not apply to --block colour");
  const auto size_text = args.value("--size");
  if (!size_text)
    throw UsageError("missing --size WxH (the size of the photos the colour camera will recolour)");
  const FrameSize frame = parseSize(*size_text, "--size");
  ColourFitOptions options;
  const std::string model_name = args.valueOr("--model", "auto");
  const auto model = colourModelFromName(model_name);
  if (!model) throw UsageError("unknown colour --model \"" + model_name + "\"");
  if (*model == ColourModel::RootPolynomial)
    throw UsageError("a root-polynomial colour map is not a quadratic form, so no ARTcam can hold "
                     "it; use --model auto to compare it with the models that can be stored");
  options.model = *model;
  options.robust = args.has("--robust");
  if (args.has("--threshold") && !options.robust)
    throw UsageError("--threshold goes with --robust");
  options.robust_threshold_de = numberOption(args, "--threshold", options.robust_threshold_de, 0,
                                             kUnbounded, Ends::OpenMin);  // dE00
  checkFitOptions(options, {{"model", "--model"}, {"robust_threshold_de", "--threshold"}});
  // No core hook here: the bar names the stage and Ctrl-C exits at once (interrupt.h).
  return runJobStages("fit", args.has("--quiet"), [&](JobStages& job) {
    const std::string& csv = args.positional()[0];
    job.stage("reading");
    const auto samples = readColourSamplesCsv(
        csv, args.has("--srgb") ? ColourEncoding::Srgb : ColourEncoding::Linear);
    if (!samples) throw CommandError(samples.status.message);
    job.stage("fitting");
    const ColourFitSummary fit = fitColourSamples(*samples, options);
    if (!fit.status) throw CommandError(csv + ": " + fit.status.message);

    job.stage("writing");
    Artcam doc(colourCamera(fit.map, frame));
    doc.matches = *samples;
    doc.fit = fit.record();
    if (const Status s = writeArtcam(output, doc); !s) throw CommandError(s.message);
    job.finish();

    if (args.has("--json")) {
      nlohmann::json j = colourFitJson(fit, options.robust);
      j["output"] = output;
      std::printf("%s\n", j.dump().c_str());
      return 0;
    }
    std::printf("%s\n", fit.report().c_str());
    if (!fit.reason.empty()) std::printf("%s\n", fit.reason.c_str());
    if (fit.held_out_de >= 0)
      std::printf("held-out mean dE00 %.4g (cross-validated)\n", fit.held_out_de);
    std::printf("dE00 per sample (enabled, in file order):");
    for (size_t k = 0; k < fit.delta_e.size(); ++k)
      std::printf("%s %zu:%.3g", k % 10 ? "" : "\n ", k + 1, fit.delta_e[k]);
    std::printf("\n");
    if (options.robust) {
      std::printf("inliers (%zu):", fit.inliers.size());
      for (int k : fit.inliers) std::printf(" %d", k + 1);
      std::printf("\n");
    }
    std::printf("wrote %s\n", outputName(output).c_str());
    return 0;
  });
}

int fitPositionCommand(const Args& args, const std::string& output, FrameSize source,
                       FrameSize target, int dimension, const MatchInput& input);
MatchInput csvInput(const std::string& csv, int dimension);
int fitStmapCommand(const Args& args, const std::string& map_path);

}  // namespace

int fitCommand(const std::vector<std::string>& argv) {
  const Args args(
      argv, {{"--output", "-o", true},   {"--size", "", true},       {"--target-size", "", true},
             {"--model", "", true},      {"--dim", "", true},        {"--no-refine", "", false},
             {"--robust", "", false},    {"--threshold", "", true},  {"--allow-poles", "", false},
             {"--json", "", false},      {"--block", "", true},      {"--srgb", "", false},
             {"--piecewise", "", false}, {"--max-error", "", true},  {"--overwrite", "", false},
             {"--force", "", false},     {"--stmap", "", true},      {"--layer", "", true},
             {"--lines", "", true},      {"--flat-field", "", true}, {"--cells", "", true},
             {"--quiet", "-q", false}});
  if (args.has("--cells") && !args.has("--flat-field"))
    throw UsageError("--cells goes with --flat-field");
  if (const auto flat = args.value("--flat-field")) {
    if (args.has("--lines")) throw UsageError("--lines does not apply to --flat-field");
    return fitFlatFieldCommand(args, *flat);
  }
  if (args.has("--layer") && !args.has("--stmap"))
    throw UsageError("--layer names a layer of a layered --stmap map");
  if (const auto lines = args.value("--lines")) return fitLinesCommand(args, *lines);
  const auto stmap = args.value("--stmap");
  if (stmap) return fitStmapCommand(args, *stmap);
  args.expectPositional(1, "MATCHES.csv");
  const auto output = args.value("--output");
  if (!output) throw UsageError("missing -o CAM.artcam");
  checkOutputs(args, {*output}, {args.positional()[0]});
  const std::string block = args.valueOr("--block", "position");
  if (block == "colour" || block == "color") return fitColourCommand(args, *output);
  if (block != "position") throw UsageError("--block expects position or colour");
  if (args.has("--srgb")) throw UsageError("--srgb goes with --block colour");
  const std::string dim = args.valueOr("--dim", "2");
  if (dim != "2" && dim != "3") throw UsageError("--dim expects 2 or 3");
  const int dimension = dim == "3" ? 3 : 2;
  FrameSize source, target;
  if (dimension == 2) {
    const auto size_text = args.value("--size");
    if (!size_text) throw UsageError("missing --size WxH (the source image size)");
    source = parseSize(*size_text, "--size");
    target = args.has("--target-size") ? parseSize(*args.value("--target-size"), "--target-size")
                                       : source;
  }
  if (args.has("--piecewise")) {
    if (dimension != 2) throw UsageError("--piecewise fits image cameras (--dim 2)");
    return fitPiecewiseCommand(args, *output, source, target, csvInput(args.positional()[0], 2));
  }
  return fitPositionCommand(args, *output, source, target, dimension,
                            csvInput(args.positional()[0], dimension));
}

namespace {

int fitPositionCommand(const Args& args, const std::string& output, FrameSize source,
                       FrameSize target, int dimension, const MatchInput& input) {
  if (args.has("--max-error")) throw UsageError("--max-error goes with --piecewise");
  FitOptions options;
  const std::string model_name = args.valueOr("--model", "auto");
  const auto model = modelClassFromName(model_name);
  if (!model) throw UsageError("unknown --model \"" + model_name + "\"");
  options.model = *model;
  options.refine = !args.has("--no-refine");
  options.require_pole_free = !args.has("--allow-poles");
  options.robust = args.has("--robust");
  if (args.has("--threshold") && !options.robust)
    throw UsageError("--threshold goes with --robust");
  options.robust_threshold_px =
      numberOption(args, "--threshold", options.robust_threshold_px, 0, kUnbounded, Ends::OpenMin);
  checkFitOptions(options, {{"model", "--model"}, {"robust_threshold_px", "--threshold"}});

  // No core hook here (the robust fit's RANSAC included): the bar names the stage and Ctrl-C
  // exits at once, the handler removing the atomic writer's temporary (interrupt.h).
  return runJobStages("fit", args.has("--quiet"), [&](JobStages& job) {
    const std::string& csv = input.name;
    job.stage("reading");
    const std::vector<PointMatch> matches = input.read();
    job.stage(options.robust ? "fitting (robust)" : "fitting");
    const FitSummary fit = dimension == 2 ? fitImageCamera(matches, source, target, options)
                                          : fitObjectCamera(matches, options);
    if (!fit.status) throw CommandError(csv + ": " + fit.status.message);

    job.stage("writing");
    Artcam doc(fit.camera);
    doc.matches = matches;
    doc.fit = fit.record;
    if (const Status s = writeArtcam(output, doc); !s) throw CommandError(s.message);
    job.finish();
    // Valid but surprising (nothing inside the target frame, a pole across part of it): written,
    // and said (coverage.h).
    for (const std::string& warning : cameraWarnings(doc))
      std::fprintf(stderr, "artcam fit: warning: %s: %s\n", outputName(output).c_str(),
                   warning.c_str());

    if (args.has("--json")) {
      nlohmann::json j = fitReportJson(fit.record, options.robust);
      j["output"] = output;
      std::printf("%s\n", j.dump().c_str());
    } else {
      std::printf("%s\n", fit.report().c_str());
      if (!fit.record.reason.empty()) std::printf("%s\n", fit.record.reason.c_str());
      if (fit.record.held_out_rms_px >= 0)
        std::printf("held-out RMS %.4g (cross-validated)\n", fit.record.held_out_rms_px);
      if (fit.record.algebraic_rms_px >= 0)
        std::printf("refined from the algebraic RMS %.4g\n", fit.record.algebraic_rms_px);
      if (fit.record.pole_checked)
        std::printf("%s over the source frame (margin %.3g)\n",
                    fit.record.pole_free ? "pole-free" : "HAS A POLE", fit.record.pole_margin);
      if (options.robust) {
        std::printf("inliers (%zu):", fit.record.inliers.size());
        for (int k : fit.record.inliers) std::printf(" %d", k + 1);
        std::printf("\n");
      }
      std::printf("wrote %s\n", outputName(output).c_str());
    }
    return 0;
  });
}

MatchInput csvInput(const std::string& csv, int dimension) {
  return {textInputName(csv), [csv, dimension] {
            auto matches = readMatchesCsv(csv, dimension);
            if (!matches) throw CommandError(matches.status.message);
            return std::move(*matches);
          }};
}

// fit --stmap: the map is read before the fit starts, since its header says the frame sizes.
int fitStmapCommand(const Args& args, const std::string& map_path) {
  if (!args.positional().empty())
    throw UsageError("unexpected argument " + args.positional()[0] +
                     ": with --stmap the map is the matches");
  const auto output = args.value("--output");
  if (!output) throw UsageError("missing -o CAM.artcam");
  for (const char* option : {"--target-size", "--dim", "--block", "--srgb"})
    if (args.has(option))
      throw UsageError(std::string(option) +
                       " does not apply to --stmap (the map is the target "
                       "frame of an image camera)");
  checkOutputs(args, {*output}, {map_path});
  StmapSampleOptions options;
  if (const auto size_text = args.value("--size"))
    options.source_px = parseSize(*size_text, "--size");
  options.layer = args.valueOr("--layer", "");
  // A map from standard input ("-") is spooled and read as a named one (standard_streams.h).
  StdioPaths streams(args, map_path, "");
  streams.open();
  const auto samples = readStmapSamples(streams.input(), options);
  if (!samples) throw CommandError(streams.named(samples.status.message));
  const std::string& map_name = streams.inputName();
  if (!args.has("--json"))
    std::printf("%s: %zu samples (every %d px) of a %dx%d %s map, source %dx%d\n",
                streams.inputName().c_str(), samples->matches.size(), samples->step,
                samples->map_px.width, samples->map_px.height,
                std::string(stmapConventionName(samples->convention)).c_str(),
                samples->source_px.width, samples->source_px.height);
  const MatchInput input{map_name, [&samples] { return samples->matches; }};
  if (args.has("--piecewise")) {
    // Patches tile the source frame; samples that read from outside it (a barrel map's corners)
    // hold no photo and would stretch the patches past the frame, so they are left out here.
    // The single camera keeps them: they constrain its shape.
    const MatchInput inside{
        map_name, [&samples, &map_name] {
          std::vector<PointMatch> kept;
          for (const PointMatch& m : samples->matches)
            if (m.source.x() >= 0 && m.source.y() >= 0 &&
                m.source.x() <= samples->source_px.width &&
                m.source.y() <= samples->source_px.height)
              kept.push_back(m);
          if (kept.empty())
            throw CommandError(map_name + ": every sample of the map reads from outside the " +
                               std::to_string(samples->source_px.width) + "x" +
                               std::to_string(samples->source_px.height) + " source frame");
          return kept;
        }};
    return fitPiecewiseCommand(args, *output, samples->source_px, samples->map_px, inside);
  }
  return fitPositionCommand(args, *output, samples->source_px, samples->map_px, 2, input);
}

}  // namespace

}  // namespace artcam::cli
