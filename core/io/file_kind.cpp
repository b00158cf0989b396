// SPDX-License-Identifier: Apache-2.0
// The regular-file checks of image_checks.h, apart from the image readers so that the text
// readers (text_input.cpp), which make the same refusals, link without them (the fuzz build).
#include "core/io/image_checks.h"

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstring>
#include <string>
#include <string_view>

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

namespace {

// ISO base media brands of moving pictures (MP4, QuickTime, 3GPP, Flash MP4, DASH segments).
bool movieBrand(std::string_view brand) {
  static constexpr std::array<std::string_view, 24> kBrands = {
      "isom", "iso2", "iso3", "iso4", "iso5", "iso6", "iso8", "iso9",
      "mp41", "mp42", "avc1", "M4V ", "M4VH", "M4VP", "qt  ", "3gp4",
      "3gp5", "3gp6", "3g2a", "f4v ", "dash", "mmp4", "MSNV", "XAVC"};
  for (std::string_view b : kBrands)
    if (brand == b) return true;
  return false;
}

// Brands a HEIF/AVIF still declares (major or compatible): such a file is an image.
bool stillBrand(std::string_view brand) {
  static constexpr std::array<std::string_view, 8> kBrands = {"mif1", "mif2", "heic", "heix",
                                                              "avif", "miaf", "heim", "heis"};
  for (std::string_view b : kBrands)
    if (brand == b) return true;
  return false;
}

}  // namespace

std::string movieContainer(std::string_view head) {
  using namespace std::string_view_literals;
  const auto starts = [&](std::string_view magic, size_t at = 0) {
    return head.size() >= at + magic.size() && head.substr(at, magic.size()) == magic;
  };
  if (starts("ftyp"sv, 4) && head.size() >= 12) {
    const auto byte = [&](size_t i) { return static_cast<unsigned char>(head[i]); };
    const size_t box = (size_t{byte(0)} << 24) | (size_t{byte(1)} << 16) | (size_t{byte(2)} << 8) |
                       size_t{byte(3)};
    const std::string_view major = head.substr(8, 4);
    if (stillBrand(major)) return "";
    // Compatible brands follow the minor version, four bytes each, to the end of the box.
    for (size_t at = 16; at + 4 <= std::min(box, head.size()); at += 4)
      if (stillBrand(head.substr(at, 4))) return "";
    if (!movieBrand(major)) return "";
    return major == "qt  "sv ? "QuickTime" : "MP4";
  }
  // QuickTime files older than the ftyp box open with a movie atom.
  for (std::string_view atom : {"moov"sv, "mdat"sv, "wide"sv, "pnot"sv})
    if (starts(atom, 4)) return "QuickTime";
  if (starts("RIFF"sv) && (starts("AVI "sv, 8) || starts("AVIX"sv, 8))) return "AVI";
  if (starts("\x1a\x45\xdf\xa3"sv)) return "Matroska/WebM";
  if (starts("\0\0\1\xba"sv) || starts("\0\0\1\xb3"sv)) return "MPEG";
  if (head.size() > 188 && head[0] == 0x47 && head[188] == 0x47) return "MPEG transport stream";
  if (starts("FLV\x01"sv)) return "Flash video";
  if (starts("\x30\x26\xb2\x75\x8e\x66\xcf\x11"sv)) return "Windows Media";
  if (starts("OggS"sv)) return "Ogg";
  return "";
}

std::string movieRefusal(const std::string& path, const std::string& kind) {
  return path + ": cannot read: a movie (" + kind +
         "), not a still image (take a frame out first, e.g. ffmpeg -i CLIP -frames:v 1 "
         "frame.png)";
}

}  // namespace artcam::image_checks
