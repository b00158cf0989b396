// SPDX-License-Identifier: Apache-2.0
// The parts of the image-file entry points that need no codec (so no OpenImageIO: oiio_io.h):
// channel names, the JPEG quality a write takes, the first look's reduction, the STMap
// conventions' names, an empty stored image and the readers' checks (image_checks.h).
#include "core/io/image_checks.h"
#include "core/io/first_look.h"
#include "core/io/image_io.h"
#include "core/io/io_text.h"
#include "core/io/stmap_file.h"
#include "core/io/stored_image.h"
#include "core/util/memory_budget.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include <sys/stat.h>

namespace artcam {

StoredEncoding storedEncodingOf(const ImageInfo& info) {
  if (info.icc) return StoredEncoding::ofProfile(info.icc);
  if (info.srgb) return StoredEncoding::ofTransfer(Transfer::srgb());
  const std::optional<Transfer> transfer = Transfer::fromColourSpace(info.colour_space);
  return StoredEncoding::ofTransfer(transfer ? *transfer : Transfer::linear());
}

std::vector<std::string> ExtraChannels::names() const {
  std::vector<std::string> all;
  for (const ChannelGroup& g : groups) all.insert(all.end(), g.names.begin(), g.names.end());
  return all;
}

bool isDepthChannel(const std::string& name) {
  // Case matters for Z: OpenEXR's depth is "Z", while "N.z" or "P.z" is a vector's component.
  const size_t dot = name.rfind('.');
  const std::string last = dot == std::string::npos ? name : name.substr(dot + 1);
  return last == "Z" || last == "ZBack" || io_text::lower(last) == "depth";
}

bool sampledNearest(const std::string& name, bool integer) {
  if (integer || isDepthChannel(name)) return true;
  const std::string lowered = io_text::lower(name);
  const size_t dot = lowered.rfind('.');
  const std::string last = dot == std::string::npos ? lowered : lowered.substr(dot + 1);
  if (last == "id" || last == "index") return true;
  for (size_t start = 0; start <= lowered.size();) {
    if (lowered.compare(start, 6, "crypto") == 0) return true;
    const size_t next = lowered.find('.', start);
    if (next == std::string::npos) break;
    start = next + 1;
  }
  return false;
}

int jpegQualityFor(const WriteImageOptions& options, const ImageInfo* like) {
  if (options.jpeg_quality) return std::clamp(*options.jpeg_quality, 1, 100);
  if (like && like->format_name == "jpeg" && like->jpeg_quality > 0) return like->jpeg_quality;
  return 95;
}

std::string jpegSubsamplingFor(const WriteImageOptions& options, const ImageInfo* like) {
  const auto known = [](const std::string& s) {
    return s == "4:4:4" || s == "4:2:2" || s == "4:2:0";
  };
  if (known(options.jpeg_subsampling)) return options.jpeg_subsampling;
  if (like && like->format_name == "jpeg" && known(like->jpeg_subsampling))
    return like->jpeg_subsampling;
  return "4:2:0";
}

int firstLookReduction(int width, int height, int box_width, int box_height) {
  if (box_width <= 0 || box_height <= 0 || width <= 0 || height <= 0) return 1;
  const double bw = box_width, bh = box_height;
  const double as_stored = std::min({1.0, bw / width, bh / height});
  const double turned = std::min({1.0, bw / height, bh / width});
  const double shrink = std::max(as_stored, turned);
  const double cover = shrink * kFirstLookCover;
  const int need_w = static_cast<int>(std::ceil(width * cover - 1e-9));
  const int need_h = static_cast<int>(std::ceil(height * cover - 1e-9));
  for (const int n : {8, 4, 2})
    if ((width + n - 1) / n >= need_w && (height + n - 1) / n >= need_h) return n;
  return 1;
}

std::string_view stmapConventionName(StmapConvention convention) {
  return convention == StmapConvention::OpenCv ? "opencv" : "stmap";
}

std::optional<StmapConvention> stmapConventionFromName(std::string_view name) {
  if (name == "stmap") return StmapConvention::StMap;
  if (name == "opencv") return StmapConvention::OpenCv;
  return std::nullopt;
}

StoredImage makeStoredImage(int width, int height, int channels, int alpha_channel, PixelType type,
                            PixelBuffer::Init init) {
  StoredImage image;
  image.width = width;
  image.height = height;
  image.channels = channels;
  image.alpha_channel = alpha_channel;
  image.type = type;
  image.bytes = PixelBuffer(static_cast<size_t>(width) * static_cast<size_t>(height) *
                            static_cast<size_t>(channels) * static_cast<size_t>(pixelTypeSize(type)),
                            init);
  return image;
}

namespace image_checks {

Status claimedSize(const std::string& path, int width, int height, int channels,
                   int bytes_per_sample, bool whole) {
  // A header can claim any size; the readers allocate what it claims before decoding. No codec
  // OpenImageIO reads packs more than kMaxCompression decoded bytes into one file byte (deflate
  // peaks at 1032:1, LZW near 2700:1), so a claim beyond that is a corrupt or truncated file,
  // refused before gigabytes are asked for (a 67-byte PNG can claim 100 000 × 100 000 pixels).
  constexpr double kMaxCompression = 4096.0;
  const double decoded_bytes = static_cast<double>(width) * static_cast<double>(height) *
                               static_cast<double>(channels) * static_cast<double>(bytes_per_sample);
  std::error_code error;
  const double file_bytes = static_cast<double>(std::filesystem::file_size(path, error));
  if (!error && decoded_bytes > kMaxCompression * file_bytes)
    return Status::failure(path + ": cannot read: the header claims " + std::to_string(width) +
                           "x" + std::to_string(height) + " pixels (" +
                           std::to_string(static_cast<long long>(decoded_bytes / 1e6)) +
                           " MB decoded) but the file holds only " +
                           std::to_string(static_cast<long long>(file_bytes)) +
                           " bytes (corrupt or truncated)");
  // The padding above cannot buy memory: whatever the file's size, the photo as the engine holds
  // it (float, at least the 4 channels of a render) must fit the memory budget, checked here from
  // the header before any pixel is allocated.
  const double float_bytes = static_cast<double>(width) * static_cast<double>(height) *
                             std::max(4.0, static_cast<double>(channels)) * 4.0;
  const double budget = memoryBudgetBytes();
  if (whole && float_bytes > budget)
    return Status::failure(path + ": cannot read: " + std::to_string(width) + "x" +
                           std::to_string(height) + " pixels need " + describeBytes(float_bytes) +
                           " as float, more than " + describeMemoryBudget());
  return Status::success();
}

}  // namespace image_checks
}  // namespace artcam
