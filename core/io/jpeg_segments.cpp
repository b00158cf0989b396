// SPDX-License-Identifier: Apache-2.0
#include "core/io/jpeg_segments.h"

#include <OpenImageIO/export.h>
#include <OpenImageIO/oiioversion.h>

#include <algorithm>
#include <cstddef>
#include <cstring>

// OpenImageIO's metadata encoders, as tiffutils.h declares them (that header needs libtiff's
// headers, which the build does not otherwise use).
OIIO_NAMESPACE_BEGIN
OIIO_API void encode_exif(const ImageSpec& spec, std::vector<char>& blob);
OIIO_API void encode_iptc_iim(const ImageSpec& spec, std::vector<char>& iptc);
OIIO_API std::string encode_xmp(const ImageSpec& spec, bool minimal);
OIIO_NAMESPACE_END

namespace artcam::io_jpeg {
namespace {

// libjpeg's limit for one marker's data: 65535 less the two length bytes.
constexpr std::size_t kMaxSegment = 65533;
// The identifiers OpenImageIO writes ahead of each block: "Exif\0\0", the XMP namespace with
// its NUL, "Photoshop 3.0\0" and the 8BIM resource header (rounded up).
constexpr std::size_t kExifHead = 6, kXmpHead = 29, kIptcHead = 32;

std::size_t attributeBytes(const OIIO::ParamValue& p) {
  if (p.type().basetype != OIIO::TypeDesc::STRING) return p.datasize();
  std::size_t bytes = 0;
  const auto* strings = static_cast<const char* const*>(p.data());
  for (int k = 0; k < p.nvalues() * static_cast<int>(p.type().numelements()); ++k)
    bytes += strings[k] ? std::strlen(strings[k]) : 0;
  return bytes;
}

// What the writer needs to encode the pixels and their colours: never left out.
bool essential(const std::string& name) {
  return name == "ICCProfile" || name == "Compression" || name == "CompressionQuality" ||
         name.rfind("oiio:", 0) == 0 || name.rfind("jpeg:", 0) == 0;
}

bool fits(const OIIO::ImageSpec& spec) {
  const std::string comment = spec.get_string_attribute("ImageDescription");
  if (comment.size() + 1 > kMaxSegment) return false;
  std::vector<char> exif;
  OIIO::encode_exif(spec, exif);
  if (!exif.empty() && exif.size() + kExifHead > kMaxSegment) return false;
  const std::size_t xmp =
      std::max(OIIO::encode_xmp(spec, true).size(), OIIO::encode_xmp(spec, false).size());
  if (xmp > 0 && xmp + kXmpHead > kMaxSegment) return false;
  std::vector<char> iptc;
  OIIO::encode_iptc_iim(spec, iptc);
  return iptc.empty() || iptc.size() + kIptcHead <= kMaxSegment;
}

}  // namespace

std::vector<std::string> fitJpegSegments(OIIO::ImageSpec& spec) {
  std::vector<std::string> left_out;
  while (!fits(spec)) {
    const OIIO::ParamValue* largest = nullptr;
    for (const OIIO::ParamValue& p : spec.extra_attribs)
      if (!essential(p.name().string()) &&
          (!largest || attributeBytes(p) > attributeBytes(*largest)))
        largest = &p;
    if (!largest) break;  // nothing left to drop: fits() holds for an empty spec
    const std::string name = largest->name().string();
    left_out.push_back(name + " (" + std::to_string(attributeBytes(*largest)) + " bytes)");
    spec.erase_attribute(name);
  }
  return left_out;
}

}  // namespace artcam::io_jpeg
