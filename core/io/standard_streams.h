// SPDX-License-Identifier: Apache-2.0
// Images through standard input and output: "-" for a command's photo or its output.
//
// Decisions:
// - Standard input is read to its end and spooled into an anonymous temporary file (O_TMPFILE
//   in $TMPDIR, else /tmp; where the file system lacks it, a named file unlinked at once), and
//   the readers open it as /proc/self/fd/N. A pipe then takes exactly the route a named file
//   takes (the format found from the content, the libjpeg codec path, the stored-type path,
//   EXIF orientation, metadata, JPEG quality, the header and memory-budget refusals), so it
//   gives the same picture, bit for bit. Not an in-memory proxy: the metadata reader, the codec
//   path and the JPEG quality estimate read files by name, and a second decoder for pipes
//   would drift from the first. The cost is disk space for the compressed bytes; the file has
//   no name, so nothing is left behind even when the process is killed.
// - Standard output: the command writes to "stdout.EXT" in a private temporary folder through
//   the ordinary writers (every format, pixel type and metadata rule applies; the extension
//   chooses the format as for a file), and only after the encode succeeded are the bytes copied
//   to standard output in one go. A failed or cancelled encode puts nothing on standard output.
//   Every format OpenImageIO writes to a file can therefore stream; none is refused for it.
// - Messages name the streams "<stdin>" and "<stdout>", never the spool paths.
// - Text a command prints on standard output (reports, --json, map's rows) is checked when the
//   command ends (finishStandardOutput): a lost write makes the command fail, never exit 0.
// Linux only (/proc/self/fd), as the project is.
#pragma once

#include "core/model/status.h"

#include <cstddef>
#include <memory>
#include <string>

namespace artcam {

inline const std::string kStdinName = "<stdin>";
inline const std::string kStdoutName = "<stdout>";

// Standard input, read to its end into an anonymous file the readers open by `path`.
class StdinSpool {
 public:
  // Fails (one line naming <stdin>) when standard input is a terminal, cannot be read, or
  // holds no bytes.
  static Result<std::shared_ptr<const StdinSpool>> read();
  ~StdinSpool();
  StdinSpool(const StdinSpool&) = delete;
  StdinSpool& operator=(const StdinSpool&) = delete;

  const std::string& path() const { return path_; }  // "/proc/self/fd/N"
  std::size_t bytes() const { return bytes_; }
  // `message` with the spool's path replaced by <stdin>.
  std::string named(std::string message) const;

 private:
  StdinSpool(int fd, std::size_t bytes);
  int fd_ = -1;
  std::size_t bytes_ = 0;
  std::string path_;
};

// Where an image for standard output is written before it is sent.
class StdoutSpool {
 public:
  // `extension` without the dot ("png", "exr"). Fails (one line) when the private folder cannot
  // be made.
  static Result<std::shared_ptr<StdoutSpool>> create(const std::string& extension);
  ~StdoutSpool();  // removes the folder and what is in it
  StdoutSpool(const StdoutSpool&) = delete;
  StdoutSpool& operator=(const StdoutSpool&) = delete;

  const std::string& path() const { return path_; }  // "<folder>/stdout.<extension>"
  // Copies the written file to standard output and flushes; fails naming <stdout>.
  Status send() const;
  // `message` with the spool's path (and its folder) replaced by <stdout>.
  std::string named(std::string message) const;

 private:
  StdoutSpool(std::string folder, std::string path);
  std::string folder_;
  std::string path_;
};

// The standard descriptors 0, 1 and 2 that are closed when the program starts are taken by
// /dev/null, opened the wrong way round (write-only for 0, read-only for 1 and 2), so reading a
// closed input or writing a closed output still fails (EBADF) as it would have, while no file
// the program opens later becomes one of them (the stdin spool would have become standard
// output, and `-o -` written the image into it). Call first thing in main.
void guardStandardDescriptors();
// Whether standard output was closed when guardStandardDescriptors ran: `-o -` is refused.
bool standardOutputWasClosed();
// Flushes and closes standard output at the end of a command: fails, naming <stdout> and
// errno's text, when anything written to it was lost (a full disk, /dev/full, a closed stdout).
Status finishStandardOutput();

// Data on standard output: an .artcam, a CSV or an image a command writes to "-".
// Decided: the command's data and its reports never share the stream. reserveStandardOutputFor-
// Data moves the data's descriptor aside and points descriptor 1 at standard error, so every
// report a command prints ("wrote …", a fit's figures) reaches the terminal and a pipe
// (`artcam fit … -o - | jq .`) gets the data alone, whichever command prints. Call it once
// the command knows an output is "-", before anything is printed.
void reserveStandardOutputForData();
// Writes `bytes` to standard output (the reserved descriptor, else 1) and fails naming
// <stdout>: a reader that closed the pipe early (EPIPE, never a silent SIGPIPE), a full disk.
Status writeStandardOutputData(const std::string& bytes);

// Whether OpenImageIO writes a file with this extension (no dot, any case): what `--format`
// accepts.
bool imageExtensionWritable(const std::string& extension);

}  // namespace artcam
