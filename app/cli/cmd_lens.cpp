// SPDX-License-Identifier: Apache-2.0
// artcam lens: lenses of the lensfun database (core/lens): search them, and write the camera
// that corrects (or simulates) one at a focal length.
#include "app/cli/args.h"
#include "app/cli/commands.h"
#include "app/cli/outputs.h"
#include "app/cli/reports.h"
#include "app/cli/stdio_paths.h"
#include "core/io/artcam_file.h"
#include "core/lens/lens_camera.h"
#include "core/lens/lens_database.h"
#include "core/lens/photo_lens.h"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <optional>

namespace artcam::cli {

const char* const kLensUsage =
    "usage: artcam lens search TEXT... [--limit N] [--json]\n"
    "       artcam lens camera --lens NAME --focal MM --size WxH -o CAM.artcam [--crop C]\n"
    "                          [--aperture F] [--distance M] [--distort] [--no-tca]\n"
    "                          [--no-vignetting] [--max-error PX] [--json]\n"
    "       artcam lens camera --from PHOTO -o CAM.artcam [--crop C] [--aperture F]\n"
    "                          [--distance M] [--distort] [--no-tca] [--no-vignetting]\n"
    "                          [--max-error PX] [--json]\n\n"
    "Lenses from the lensfun database (Debian's liblensfun-data-v1).\n\n"
    "search lists the lenses whose maker and model hold every word of TEXT (case-insensitive),\n"
    "an exact name first, with the focal range, the crop factor of the camera they were\n"
    "calibrated on, the projection and what the database has (distortion, TCA, vignetting).\n"
    "When no name holds every word, lensfun's own match is used (words split at punctuation\n"
    "too, so \"nikon 50mm 1.4\" finds \"Nikon AF-S Nikkor 50mm f/1.4G\"), then its loose match\n"
    "(some of the words, best first), and the output says so.\n"
    "--limit N shows at most N (default 50; 0: all). --json prints {lenses: [{maker, model,\n"
    "min_focal_mm, max_focal_mm, crop_factor, type, distortion, tca, vignetting}], found,\n"
    "match (words, lensfun, lensfun-loose or none)}.\n\n"
    "camera writes the camera that corrects a photo taken with lens NAME (its model as search\n"
    "prints it) at focal length --focal MM: source = the photo as shot, target = the\n"
    "corrected photo, both --size WxH (the photo's pixels). --distort writes the reverse,\n"
    "which makes a clean picture look shot through the lens. lensfun's own conventions hold:\n"
    "its modifier's normalisation, --crop C the crop factor of the camera the photo was taken\n"
    "with (default: the lens's calibration crop factor; of several calibrations the nearest\n"
    "is used), scale 1, a fisheye converted to rectilinear. lensfun's map is sampled on a grid\n"
    "and fitted as artcam fit --stmap fits a map; the camera is checked against lensfun's own\n"
    "coordinates on a denser grid: a single camera when its max error is within --max-error\n"
    "(default 0.5 px), else a piecewise one fitted to that threshold. Where the database has\n"
    "transverse chromatic aberration (TCA) the camera is three colour layers, one per channel\n"
    "(--no-tca: geometry only; a piecewise camera cannot be layered, so it leaves TCA out and\n"
    "says so). Where the database has vignetting and the aperture is known (--aperture F, the\n"
    "f-number; --distance M the focus distance in metres, default 1000), the camera also\n"
    "corrects (--distort: adds) it: a radial gain on colour at the photo's point, fitted to\n"
    "lensfun's own colour modifier and checked against it in percent (--no-vignetting: leave\n"
    "it out; a piecewise camera leaves it out and says so). Prints the lens, the error against\n"
    "lensfun (max and RMS over the checked points the camera maps; those it gives no image\n"
    "are counted apart) and notes; --json prints {lens, crop, focal_mm, piecewise, patches,\n"
    "single_max_px, single_rms_px, max_px, rms_px, checked, unmapped, within_tolerance, tca,\n"
    "tca_max_px, aperture, distance_m, vignetting, vignetting_max_percent,\n"
    "vignetting_rms_percent, notes, output}.\n\n"
    "--from PHOTO takes the lens, the focal length and the size from the photo: its EXIF make\n"
    "and model find lensfun's camera (its crop factor is --crop's default), its lens model the\n"
    "lens among those that fit it (lensfun's match, strict then loose; a compact without a\n"
    "lens name its one lens), its focal length --focal, its f-number and subject distance\n"
    "--aperture and --distance (unless given), and its stored raster (the sensor's\n"
    "pixels, before any EXIF turn) --size; --lens, --focal and --size are then refused. A\n"
    "photo without that EXIF, or whose lens lensfun does not know, is refused in one line\n"
    "naming what was missing or searched. The report (and --json's photo, camera, lens_match)\n"
    "says what the EXIF chose.\n\n"
    "-o/--output names the camera file (required; written atomically). An existing one is\n"
    "refused unless --overwrite (--force is the same).\n\n"
    "Examples:\n"
    "  artcam lens search canon 10-22\n"
    "  artcam lens camera --lens \"Canon EF-S 10-22mm f/3.5-4.5 USM\" --focal 10 \\\n"
    "      --size 6000x4000 -o efs10-22.artcam\n"
    "  artcam warp photo.jpg efs10-22.artcam -o corrected.jpg\n"
    "  artcam lens camera --from photo.jpg -o photo-lens.artcam\n";

namespace {

std::shared_ptr<const LensDatabase> loadDatabase() {
  auto db = LensDatabase::load();
  if (!db) throw CommandError(db.status.message);
  return *db.value;
}

int searchCommand(const std::vector<std::string>& argv) {
  const Args args(argv, {{"--limit", "", true}, {"--json", "", false}});
  if (args.positional().empty()) throw UsageError("missing the TEXT to search for");
  std::string text;
  for (const std::string& w : args.positional()) text += (text.empty() ? "" : " ") + w;
  const int limit = intOption(args, "--limit", 50, 0, 1000000);  // 0: all
  const auto db = loadDatabase();
  LensSearchMatch match = LensSearchMatch::None;
  const std::vector<LensEntry> hits = db->search(text, 0, &match);
  const size_t shown = limit > 0 ? std::min(hits.size(), static_cast<size_t>(limit)) : hits.size();
  if (args.has("--json")) {
    nlohmann::json lenses = nlohmann::json::array();
    for (size_t i = 0; i < shown; ++i) lenses.push_back(lensEntryJson(hits[i]));
    std::printf("%s\n", nlohmann::json{{"lenses", lenses},
                                       {"found", hits.size()},
                                       {"match", lensSearchMatchName(match)}}
                            .dump()
                            .c_str());
    return 0;
  }
  if (match == LensSearchMatch::Lensfun || match == LensSearchMatch::LensfunLoose)
    std::printf("no lens holds every word of \"%s\" as a word's start; lensfun's %s match:\n",
                text.c_str(), match == LensSearchMatch::Lensfun ? "own" : "loose");
  for (size_t i = 0; i < shown; ++i) std::printf("%s\n", hits[i].describe().c_str());
  if (hits.empty())
    std::printf("no lens in the lensfun database (%d lenses) holds every word of \"%s\"\n",
                db->size(), text.c_str());
  else if (shown < hits.size())
    std::printf("(%zu more; --limit 0 shows all)\n", hits.size() - shown);
  return 0;
}

int cameraCommand(const std::vector<std::string>& argv) {
  const Args args(argv, {{"--lens", "", true},
                         {"--from", "", true},
                         {"--focal", "", true},
                         {"--crop", "", true},
                         {"--size", "", true},
                         {"--output", "-o", true},
                         {"--distort", "", false},
                         {"--no-tca", "", false},
                         {"--no-vignetting", "", false},
                         {"--aperture", "", true},
                         {"--distance", "", true},
                         {"--max-error", "", true},
                         {"--json", "", false},
                         {"--overwrite", "", false},
                         {"--force", "", false}});
  if (!args.positional().empty())
    throw UsageError("unexpected argument " + args.positional()[0] +
                     " (the lens is named by --lens NAME)");
  LensCameraOptions options;
  const auto from = args.value("--from");
  if (from) {
    for (const char* given : {"--lens", "--focal", "--size"})
      if (args.has(given))
        throw UsageError(std::string(given) + " cannot go with --from PHOTO (the photo gives it)");
  } else {
    const auto lens = args.value("--lens");
    if (!lens)
      throw UsageError("missing --lens NAME or --from PHOTO (artcam lens search lists names)");
    options.lens = *lens;
    if (!args.has("--focal")) throw UsageError("missing --focal MM (the focal length)");
    options.focal_mm = parseNumber(*args.value("--focal"), "--focal", 0, kUnbounded, Ends::OpenMin);
    const auto size = args.value("--size");
    if (!size) throw UsageError("missing --size WxH (the photo's size)");
    options.size = parseSize(*size, "--size");
  }
  options.crop = numberOption(args, "--crop", options.crop, 0, kUnbounded, Ends::OpenMin);
  options.max_error_px =
      numberOption(args, "--max-error", options.max_error_px, 0, kUnbounded, Ends::OpenMin);
  options.distort = args.has("--distort");
  options.tca = !args.has("--no-tca");
  options.vignetting = !args.has("--no-vignetting");
  options.aperture =
      numberOption(args, "--aperture", options.aperture, 0, kUnbounded, Ends::OpenMin);
  options.distance_m =
      numberOption(args, "--distance", options.distance_m, 0, kUnbounded, Ends::OpenMin);
  const auto output = args.value("--output");
  if (!output) throw UsageError("missing -o CAM.artcam");
  checkOutputs(args, {*output},
               from ? std::vector<std::string>{*from} : std::vector<std::string>{});

  const auto db = loadDatabase();
  std::optional<PhotoLensChoice> choice;
  if (from) {
    Result<PhotoLensChoice> chosen = lensForPhoto(*db, *from, options);
    if (!chosen) throw CommandError(chosen.status.message);
    choice = std::move(*chosen.value);
    options = choice->options;
  }
  const LensCameraSummary s = lensCamera(*db, options);
  if (!s.status)
    throw CommandError(choice ? *from + ": " + choice->describe() + ": " + s.status.message
                              : s.status.message);
  if (const Status w = writeArtcam(*output, s.camera); !w) throw CommandError(w.message);
  if (args.has("--json")) {
    nlohmann::json j = lensCameraJson(s, options, choice ? &*choice : nullptr, from.value_or(""));
    j["output"] = *output;
    std::printf("%s\n", j.dump().c_str());
    return 0;
  }
  if (choice)
    std::printf("%s: %s, %dx%d (from its EXIF: %s)\n", from->c_str(), choice->describe().c_str(),
                options.size.width, options.size.height, choice->lookup.searched().c_str());
  std::printf("%s\nwrote %s\n", s.report().c_str(), outputName(*output).c_str());
  return 0;
}

}  // namespace

int lensCommand(const std::vector<std::string>& argv) {
  if (argv.empty()) throw UsageError("lens what? \"search\" or \"camera\"");
  const std::vector<std::string> rest(argv.begin() + 1, argv.end());
  if (argv[0] == "search") return searchCommand(rest);
  if (argv[0] == "camera") return cameraCommand(rest);
  throw UsageError("lens what? \"search\" or \"camera\"", didYouMean(argv[0], {"search", "camera"}));
}

}  // namespace artcam::cli
