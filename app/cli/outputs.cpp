// SPDX-License-Identifier: Apache-2.0
#include "app/cli/outputs.h"

#include "app/cli/commands.h"
#include "app/cli/stdio_paths.h"
#include "core/io/atomic_file.h"

#include <filesystem>
#include <system_error>

namespace artcam::cli {

namespace fs = std::filesystem;

bool overwriteRequested(const Args& args) { return args.has("--overwrite") || args.has("--force"); }

bool isSameFile(const std::string& a, const std::string& b) {
  std::error_code ec;
  return fs::equivalent(a, b, ec) && !ec;
}

void checkOutputs(const std::vector<std::string>& all_outputs,
                  const std::vector<std::string>& inputs, bool overwrite) {
  // "-" is standard output, never a file to compare, replace or reserve (stdio_paths.h).
  std::vector<std::string> outputs;
  for (const std::string& out : all_outputs)
    if (!isStreamPath(out)) outputs.push_back(out);
  // Inputs first: that refusal holds whatever the options, so it is the one to report.
  for (const std::string& out : outputs)
    for (const std::string& in : inputs)
      if (!isStreamPath(in) && isSameFile(in, out))
        throw CommandError(out + ": refusing to overwrite the input " + in +
                           " (an output never replaces one of its inputs, even with --overwrite)");
  for (const std::string& out : outputs) {
    std::error_code ec;
    // symlink_status: a dangling symlink is an existing name the save would replace.
    if (!overwrite && fs::symlink_status(out, ec).type() != fs::file_type::not_found && !ec)
      throw CommandError(out + " exists; pass --overwrite to replace it");
  }
  // Every output's folder before any work: no output is written and then another refused.
  for (const std::string& out : outputs) {
    const fs::path folder = fs::path(out).parent_path();
    std::error_code ec;
    if (!folder.empty() && !fs::is_directory(folder, ec))
      throw CommandError(out + ": cannot write: the folder " + folder.string() +
                         (fs::exists(folder, ec) ? " is not a folder" : " does not exist"));
  }
  // The name was free just now; another run may take it before the save commits.
  if (!overwrite)
    for (const std::string& out : outputs) commitWithoutReplacing(out);
}

void checkOutputs(const Args& args, const std::vector<std::string>& outputs,
                  const std::vector<std::string>& inputs) {
  checkStreamArguments(args, inputs, outputs);
  checkOutputs(outputs, inputs, overwriteRequested(args));
}

}  // namespace artcam::cli
