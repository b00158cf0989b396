// SPDX-License-Identifier: Apache-2.0
// Atomic saves: write to a temporary file in the target's folder, flush, then
// rename over the target. On any failure the temporary is removed and the target untouched.
//
// Temporaries are named ".<stem>.tmp-<pid>-<n><ext>" (hidden, with the target's extension
// because image writers pick their format from it). Two things keep them from outliving the
// save, so no work is lost:
// - every live temporary is registered, and removeLiveTemporaries() unlinks them from a signal
//   handler (async-signal-safe), so an interrupted program leaves none behind;
// - a SIGKILLed writer cannot clean up, so each save first removes the temporaries of ITS
//   target left by processes that no longer exist (never those of a running process).
#pragma once

#include "core/model/status.h"

#include <functional>
#include <string>

namespace artcam {

// `write` receives the temporary path (same folder and extension as `path`) and returns
// whether it succeeded; its message is passed on.
// `path` "-" is standard output: `write` writes a private spool file, copied to standard output
// once it succeeded (standard_streams.h). Image writers choose the format by extension, so a
// command hands them a spool of its own instead (app/cli/stdio_paths.h).
Status writeAtomically(const std::string& path,
                       const std::function<Status(const std::string& temp_path)>& write);
Status writeTextAtomically(const std::string& path, const std::string& text);

// Marks `path` as one this process must not replace (the command line without --overwrite,
// app/cli/outputs.h): its save then commits with renameat2(RENAME_NOREPLACE), or link(2) where
// the file system lacks it, both of which fail when the name exists, instead of rename(2),
// which replaces. Of two runs that both found the name free, exactly one writes it; the other
// fails naming the file and leaves the winner's file as it is. A successful save clears the mark.
void commitWithoutReplacing(const std::string& path);

// Unlinks every temporary a save in this process is writing right now. Async-signal-safe
// (only atomics and unlink(2)): meant for a SIGINT/SIGTERM handler that then calls _exit.
void removeLiveTemporaries() noexcept;

// Whether `file_name` (no folder) is an atomic save's temporary: ".<stem>.tmp-<pid>-<n><ext>".
// Batch jobs use it so a stale temporary is never taken for an input or an output.
bool isAtomicTemporaryName(const std::string& file_name);

// Removes the temporaries for `path` whose writing process is gone (killed mid-save); returns
// how many. writeAtomically calls it before each save.
int removeStaleTemporaries(const std::string& path);

}  // namespace artcam
