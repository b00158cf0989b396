// SPDX-License-Identifier: Apache-2.0
// artcam batch: many photos (or a frame sequence) through one camera.
// Three stages overlap across files — decode (a thread), render (this thread, itself on all
// cores), encode (a thread) — joined by BoundedQueues of capacity 1, so about two inputs and
// two outputs are in memory at once however many files there are. The stages are warp_job.h's,
// the same code artcam warp runs. A failed file is reported and skipped; Ctrl-C stops between
// bands of rows (interrupt.h) and keeps the finished outputs.
#include "app/cli/args.h"
#include "app/cli/batch_inputs.h"
#include "app/cli/batch_lens.h"
#include "app/cli/bounded_queue.h"
#include "app/cli/commands.h"
#include "app/cli/interrupt.h"
#include "app/cli/outputs.h"
#include "app/cli/progress.h"
#include "app/cli/stdio_paths.h"
#include "app/cli/warp_job.h"
#include "core/io/atomic_file.h"

#include <nlohmann/json.hpp>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <memory>
#include <optional>
#include <system_error>
#include <thread>
#include <vector>

namespace artcam::cli {

const char* const kBatchUsage =
    "usage: artcam batch CAM.artcam IN... -o DIR [--suffix S] [--format EXT] [--first N]\n"
    "                    [--frames LIST] [--chunk K/N] [--skip-existing]\n"
    "                    [--size WxH] [--filter nearest|bilinear|bicubic] [--threads N]\n"
    "                    [--edge transparent|extend|black] [--subsampling 444|422|420]\n"
    "                    [--quality N] [--bit-depth 8|16|half|float] [--colourspace input|srgb]\n"
    "                    [--colourspace-in NAME] [--colourspace-out NAME]\n"
    "                    [--finish pencil|charcoal|painting|cartoon]\n"
    "                    [--overwrite] [--json] [--quiet]\n"
    "       artcam batch --lens-from-exif IN... -o DIR [options as above]\n\n"
    "Warps every IN through the camera into DIR (created if missing), as artcam warp does\n"
    "(upright, with IN's metadata, quality and pixel type unless --quality or --bit-depth),\n"
    "under IN's name, with --suffix added to the name and --format EXT as the extension\n"
    "(format) if given. An IN written as a printf-style pattern, e.g. frames/f_%04d.png, is a\n"
    "frame sequence: numbers from --first N (default 0, or 1 when there is no frame 0) up to\n"
    "the first missing frame, or exactly the frames of --frames (a missing one fails).\n"
    "For a render farm: --frames 1001-1100 (x2 for every other frame; lists such as\n"
    "1001,1010-1020) and --chunk K/N (the K-th of N contiguous slices of the files, sizes\n"
    "differing by at most one) split a shot into tasks whose union is the whole run; every\n"
    "output is written atomically, so a retried task is harmless, and --skip-existing lets a\n"
    "rerun do only what is missing.\n"
    "Decoding, rendering and encoding overlap across files (about two inputs and two outputs\n"
    "in memory at a time). On a terminal stderr shows a progress bar (files done, Mpix/s,\n"
    "ETA); otherwise one line per file. A file that fails gets one error line and the rest go\n"
    "on; a summary ends the run. Exit status: 0, 1 if any file failed, 130 when interrupted\n"
    "(Ctrl-C: finished outputs are kept, unfinished ones never appear).\n"
    "An output that exists already is refused unless --overwrite; one that would replace an\n"
    "input (or the camera) is always refused, as are two inputs that would write one output.\n"
    "--json prints, instead of the summary line, one JSON object {files: [{input, output,\n"
    "frame (for a pattern's frames), status (written, skipped, failed or not done), error,\n"
    "width, height, render_ms, description, warning (when IN's aspect differs from the\n"
    "camera's source frame)}], totals: {files, written, skipped, failed, not_done, seconds,\n"
    "megapixels, mpix_per_s}, frames: {done, skipped, failed, not_done} (frame numbers, or\n"
    "the input's name for a file of no pattern), chunk (with --chunk), interrupted}.\n"
    "--lens-from-exif takes no CAM.artcam: each IN is corrected by the camera artcam lens\n"
    "camera --from IN makes (its EXIF's camera, lens and focal length in the lensfun\n"
    "database, for its stored raster), one camera made per distinct camera, lens, focal\n"
    "length and size and kept for the rest, so a zoom shoot makes one per focal length. A\n"
    "photo whose EXIF gives no lens camera fails alone. Each file's line names its lens and\n"
    "focal length; --json adds lens: {model, focal_mm, crop, camera, camera_number} per file\n"
    "and lens_cameras (cameras made) to totals.\n\n"
    "options:\n"
    "  -o, --output DIR     the folder for the outputs (required)\n"
    "  --suffix S           added to each output's name before the extension (default none)\n"
    "  --format EXT         output extension, e.g. tif, png, jpg, exr (default: the input's)\n"
    "  --first N            first frame number of a pattern (default 0, else 1)\n"
    "  --frames LIST        the frames of a pattern to do: 1001-1100, 1001-1100x2, 1001,1005\n"
    "  --chunk K/N          only the K-th of N equal contiguous slices of the files\n"
    "  --skip-existing      leave outputs that exist as they are (status skipped)\n"
    "  --size WxH           output size in pixels (default: the target frame scaled to IN)\n"
    "  --filter NAME        nearest, bilinear or bicubic (default bilinear)\n"
    "  --edge MODE          what the filter reads past the edge: transparent (default: the\n"
    "                       last half pixel fades out; black in formats without alpha, as the\n"
    "                       ST maps of export-map assume), extend (the edge pixel, as Hugin's\n"
    "                       nona and fulla and OpenImageIO's clamp) or black (opaque black)\n"
    "  --threads N          render threads (default 0: all cores)\n"
    "  --quality N          JPEG quality 1-100 (default: each IN's when it and its output\n"
    "                       are JPEG, else 95)\n"
    "                       HEIC/AVIF quality (default: the encoder's); PNG: zlib level\n"
    "                       N/10 (as ImageMagick), the pixels the same\n"
    "  --subsampling S      JPEG chroma subsampling 444, 422 or 420 (default: IN's when IN and\n"
    "                       OUT are JPEG, else 420)\n"
    "  --bit-depth B        8, 16, half or float, fitted to what OUT's format stores (default:\n"
    "                       IN's)\n"
    "  --colourspace C      input or srgb: what 8/16-bit output is encoded in (default input:\n"
    "                       IN's ICC profile when it had one, embedded; srgb: sRGB, with an\n"
    "                       sRGB profile). Float output is linear Rec.709/D65, but an OpenEXR\n"
    "                       output keeps an EXR input's other primaries (ACEScg) with input\n"
    "  --colourspace-in NAME the OpenColorIO colour space the input is in, over what the\n"
    "                       file says (config: $OCIO, else OpenImageIO's built-in one)\n"
    "  --colourspace-out NAME the OpenColorIO colour space the output is encoded in\n"
    "  --finish NAME        marks after the render (G'MIC), as artcam warp --finish\n"
    "  --overwrite          replace outputs that exist (--force is the same); never an input\n"
    "  --json               the results as one JSON object on stdout (above)\n"
    "  -q, --quiet          no progress and no per-file lines (errors and summary only)\n"
    "  --lens-from-exif     each IN's lens camera from its EXIF, instead of CAM.artcam\n\n"
    "Examples:\n"
    "  artcam batch lens.artcam shoot/*.jpg -o fixed/\n"
    "  artcam batch lens.artcam frames/f_%04d.png -o out/ --format exr --suffix _warped\n"
    "  artcam batch lens.artcam plate.%04d.exr -o out/ --frames 1001-1100 --chunk 3/10\n"
    "  artcam batch --lens-from-exif zoom-shoot/*.jpg -o fixed/\n";

namespace {

struct Decoded {
  size_t index;
  DecodedInput image;
  std::shared_ptr<const WarpCameraFile> camera;  // CAM.artcam's, or the frame's lens camera
};
struct Rendered {
  size_t index;
  RenderedOutput image;
  std::shared_ptr<const WarpCameraFile> camera;
};

// One file's result for --json; each slot is written by the one stage that settles its file.
struct FileResult {
  std::string status = "not done";
  std::string error;
  int width = 0;
  int height = 0;
  double render_ms = 0.0;
  std::string description;
  std::string warning;  // warp's aspect warning (the output-frame rule, render.h), if any
  std::optional<BatchLensFrame> lens;  // --lens-from-exif: the frame's lens
};

struct BatchTally {
  std::atomic<int> written{0};
  std::atomic<int> failed{0};
  std::atomic<double> megapixels{0.0};
};

}  // namespace

int batchCommand(const std::vector<std::string>& argv) {
  const Args args(argv, {{"--output", "-o", true},       {"--suffix", "", true},
                         {"--format", "", true},         {"--first", "", true},
                         {"--frames", "", true},         {"--chunk", "", true},
                         {"--skip-existing", "", false}, {"--finish", "", true},
                         {"--size", "", true},           {"--filter", "", true},
                         {"--edge", "", true},           {"--threads", "", true},
                         {"--quality", "", true},        {"--subsampling", "", true},
                         {"--bit-depth", "", true},      {"--colourspace", "", true},
                         {"--colourspace-in", "", true}, {"--colourspace-out", "", true},
                         {"--overwrite", "", false},     {"--force", "", false},
                         {"--json", "", false},          {"--quiet", "-q", false},
                         {"--lens-from-exif", "", false}});
  const bool lens_from_exif = args.has("--lens-from-exif");
  // CAM.artcam comes first, unless each IN's camera comes from its EXIF.
  const size_t first_input = lens_from_exif ? 0 : 1;
  if (args.positional().size() < first_input + 1)
    throw UsageError(lens_from_exif ? "expected at least one IN"
                                    : "expected CAM.artcam and at least one IN");
  const auto folder = args.value("--output");
  if (!folder) throw UsageError("missing -o DIR");
  refuseStreamFolder(*folder, "batch's -o DIR");
  for (auto in = args.positional().begin() + 1; in != args.positional().end(); ++in)
    if (isStreamPath(*in))
      throw UsageError(
          "batch reads its photos by name; for one photo through standard input use "
          "artcam warp - CAM -o OUT");
  BatchNaming naming{*folder, args.valueOr("--suffix", ""), args.valueOr("--format", "")};
  if (!naming.format.empty() && naming.format.front() == '.') naming.format.erase(0, 1);
  std::optional<long> first;
  if (const auto text = args.value("--first"))
    first = static_cast<long>(parseInteger(*text, "--first", -kMaxFrameNumber, kMaxFrameNumber));
  std::optional<std::vector<long>> frames;
  if (const auto text = args.value("--frames")) {
    if (first) throw UsageError("--first and --frames both say where a pattern starts; give one");
    frames = parseFrameList(*text);
  }
  std::optional<BatchChunk> chunk;
  if (const auto text = args.value("--chunk")) chunk = parseChunk(*text);
  const bool skip_existing = args.has("--skip-existing");
  if (skip_existing && overwriteRequested(args))
    throw UsageError(
        "--skip-existing keeps outputs that exist and --overwrite replaces them; "
        "give one");
  const WarpRequest request = parseWarpRequest(args);
  const bool quiet = args.has("--quiet");

  std::vector<BatchInput> inputs;
  for (BatchInput& in : expandBatchInputs(
           std::vector<std::string>(args.positional().begin() + static_cast<long>(first_input),
                                    args.positional().end()),
           first, frames ? &*frames : nullptr)) {
    // A hidden ".name.tmp-<pid>-<n>.ext" is an unfinished save, not a photo.
    if (isAtomicTemporaryName(std::filesystem::path(in.path).filename().string())) {
      std::fprintf(stderr, "artcam batch: skipping %s: the temporary file of an unfinished save\n",
                   in.path.c_str());
      continue;
    }
    inputs.push_back(std::move(in));
  }
  if (inputs.empty()) throw CommandError("no input images");
  std::error_code ec;
  std::filesystem::create_directories(naming.folder, ec);
  if (!std::filesystem::is_directory(naming.folder))
    throw CommandError(naming.folder + ": cannot create the output folder" +
                       (ec ? ": " + ec.message() : std::string(": it is not a folder")));
  // Named over the whole shot, so every chunk's outputs are the whole run's (and clashes are
  // found whichever chunk they fall in); then this chunk's slice.
  std::vector<BatchItem> items = planBatch(inputs, naming);
  if (chunk) {
    const auto [begin, end] = chunkRange(items.size(), *chunk);
    items = std::vector<BatchItem>(items.begin() + static_cast<long>(begin),
                                   items.begin() + static_cast<long>(end));
  }
  // What this run does: every item but those --skip-existing leaves alone.
  std::vector<size_t> todo;
  std::vector<FileResult> results(items.size());
  {
    std::vector<std::string> outputs, read;
    for (const BatchInput& in : inputs) read.push_back(in.path);
    for (const BatchItem& item : items) outputs.push_back(item.output);
    if (!lens_from_exif) read.push_back(args.positional()[0]);
    // An output is never an input, skipped or not; with --skip-existing one that exists is
    // kept instead of refused.
    checkOutputs(outputs, read, overwriteRequested(args) || skip_existing);
    for (size_t i = 0; i < items.size(); ++i) {
      std::error_code exists_ec;
      if (skip_existing && std::filesystem::exists(items[i].output, exists_ec))
        results[i].status = "skipped";
      else
        todo.push_back(i);
    }
  }
  std::shared_ptr<const WarpCameraFile> fixed_camera;
  std::optional<BatchLensCameras> lens_cameras;
  if (lens_from_exif)
    lens_cameras.emplace();
  else
    fixed_camera = std::make_shared<const WarpCameraFile>(loadWarpCamera(args.positional()[0]));

  const CooperativeInterrupt interrupt;
  ProgressBar bar(static_cast<int>(todo.size()), quiet);
  BatchTally tally;
  auto fail = [&](size_t index, const std::string& message) {
    if (interruptRequested()) return;  // a cancelled stage is not the file's fault
    tally.failed.fetch_add(1);
    results[index].status = "failed";
    results[index].error = message;
    const std::string& input = items[index].input;
    // Core messages name the file already; add it only when they do not.
    bar.error("artcam batch: " + (message.find(input) == std::string::npos &&
                                          message.find(items[index].output) == std::string::npos
                                      ? input + ": " + message
                                      : message));
  };
  auto guarded = [&](size_t index, auto&& stage) {
    try {
      stage();
      return true;
    } catch (const std::exception& e) {
      fail(index, e.what());
    }
    return false;
  };
  const Progress no_report = cancelOnInterrupt();
  const auto start = std::chrono::steady_clock::now();

  BoundedQueue<Decoded> decoded(1);
  BoundedQueue<Rendered> rendered(1);
  std::thread decoder([&] {
    for (size_t k = 0; k < todo.size() && !interruptRequested(); ++k) {
      const size_t i = todo[k];
      if (!decoded.waitForSpace()) break;
      if (!guarded(i, [&] {
            std::shared_ptr<const WarpCameraFile> camera = fixed_camera;
            if (lens_cameras) {
              results[i].lens = lens_cameras->forPhoto(items[i].input);
              camera = results[i].lens->camera;
            }
            decoded.push(
                {i, decodeForWarp(*camera, request, items[i].input, items[i].output, no_report),
                 camera});
          }))
        bar.itemDone(0.0, "");
    }
    decoded.close();
  });
  std::thread encoder([&] {
    while (auto item = rendered.pop()) {
      if (interruptRequested()) break;
      const double mpix = static_cast<double>(item->image.width) * item->image.height / 1e6;
      const BatchItem& names = items[item->index];
      if (guarded(item->index,
                  [&] { encodeWarp(item->image, request, no_report, *item->camera); })) {
        tally.written.fetch_add(1);
        // A photo of another aspect than the camera's source frame is stretched: said, as warp
        // says it.
        if (!item->image.warning.empty())
          std::fprintf(stderr, "artcam batch: warning: %s: %s\n", names.input.c_str(),
                       item->image.warning.c_str());
        // Channels past RGBA that are not warped are said, never dropped silently.
        if (const std::string left_out = leftOutWarning(item->image, names.input, names.output);
            !left_out.empty())
          std::fprintf(stderr, "artcam batch: warning: %s\n", left_out.c_str());
        if (const std::string profile =
                droppedProfileWarning(item->image, names.input, names.output);
            !profile.empty())
          std::fprintf(stderr, "artcam batch: warning: %s\n", profile.c_str());
        FileResult& result = results[item->index];
        result.status = "written";
        result.width = item->image.width;
        result.height = item->image.height;
        result.render_ms = item->image.render_ms;
        result.description = item->image.description;
        result.warning = item->image.warning;
        tally.megapixels.store(tally.megapixels.load() + mpix);  // only this thread adds
        char line[64];
        std::snprintf(line, sizeof line, "%zu/%zu ", item->index + 1, items.size());
        bar.itemDone(mpix, line + names.input + " -> " + names.output + " (" +
                               std::to_string(item->image.width) + "x" +
                               std::to_string(item->image.height) + ", " + item->image.description +
                               (result.lens ? ", lens " + result.lens->choice.describe() : "") +
                               ")");
      } else {
        bar.itemDone(0.0, "");
      }
    }
    rendered.close();  // stops the renderer if this loop ended early
  });
  // Render on this thread: the warp itself uses every core.
  const Progress render_progress = cancelOnInterrupt([&](double f) { bar.itemFraction(f); });
  while (auto item = decoded.pop()) {
    if (interruptRequested() || !rendered.waitForSpace()) break;
    const size_t index = item->index;
    if (!guarded(index, [&] {
          rendered.push(
              {index,
               renderForWarp(*item->camera, std::move(item->image), request, render_progress),
               item->camera});
        }))
      bar.itemDone(0.0, "");
  }
  decoded.close();   // the decoder stops if this loop ended early
  rendered.close();  // the encoder finishes what is queued
  decoder.join();
  encoder.join();

  bar.finish();
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const int written = tally.written.load(), failed = tally.failed.load();
  const int skipped_count = static_cast<int>(items.size() - todo.size());
  const int left = static_cast<int>(todo.size()) - written - failed;
  const double mpix_per_s = seconds > 0 ? tally.megapixels.load() / seconds : 0.0;
  if (args.has("--json")) {
    nlohmann::json files = nlohmann::json::array();
    nlohmann::json by_status = {{"done", nlohmann::json::array()},
                                {"skipped", nlohmann::json::array()},
                                {"failed", nlohmann::json::array()},
                                {"not_done", nlohmann::json::array()}};
    for (size_t i = 0; i < items.size(); ++i) {
      const FileResult& f = results[i];
      nlohmann::json j = {{"input", items[i].input}, {"output", items[i].output},
                          {"status", f.status}};
      if (items[i].frame) j["frame"] = *items[i].frame;
      // Frames by number (a file of no pattern by its name), for a farm's task log.
      const nlohmann::json frame =
          items[i].frame ? nlohmann::json(*items[i].frame) : nlohmann::json(items[i].input);
      by_status[f.status == "written"    ? "done"
                : f.status == "not done" ? "not_done"
                                         : f.status]
          .push_back(frame);
      if (f.status == "failed") j["error"] = f.error;
      if (f.status == "written") {
        j["width"] = f.width;
        j["height"] = f.height;
        j["render_ms"] = f.render_ms;
        j["description"] = f.description;
        if (!f.warning.empty()) j["warning"] = f.warning;
      }
      if (f.lens) {
        const LensCameraOptions& o = f.lens->choice.options;
        j["lens"] = {{"model", o.lens},
                     {"focal_mm", o.focal_mm},
                     {"crop", o.crop},
                     {"camera", f.lens->choice.lookup.camera},
                     {"camera_number", f.lens->camera_number}};
      }
      files.push_back(j);
    }
    const nlohmann::json totals = {{"files", items.size()},
                                   {"written", written},
                                   {"skipped", skipped_count},
                                   {"failed", failed},
                                   {"not_done", left},
                                   {"seconds", seconds},
                                   {"megapixels", tally.megapixels.load()},
                                   {"mpix_per_s", mpix_per_s},
                                   {"folder", naming.folder}};
    nlohmann::json report = {{"files", files},
                             {"totals", totals},
                             {"frames", by_status},
                             {"interrupted", interruptRequested()}};
    if (chunk) report["chunk"] = {{"index", chunk->index}, {"count", chunk->count}};
    if (lens_cameras) report["totals"]["lens_cameras"] = lens_cameras->made();
    std::printf("%s\n", report.dump().c_str());
  } else {
    const std::string kept =
        skipped_count > 0 ? ", " + std::to_string(skipped_count) + " skipped (they exist)" : "";
    const std::string slice =
        chunk ? " (chunk " + std::to_string(chunk->index) + "/" + std::to_string(chunk->count) + ")"
              : "";
    std::printf("batch: %d of %zu written to %s%s%s, %d failed%s in %.1f s (%.1f Mpix/s)\n",
                written, items.size(), naming.folder.c_str(), slice.c_str(), kept.c_str(), failed,
                interruptRequested()
                    ? (", " + std::to_string(left) + " not done (interrupted)").c_str()
                    : "",
                seconds, mpix_per_s);
    if (lens_cameras)
      std::printf("batch: %d lens camera%s made from the photos' EXIF\n", lens_cameras->made(),
                  lens_cameras->made() == 1 ? "" : "s");
  }
  std::fflush(stdout);
  // 130 means work was left undone; a signal after the last file was in place changes nothing
  // on disk, so the status stays what the files say.
  if (interruptRequested() && left > 0) return interruptExitCode();
  return failed > 0 ? 1 : 0;
}

}  // namespace artcam::cli
