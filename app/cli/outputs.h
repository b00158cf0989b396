// SPDX-License-Identifier: Apache-2.0
// The rule every artcam command that writes files follows before it starts work:
//   - an output is never one of the command's own inputs, even with --overwrite (the same file
//     by identity, std::filesystem::equivalent: symlinks, hard links and ./.. spellings
//     included, not a string compare), so no run can destroy the data it reads;
//   - an output that exists already is refused unless --overwrite (alias --force) is given.
//   - every output's folder exists, checked before any work, so no output is written before
//     another is refused;
//   - without --overwrite the saves commit without replacing (atomic_file.h,
//     commitWithoutReplacing): of two runs racing for one name, one writes it, the other fails.
// Files are then written atomically (core/io/atomic_file.h), so a refused or failed run leaves
// every existing file as it was.
#pragma once

#include "app/cli/args.h"

#include <string>
#include <vector>

namespace artcam::cli {

// --overwrite or its alias --force (each writing command lists both in its OptionSpecs).
bool overwriteRequested(const Args& args);

// True when both paths name one existing file.
bool isSameFile(const std::string& a, const std::string& b);

// Throws CommandError "OUT: refusing to overwrite the input IN …" when an output is one of
// `inputs`, and (unless `overwrite`) "OUT exists; pass --overwrite to replace it" when an output
// exists. Inputs that do not exist are skipped (their readers report them).
void checkOutputs(const std::vector<std::string>& outputs, const std::vector<std::string>& inputs,
                  bool overwrite);
// The same for a command's --overwrite/--force in `args`.
void checkOutputs(const Args& args, const std::vector<std::string>& outputs,
                  const std::vector<std::string>& inputs);

}  // namespace artcam::cli
