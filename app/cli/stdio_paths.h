// SPDX-License-Identifier: Apache-2.0
// "-" for a command's one photo (standard input) and its one image output (standard output),
// in one place for every command that offers it (core/io/standard_streams.h says how the
// streams are read and written).
//
// Dialect: `-o -` writes to standard output and needs `--format EXT` (png, jpg, exr, tif, any
// extension OpenImageIO writes), since there is no extension to choose the format from; with
// a file OUT the format follows its extension and `--format` is refused (one source of truth,
// never two that could disagree). The ImageMagick spelling `png:-` is not taken: a colon is a
// legal character in a file name, and one spelling is enough.
// With `-o -` standard output carries the image bytes and nothing else: reports ("wrote …")
// go to stderr, and `--json`, which prints on stdout, is refused as a usage error.
#pragma once

#include "app/cli/args.h"
#include "core/io/standard_streams.h"

#include <memory>
#include <string>
#include <vector>

namespace artcam::cli {

class StdioPaths {
 public:
  // `input` and `output` as typed ("-" or a path). Checks the dialect above (UsageError: exit 2);
  // nothing is read yet, so a command can finish its own usage checks first.
  // `fixed_format`: the extension of the one format the command writes (export-map's "exr");
  // `-o -` then needs no --format. "" for commands that write any image format.
  StdioPaths(const Args& args, const std::string& input, const std::string& output,
             const std::string& fixed_format = "");
  // Reads standard input when the input is "-" and makes the output's spool when it is "-";
  // throws CommandError naming the stream. The paths below are the spools' from then on.
  void open();

  // The paths the readers and writers open: the spools' for "-".
  const std::string& input() const { return input_path_; }
  const std::string& output() const { return output_path_; }
  // The names a user reads: "<stdin>"/"<stdout>" for "-", else the paths.
  const std::string& inputName() const { return input_name_; }
  const std::string& outputName() const { return output_name_; }
  bool inputIsStdin() const { return input_name_ == kStdinName; }
  bool outputIsStdout() const { return output_name_ == kStdoutName; }

  // `message` with the spool paths replaced by the stream names.
  std::string named(std::string message) const;
  // After the output was written: copies it to standard output (no-op for a file). Throws
  // CommandError naming <stdout>.
  void sendOutput() const;

 private:
  std::shared_ptr<const StdinSpool> stdin_;
  std::shared_ptr<StdoutSpool> stdout_;
  std::string input_path_, output_path_, input_name_, output_name_;
  std::string format_;  // --format, lower case
};

// Whether a command-line path means a standard stream.
inline bool isStreamPath(const std::string& path) { return path == "-"; }

// The name a report gives an output: "<stdout>" for "-", else the path.
inline std::string outputName(const std::string& path) {
  return isStreamPath(path) ? kStdoutName : path;
}

// The rule for "-" among a command's file arguments (`inputs` and `outputs` as typed), checked
// before any work (checkOutputs calls it; a command without outputs calls it itself):
// - standard input holds one file, so at most one input is "-";
// - standard output carries one file, so at most one output is "-", and `--json` (which prints
//   on it) is refused beside it;
// - an output "-" reserves standard output for the data (reserveStandardOutputForData): the
//   command's reports go to stderr.
// Throws UsageError (exit 2).
void checkStreamArguments(const Args& args, const std::vector<std::string>& inputs,
                          const std::vector<std::string>& outputs);
// Refuses "-" for an argument that names a folder (`what`: "-o DIR"): there is no stream of
// many files. Throws UsageError.
void refuseStreamFolder(const std::string& path, const std::string& what);

}  // namespace artcam::cli
