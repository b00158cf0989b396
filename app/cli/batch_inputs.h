// SPDX-License-Identifier: Apache-2.0
// artcam batch's list of work: inputs (files, or frame sequences written as a printf-style
// pattern "frame_%04d.png") and the output each one goes to.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace artcam::cli {

struct BatchNaming {
  std::string folder;  // -o DIR
  std::string suffix;  // --suffix: added to the input's stem
  std::string format;  // --format: the output's extension (no dot); empty: the input's
};

// One input: a file as named, or a frame of a pattern (then `frame` is its number).
struct BatchInput {
  std::string path;
  std::optional<long> frame;
};

struct BatchItem {
  std::string input;
  std::string output;
  std::optional<long> frame;  // the frame number, for an input from a pattern
};

// --chunk K/N: the K-th (from 1) of N contiguous slices of the work, their sizes differing by
// at most one, so N farm tasks cover every item exactly once.
struct BatchChunk {
  long index = 1;
  long count = 1;
};

// Frame numbers (--first and up) stay within ±kMaxFrameNumber, far from overflowing as they
// count up; %0Nd pads to at most kMaxFramePadding digits, more than any frame number has, so
// a width such as %099999999999999999999d is a mistake to refuse, not a name to build.
constexpr long kMaxFrameNumber = 1000000000;
constexpr int kMaxFramePadding = 32;

// A shot's frames are at most this many (a list expands to one entry per frame).
constexpr size_t kMaxListedFrames = 1000000;

// --frames: "1001-1100", with a step "1001-1100x2", single frames and lists of both
// ("1001,1010-1020x5"), as render farm managers (OpenCue, Deadline, Tractor) write them. Frames
// come out in the order written, each once. Throws UsageError naming `option` for anything else.
std::vector<long> parseFrameList(const std::string& text, const std::string& option = "--frames");

// "K/N" with 1 <= K <= N; throws UsageError naming `option`.
BatchChunk parseChunk(const std::string& text, const std::string& option = "--chunk");

// The [begin, end) of chunk K/N of `total` items.
std::pair<size_t, size_t> chunkRange(size_t total, const BatchChunk& chunk);

// Expands "name_%04d.ext" (one %d, optionally %0Nd; "%%" for a literal %). With `frames`, a
// pattern names exactly those frames, whether or not each file exists (a missing one fails as
// that frame), and an argument that is not a pattern is refused (UsageError). Without, it
// runs from `first` upward until a number has no file (first: 0, or 1 when there is no frame 0)
// and other arguments are taken as they are. Throws UsageError for a malformed pattern,
// CommandError when a pattern matches no file.
std::vector<BatchInput> expandBatchInputs(const std::vector<std::string>& arguments,
                                          std::optional<long> first,
                                          const std::vector<long>* frames = nullptr);

// The output of each input; throws CommandError when two inputs would write one output.
// (Outputs that are inputs or exist already: outputs.h, checked by the command.)
std::vector<BatchItem> planBatch(const std::vector<BatchInput>& inputs, const BatchNaming& naming);

}  // namespace artcam::cli
