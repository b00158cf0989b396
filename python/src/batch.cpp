// SPDX-License-Identifier: Apache-2.0
// The per-file work of `artcam batch`, for artcam.dask: the same plan (names of outputs) and the
// same three stages (app/cli/warp_job.h: decode, render, encode), so a frame a Dask worker writes
// is byte for byte the frame `artcam batch` writes.
#include "app/cli/batch_inputs.h"
#include "app/cli/outputs.h"
#include "app/cli/warp_job.h"
#include "core/pipeline/render.h"
#include "python/src/common.h"

#include <tuple>

namespace artcam::python {
namespace {

// batch's options that shape a frame's pixels and encoding (cmd_batch.cpp's spec, by name).
const std::vector<cli::OptionSpec> kFrameSpecs = {
    {"--size", "", true},           {"--filter", "", true},
    {"--edge", "", true},           {"--threads", "", true},
    {"--quality", "", true},        {"--subsampling", "", true},
    {"--bit-depth", "", true},      {"--colourspace", "", true},
    {"--colourspace-in", "", true}, {"--colourspace-out", "", true},
    {"--finish", "", true}};

py::list planFrames(const std::vector<std::string>& inputs, const std::string& folder,
                    const std::string& suffix, std::string format, const py::object& first,
                    const py::object& frames, const py::object& chunk) {
  std::optional<long> first_frame;
  if (!first.is_none())
    first_frame = static_cast<long>(cli::parseInteger(py::str(first).cast<std::string>(), "first",
                                                      -cli::kMaxFrameNumber, cli::kMaxFrameNumber));
  std::optional<std::vector<long>> frame_list;
  if (!frames.is_none()) {
    if (first_frame) raiseValueError("first and frames both say where a pattern starts; give one");
    frame_list = cli::parseFrameList(py::str(frames).cast<std::string>(), "frames");
  }
  if (!format.empty() && format.front() == '.') format.erase(0, 1);
  // batch's order: named over the whole shot, then the chunk's slice (cmd_batch.cpp).
  std::vector<cli::BatchItem> items = cli::planBatch(
      cli::expandBatchInputs(inputs, first_frame, frame_list ? &*frame_list : nullptr),
      {folder, suffix, format});
  size_t begin = 0, end = items.size();
  if (!chunk.is_none())
    std::tie(begin, end) =
        cli::chunkRange(items.size(), cli::parseChunk(py::str(chunk).cast<std::string>(), "chunk"));
  py::list out;
  for (size_t i = begin; i < end; ++i)
    out.append(py::make_tuple(items[i].frame ? py::object(py::int_(*items[i].frame)) : py::none(),
                              items[i].input, items[i].output));
  return out;
}

py::list warpFiles(const PyCamera& camera,
                   const std::vector<std::pair<std::string, std::string>>& items,
                   const py::dict& options) {
  const cli::WarpRequest request = cli::parseWarpRequest(argsFromKeywords(options, kFrameSpecs));
  const cli::WarpCameraFile file{camera.name, *camera.camera, needsLinearPhoto(*camera.camera)};
  struct Outcome {
    std::string status, error, description, warning;
    int width = 0, height = 0;
    double render_ms = 0.0;
  };
  std::vector<Outcome> outcomes(items.size());
  {
    py::gil_scoped_release release;
    const cli::Progress keep_going = [](double) { return true; };
    for (size_t i = 0; i < items.size(); ++i) {
      const auto& [input, output] = items[i];
      Outcome& o = outcomes[i];
      try {
        cli::RenderedOutput rendered =
            cli::renderForWarp(file, cli::decodeForWarp(file, request, input, output, keep_going),
                               request, keep_going);
        cli::encodeWarp(rendered, request, keep_going, file);
        o = {"written",
             "",
             rendered.description,
             rendered.warning,
             rendered.width,
             rendered.height,
             rendered.render_ms};
      } catch (const std::exception& e) {
        // As batch says it: core messages name the file already; added only when they do not.
        const std::string message = e.what();
        o.status = "failed";
        o.error =
            message.find(input) == std::string::npos && message.find(output) == std::string::npos
                ? input + ": " + message
                : message;
      }
    }
  }
  py::list out;
  for (size_t i = 0; i < items.size(); ++i) {
    const Outcome& o = outcomes[i];
    py::dict row;
    row["input"] = items[i].first;
    row["output"] = items[i].second;
    row["status"] = o.status;
    if (o.status == "failed") {
      row["error"] = o.error;
    } else {
      row["width"] = o.width;
      row["height"] = o.height;
      row["render_ms"] = o.render_ms;
      row["description"] = o.description;
      if (!o.warning.empty()) row["warning"] = o.warning;
    }
    out.append(row);
  }
  return out;
}

}  // namespace

void registerBatch(py::module_& m) {
  m.def("plan_frames", &planFrames, py::arg("inputs"), py::arg("folder"), py::kw_only(),
        py::arg("suffix") = "", py::arg("format") = "", py::arg("first") = py::none(),
        py::arg("frames") = py::none(), py::arg("chunk") = py::none(), R"doc(
The (frame, input, output) triples `artcam batch IN... -o FOLDER` would work through: a printf-style
pattern (frames/f_%04d.exr) expanded from `first` up to the first missing frame, or exactly the
frames of `frames` ("1001-1100x2", batch's --frames), then the slice `chunk` ("2/4", batch's
--chunk); outputs named as batch names them (`suffix` added to the stem, `format` as the
extension). `frame` is None for a file of no pattern. Raises ValueError for a malformed pattern,
frame list or chunk, and OSError for two inputs that would write one output.)doc");
  m.def(
      "check_outputs",
      [](const std::vector<std::string>& outputs, const std::vector<std::string>& inputs,
         bool overwrite) { cli::checkOutputs(outputs, inputs, overwrite); },
      py::arg("outputs"), py::arg("inputs"), py::kw_only(), py::arg("overwrite") = false,
      "Refuses (OSError, batch's message) an output that would replace an input, or that exists "
      "unless `overwrite`, or whose folder is missing.");
  m.def(
      "warp_files_options_check",
      [](const py::dict& options) {
        cli::parseWarpRequest(argsFromKeywords(options, kFrameSpecs));
      },
      py::arg("options"), "Raises ValueError (the CLI's message) for a bad warp_files option.");
  m.def("warp_files", &warpFiles, py::arg("camera"), py::arg("items"),
        py::arg("options") = py::dict(),
        R"doc(
Warps each (input, output) file pair through `camera` exactly as `artcam batch` does (the same
decode, render and encode: the same bytes), each output written atomically. `options` holds
batch's keywords: size, filter, edge, threads, quality, subsampling, bit_depth, colourspace,
colourspace_in, colourspace_out, finish. Existing outputs are replaced (the caller decides what to
skip). Returns one dict per pair: input, output, status ('written' or 'failed'), error, width,
height, render_ms, description, warning — the rows of `artcam batch --json`.)doc");
}

}  // namespace artcam::python
