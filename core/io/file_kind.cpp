// SPDX-License-Identifier: Apache-2.0
// The regular-file checks of image_checks.h, apart from the image readers so that the text
// readers (text_input.cpp), which make the same refusals, link without them (the fuzz build).
#include "core/io/image_checks.h"

#include <cerrno>
#include <cstring>
#include <string>

#include <sys/stat.h>

namespace artcam::image_checks {

std::string notRegularFile(unsigned int st_mode) {
  if (S_ISFIFO(st_mode)) return "not a file (a named pipe, which is read only through \"-\")";
  if (S_ISCHR(st_mode) || S_ISBLK(st_mode)) return "not a file (a device)";
  if (S_ISDIR(st_mode)) return "not a file (a folder)";
  if (S_ISSOCK(st_mode)) return "not a file (a socket)";
  return "not a file";
}

Status regularFile(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0)
    return Status::failure(path + ": cannot read: " +
                           (errno == ENOENT || errno == ENOTDIR
                                ? std::string("no such file")
                                : std::string(std::strerror(errno))));
  if (S_ISREG(st.st_mode)) return Status::success();
  return Status::failure(path + ": cannot read: " + notRegularFile(st.st_mode));
}

}  // namespace artcam::image_checks
