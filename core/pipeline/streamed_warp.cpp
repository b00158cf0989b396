// SPDX-License-Identifier: Apache-2.0
#include "core/pipeline/streamed_warp.h"

#include "core/model/pixel_buffer.h"
#include "core/util/memory_budget.h"

#include <algorithm>
#include <chrono>
#include <cstring>
#include <new>
#include <stdexcept>
#include <vector>

namespace artcam {
namespace {

// Output rows per planned band: the stored writer's band (stored_image.cpp), so each band the
// encoder asks for is rendered once.
constexpr int kPlanRows = 64;
// Photo rows decoded per read call.
constexpr int kReadRows = 16;

std::string rowsText(int first, int last) {
  return std::to_string(first) + "–" + std::to_string(last > first ? last - 1 : first);
}

}  // namespace

std::string StreamedWarpSummary::describe() const {
  return "streamed gather warp (" + kernel + "), " + std::to_string(window_rows) +
         " photo rows held at most (" + describeBytes(held_bytes) + "), " +
         std::to_string(transparent_pixels) + " transparent pixels";
}

bool streamableCamera(const Artcam& camera) { return rendersByGatherWarp(camera); }

Status streamWarp(StoredImageReader& reader, const Artcam& camera, const std::string& output,
                  const StreamedWarpOptions& options, StreamedWarpSummary* summary) {
  const auto start = std::chrono::steady_clock::now();
  StreamedWarpSummary local;
  StreamedWarpSummary& report = summary ? *summary : local;
  report = StreamedWarpSummary{};
  const std::string& input = reader.info().path;
  if (!streamableCamera(camera))
    return Status::failure(input + ": cannot warp in bands: the camera has layers, patches, colour "
                           "or depth, which render from the whole photo");
  if (reader.nextRow() != 0)
    throw std::invalid_argument("streamWarp: the reader has read rows already");
  const FrameSize source_px{reader.width(), reader.height()};
  const OutputFrame frame =
      outputFrameFor(camera, source_px, options.warp.width, options.warp.height);
  report.size = frame.size;
  report.warning = frame.warning;

  WarpOptions warp = options.warp;
  warp.progress = nullptr;  // the writer's bands report progress
  warp.antialias = false;
  std::optional<BandWarp> band_warp;
  try {
    band_warp.emplace(camera.main(), source_px, frame.size, warp);
  } catch (const std::invalid_argument& e) {
    return Status::failure(input + ": cannot warp in bands: " + e.what());
  }
  report.kernel = band_warp->kernelName();

  // The plan: each band's rows, and the first row any later band still reads.
  const int bands = (frame.size.height + kPlanRows - 1) / kPlanRows;
  std::vector<BandWarp::Rows> reads(static_cast<size_t>(bands));
  bool inside = true;
  for (int b = 0; b < bands; ++b) {
    bool band_inside = false;
    reads[static_cast<size_t>(b)] = band_warp->sourceRows(
        b * kPlanRows, std::min(frame.size.height, (b + 1) * kPlanRows), &band_inside);
    inside = inside && band_inside;
    if (options.warp.progress && !options.warp.progress(0.0)) {
      report.cancelled = true;
      return Status::failure(input + ": cancelled");
    }
  }
  std::vector<int> keep_from(static_cast<size_t>(bands) + 1, source_px.height);
  for (int b = bands - 1; b >= 0; --b) {
    const BandWarp::Rows& r = reads[static_cast<size_t>(b)];
    keep_from[static_cast<size_t>(b)] =
        std::min(keep_from[static_cast<size_t>(b) + 1], r.empty() ? source_px.height : r.first);
  }
  int decoded_end = 0, widest = 0, widest_band = 0;
  for (int b = 0; b < bands; ++b) {
    const BandWarp::Rows& r = reads[static_cast<size_t>(b)];
    if (!r.empty()) decoded_end = std::max(decoded_end, r.last);
    const int held = std::max(0, decoded_end - std::min(keep_from[static_cast<size_t>(b)], decoded_end));
    if (held > widest) widest = held, widest_band = b;
  }
  report.window_rows = widest;

  // The output keeps the photo's channels, plus alpha where the format stores it and the photo
  // had none (the renderer's coverage) unless every position is certainly inside the photo.
  const int in_channels = reader.channels();
  const bool add_alpha = reader.alphaChannel() < 0 && !inside && formatStoresAlpha(output);
  const int out_channels = in_channels + (add_alpha ? 1 : 0);
  const int out_alpha = add_alpha ? in_channels : reader.alphaChannel();
  const std::size_t sample = static_cast<std::size_t>(pixelTypeSize(reader.type()));
  const std::size_t in_row = static_cast<std::size_t>(source_px.width) * static_cast<std::size_t>(in_channels) * sample;
  const std::size_t out_row = static_cast<std::size_t>(frame.size.width) * static_cast<std::size_t>(out_channels) * sample;
  report.held_bytes = static_cast<double>(in_row) * (widest + kReadRows) +
                      2.0 * static_cast<double>(out_row) * kPlanRows;
  const double budget = options.memory_budget_bytes > 0.0 ? options.memory_budget_bytes : memoryBudgetBytes();
  if (report.held_bytes > budget) {
    const BandWarp::Rows& r = reads[static_cast<size_t>(widest_band)];
    return Status::failure(
        input + ": cannot warp in bands: output rows " +
        rowsText(widest_band * kPlanRows, std::min(frame.size.height, (widest_band + 1) * kPlanRows)) +
        " read photo rows " + rowsText(r.first, r.last) + " and later output rows read from photo row " +
        std::to_string(keep_from[static_cast<size_t>(widest_band)]) + " on: " +
        std::to_string(widest) + " rows (" + describeBytes(report.held_bytes) +
        ") held at once, more than the memory budget of " + describeBytes(budget) +
        " (ARTCAM_MAX_MEMORY_MB sets it)");
  }

  PixelBuffer window_bytes, band_bytes;
  try {
    window_bytes = PixelBuffer(in_row * static_cast<std::size_t>(widest + kReadRows), PixelBuffer::Init::Uninitialised);
    band_bytes = PixelBuffer(out_row * kPlanRows, PixelBuffer::Init::Uninitialised);
  } catch (const std::bad_alloc&) {
    return Status::failure(input + ": cannot warp in bands: not enough memory for " +
                           describeBytes(report.held_bytes));
  }
  int window_first = 0, window_end = 0;  // photo rows [window_first, window_end) in window_bytes
  // Drops the rows before `first`, then decodes up to `last` (rows nobody reads pass through).
  const auto slide = [&](int first, int last) -> Status {
    while (true) {
      const int drop = std::min(first, window_end) - window_first;
      if (drop > 0) {
        std::memmove(window_bytes.data(), window_bytes.data() + static_cast<std::size_t>(drop) * in_row,
                     static_cast<std::size_t>(window_end - window_first - drop) * in_row);
        window_first += drop;
      }
      if (window_end >= std::max(first, last)) return Status::success();
      const int count = std::min({kReadRows, std::max(first, last) - window_end, source_px.height - window_end});
      if (count <= 0) return Status::success();
      std::uint8_t* into = window_bytes.data() + static_cast<std::size_t>(window_end - window_first) * in_row;
      if (Status s = reader.read(count, into, in_row); !s) return s;
      window_end += count;
    }
  };

  int next_band = 0;
  long long transparent = 0;
  const StoredBandSource produce = [&](int y0, int y1, ConstImageView& rows) -> Status {
    ImageView band = packedView<void>(band_bytes.data(), frame.size.width, y1 - y0, out_channels,
                                      reader.type(), out_alpha);
    for (int b = y0 / kPlanRows; b * kPlanRows < y1; ++b) {
      if (b != next_band) throw std::logic_error("streamWarp: bands out of order");
      ++next_band;
      const BandWarp::Rows& r = reads[static_cast<size_t>(b)];
      const int b0 = b * kPlanRows, b1 = std::min(frame.size.height, b0 + kPlanRows);
      if (Status s = slide(keep_from[static_cast<size_t>(b)], r.empty() ? 0 : r.last); !s) return s;
      ImageView part = band;
      part.data = band.row(b0 - y0);
      part.height = b1 - b0;
      const ConstImageView window = packedView<const void>(
          window_bytes.data(), source_px.width, window_end - window_first, in_channels,
          reader.type(), reader.alphaChannel());
      transparent += band_warp->render(window, window_first, b0, b1, part);
    }
    rows = packedView<const void>(band_bytes.data(), frame.size.width, y1 - y0, out_channels,
                                  reader.type(), out_alpha);
    return Status::success();
  };
  WriteImageOptions write = options.write;
  // The writer's bands poll the caller's progress; a false answer is the cancel the summary
  // reports.
  if (options.warp.progress)
    write.progress = [&report, &progress = options.warp.progress](double done) {
      if (progress(done)) return true;
      report.cancelled = true;
      return false;
    };
  const ConstImageView shape = packedView<const void>(nullptr, frame.size.width, frame.size.height,
                                                      out_channels, reader.type(), out_alpha);
  Status written;
  try {
    written = writeStoredImageBands(output, shape, &reader.info(), write, produce);
  } catch (const std::invalid_argument& e) {
    written = Status::failure(input + ": cannot warp in bands: " + e.what());
  } catch (const std::bad_alloc&) {
    written = Status::failure(output + ": cannot write: not enough memory");
  }
  report.transparent_pixels = transparent;
  report.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return written;
}

}  // namespace artcam
