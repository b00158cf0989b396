// SPDX-License-Identifier: Apache-2.0
#include "app/cli/stdio_paths.h"

#include "app/cli/commands.h"

#include <algorithm>
#include <cctype>

namespace artcam::cli {

StdioPaths::StdioPaths(const Args& args, const std::string& input, const std::string& output,
                       const std::string& fixed_format)
    : input_path_(input), output_path_(output), input_name_(input), output_name_(output) {
  const auto format = fixed_format.empty() ? args.value("--format") : std::nullopt;
  if (!fixed_format.empty()) {
    format_ = fixed_format;
    if (isStreamPath(output) && args.has("--json"))
      throw UsageError("--json prints on standard output, which -o - uses for the image");
  } else if (isStreamPath(output)) {
    if (!format)
      throw UsageError("-o - writes to standard output and needs --format EXT (png, jpg, exr, "
                       "tif, ...): there is no file extension to choose the format from");
    if (args.has("--json"))
      throw UsageError("--json prints on standard output, which -o - uses for the image");
  } else if (format) {
    throw UsageError("--format is only for -o - (standard output); " + output +
                     " gets the format of its extension");
  }
  if (format && !imageExtensionWritable(*format))
    throw UsageError("--format " + *format + ": no image format is written with that extension",
                     "try png, jpg, tif or exr");
  if (format) {
    format_ = *format;
    std::transform(format_.begin(), format_.end(), format_.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  }
  if (isStreamPath(input)) input_name_ = kStdinName;
  if (isStreamPath(output)) output_name_ = kStdoutName;
}

void StdioPaths::open() {
  // Refused before standard input is read: nothing could be sent.
  if (isStreamPath(output_path_) && standardOutputWasClosed())
    throw CommandError(kStdoutName + ": cannot write: standard output is closed");
  // Standard input first: a Ctrl-C while it is read leaves no spool folder behind.
  if (isStreamPath(input_path_)) {
    auto spool = StdinSpool::read();
    if (!spool) throw CommandError(spool.status.message);
    stdin_ = *spool;
    input_path_ = stdin_->path();
  }
  if (isStreamPath(output_path_)) {
    auto spool = StdoutSpool::create(format_);
    if (!spool) throw CommandError(spool.status.message);
    stdout_ = *spool;
    output_path_ = stdout_->path();
  }
}

std::string StdioPaths::named(std::string message) const {
  if (stdin_) message = stdin_->named(std::move(message));
  if (stdout_) message = stdout_->named(std::move(message));
  return message;
}

void StdioPaths::sendOutput() const {
  if (!stdout_) return;
  if (const Status sent = stdout_->send(); !sent) throw CommandError(sent.message);
}

void checkStreamArguments(const Args& args, const std::vector<std::string>& inputs,
                          const std::vector<std::string>& outputs) {
  const auto streams = [](const std::vector<std::string>& paths) {
    return std::count_if(paths.begin(), paths.end(), isStreamPath);
  };
  if (streams(inputs) > 1)
    throw UsageError(
        "two inputs are \"-\": standard input holds one file; give the others by name");
  if (streams(outputs) > 1)
    throw UsageError(
        "two outputs are \"-\": standard output carries one file; give the others "
        "by name");
  if (streams(outputs) == 0) return;
  if (args.has("--json"))
    throw UsageError("--json prints on standard output, which -o - uses for the file");
  reserveStandardOutputForData();
}

void refuseStreamFolder(const std::string& path, const std::string& what) {
  if (isStreamPath(path))
    throw UsageError(what + " names a folder for many files; \"-\" (standard output) carries one");
}

}  // namespace artcam::cli
