// SPDX-License-Identifier: Apache-2.0
// artcam batch: many photos (or a frame sequence) through one camera.
// Three stages overlap across files — decode (a thread), render (this thread, itself on all
// cores), encode (a thread) — joined by BoundedQueues of capacity 1, so about two inputs and
// two outputs are in memory at once however many files there are. The stages are warp_job.h's,
// the same code artcam warp runs. A failed file is reported and skipped; Ctrl-C stops between
// bands of rows (interrupt.h) and keeps the finished outputs.
#include "app/cli/args.h"
#include "app/cli/batch_inputs.h"
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
#include <system_error>
#include <thread>
#include <vector>

namespace artcam::cli {

const char* const kBatchUsage =
    "usage: artcam batch CAM.artcam IN... -o DIR [--suffix S] [--format EXT] [--first N]\n"
    "                    [--size WxH] [--filter nearest|bilinear|bicubic] [--threads N]\n"
    "                    [--quality N] [--bit-depth 8|16|half|float] [--colourspace input|srgb]\n"
    "                    [--overwrite] [--json] [--quiet]\n\n"
    "Warps every IN through the camera into DIR (created if missing), as artcam warp does\n"
    "(upright, with IN's metadata, quality and pixel type unless --quality or --bit-depth),\n"
    "under IN's name, with --suffix added to the name and --format EXT as the extension\n"
    "(format) if given. An IN written as a printf-style pattern, e.g. frames/f_%04d.png, is a\n"
    "frame sequence: numbers from --first N (default 0, or 1 when there is no frame 0) up to\n"
    "the first missing frame.\n"
    "Decoding, rendering and encoding overlap across files (about two inputs and two outputs\n"
    "in memory at a time). On a terminal stderr shows a progress bar (files done, Mpix/s,\n"
    "ETA); otherwise one line per file. A file that fails gets one error line and the rest go\n"
    "on; a summary ends the run. Exit status: 0, 1 if any file failed, 130 when interrupted\n"
    "(Ctrl-C: finished outputs are kept, unfinished ones never appear).\n"
    "An output that exists already is refused unless --overwrite; one that would replace an\n"
    "input (or the camera) is always refused, as are two inputs that would write one output.\n"
    "--json prints, instead of the summary line, one JSON object {files: [{input, output,\n"
    "status (written, failed or not done), error, width, height, render_ms, description}],\n"
    "totals: {files, written, failed, not_done, seconds, megapixels, mpix_per_s},\n"
    "interrupted}.\n\n"
    "options:\n"
    "  -o, --output DIR     the folder for the outputs (required)\n"
    "  --suffix S           added to each output's name before the extension (default none)\n"
    "  --format EXT         output extension, e.g. tif, png, jpg, exr (default: the input's)\n"
    "  --first N            first frame number of a pattern (default 0, else 1)\n"
    "  --size WxH           output size in pixels (default: the target frame scaled to IN)\n"
    "  --filter NAME        nearest, bilinear or bicubic (default bilinear)\n"
    "  --threads N          render threads (default 0: all cores)\n"
    "  --quality N          JPEG quality 1-100 (default: each IN's when it and its output\n"
    "                       are JPEG, else 95)\n"
    "  --bit-depth B        8, 16, half or float, fitted to what OUT's format stores (default:\n"
    "                       IN's)\n"
    "  --colourspace C      input or srgb: what 8/16-bit output is encoded in (default input:\n"
    "                       IN's ICC profile when it had one, embedded; srgb: sRGB, with an\n"
    "                       sRGB profile). Float output is linear Rec.709/D65 either way\n"
    "  --overwrite          replace outputs that exist (--force is the same); never an input\n"
    "  --json               the results as one JSON object on stdout (above)\n"
    "  -q, --quiet          no progress and no per-file lines (errors and summary only)\n\n"
    "Examples:\n"
    "  artcam batch lens.artcam shoot/*.jpg -o fixed/\n"
    "  artcam batch lens.artcam frames/f_%04d.png -o out/ --format exr --suffix _warped\n";

namespace {

struct Decoded {
  size_t index;
  DecodedInput image;
};
struct Rendered {
  size_t index;
  RenderedOutput image;
};

// One file's result for --json; each slot is written by the one stage that settles its file.
struct FileResult {
  std::string status = "not done";
  std::string error;
  int width = 0;
  int height = 0;
  double render_ms = 0.0;
  std::string description;
};

struct BatchTally {
  std::atomic<int> written{0};
  std::atomic<int> failed{0};
  std::atomic<double> megapixels{0.0};
};

}  // namespace

int batchCommand(const std::vector<std::string>& argv) {
  const Args args(argv, {{"--output", "-o", true},
                         {"--suffix", "", true},
                         {"--format", "", true},
                         {"--first", "", true},
                         {"--size", "", true},
                         {"--filter", "", true},
                         {"--threads", "", true},
                         {"--quality", "", true},
                         {"--bit-depth", "", true},
                         {"--colourspace", "", true},
                         {"--overwrite", "", false},
                         {"--force", "", false},
                         {"--json", "", false},
                         {"--quiet", "-q", false}});
  if (args.positional().size() < 2) throw UsageError("expected CAM.artcam and at least one IN");
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
  const WarpRequest request = parseWarpRequest(args);
  const bool quiet = args.has("--quiet");

  std::vector<std::string> inputs;
  for (const std::string& in : expandBatchInputs(
           std::vector<std::string>(args.positional().begin() + 1, args.positional().end()),
           first)) {
    // A hidden ".name.tmp-<pid>-<n>.ext" is an unfinished save, not a photo.
    if (isAtomicTemporaryName(std::filesystem::path(in).filename().string())) {
      std::fprintf(stderr, "artcam batch: skipping %s: the temporary file of an unfinished save\n",
                   in.c_str());
      continue;
    }
    inputs.push_back(in);
  }
  if (inputs.empty()) throw CommandError("no input images");
  std::error_code ec;
  std::filesystem::create_directories(naming.folder, ec);
  if (!std::filesystem::is_directory(naming.folder))
    throw CommandError(naming.folder + ": cannot create the output folder" +
                       (ec ? ": " + ec.message() : std::string(": it is not a folder")));
  const std::vector<BatchItem> items = planBatch(inputs, naming);
  {
    std::vector<std::string> outputs, read = inputs;
    for (const BatchItem& item : items) outputs.push_back(item.output);
    read.push_back(args.positional()[0]);
    checkOutputs(args, outputs, read);
  }
  const WarpCameraFile camera = loadWarpCamera(args.positional()[0]);

  const CooperativeInterrupt interrupt;
  ProgressBar bar(static_cast<int>(items.size()), quiet);
  BatchTally tally;
  std::vector<FileResult> results(items.size());
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
    for (size_t i = 0; i < items.size() && !interruptRequested(); ++i) {
      if (!decoded.waitForSpace()) break;
      if (!guarded(i, [&] {
            decoded.push({i, decodeForWarp(camera, request, items[i].input, items[i].output,
                                           no_report)});
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
      if (guarded(item->index, [&] { encodeWarp(item->image, request, no_report, camera); })) {
        tally.written.fetch_add(1);
        // Channels past RGBA that are not warped are said, never dropped silently.
        if (const std::string left_out = leftOutWarning(item->image, names.input, names.output);
            !left_out.empty())
          std::fprintf(stderr, "artcam batch: warning: %s\n", left_out.c_str());
        if (const std::string profile =
                droppedProfileWarning(item->image, names.input, names.output);
            !profile.empty())
          std::fprintf(stderr, "artcam batch: warning: %s\n", profile.c_str());
        results[item->index] = {"written", "", item->image.width, item->image.height,
                                item->image.render_ms, item->image.description};
        tally.megapixels.store(tally.megapixels.load() + mpix);  // only this thread adds
        char line[64];
        std::snprintf(line, sizeof line, "%zu/%zu ", item->index + 1, items.size());
        bar.itemDone(mpix, line + names.input + " -> " + names.output + " (" +
                               std::to_string(item->image.width) + "x" +
                               std::to_string(item->image.height) + ", " + item->image.description +
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
              {index, renderForWarp(camera, std::move(item->image), request, render_progress)});
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
  const int left = static_cast<int>(items.size()) - written - failed;
  const double mpix_per_s = seconds > 0 ? tally.megapixels.load() / seconds : 0.0;
  if (args.has("--json")) {
    nlohmann::json files = nlohmann::json::array();
    for (size_t i = 0; i < items.size(); ++i) {
      const FileResult& f = results[i];
      nlohmann::json j = {{"input", items[i].input}, {"output", items[i].output},
                          {"status", f.status}};
      if (f.status == "failed") j["error"] = f.error;
      if (f.status == "written") {
        j["width"] = f.width;
        j["height"] = f.height;
        j["render_ms"] = f.render_ms;
        j["description"] = f.description;
      }
      files.push_back(j);
    }
    const nlohmann::json totals = {{"files", items.size()},
                                   {"written", written},
                                   {"failed", failed},
                                   {"not_done", left},
                                   {"seconds", seconds},
                                   {"megapixels", tally.megapixels.load()},
                                   {"mpix_per_s", mpix_per_s},
                                   {"folder", naming.folder}};
    const nlohmann::json report = {
        {"files", files}, {"totals", totals}, {"interrupted", interruptRequested()}};
    std::printf("%s\n", report.dump().c_str());
  } else {
    std::printf(
      "batch: %d of %zu written to %s, %d failed%s in %.1f s (%.1f Mpix/s)\n", written,
      items.size(), naming.folder.c_str(), failed,
      interruptRequested() ? (", " + std::to_string(left) + " not done (interrupted)").c_str() : "",
      seconds, mpix_per_s);
  }
  std::fflush(stdout);
  // 130 means work was left undone; a signal after the last file was in place changes nothing
  // on disk, so the status stays what the files say.
  if (interruptRequested() && left > 0) return interruptExitCode();
  return failed > 0 ? 1 : 0;
}

}  // namespace artcam::cli
