// SPDX-License-Identifier: Apache-2.0
// Photos as cameras write them, made in the tests with OpenImageIO and exiv2 directly (not
// through the engine): a raster stored sideways with an EXIF orientation, an XMP packet, and
// the JPEG quantisation tables that say which quality a file was saved with.
#pragma once

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>
#include <exiv2/exiv2.hpp>

#include <cstdint>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace artcam::test {

// An upright 8-bit RGB photo of four flat quadrants (red, green, blue, white on grey): each
// quadrant keeps its colour through JPEG, and any turn or mirror moves them.
inline OIIO::ImageBuf quadrantPhoto(int width, int height) {
  OIIO::ImageBuf photo(OIIO::ImageSpec(width, height, 3, OIIO::TypeDesc::UINT8));
  const float colours[4][3] = {
      {0.9f, 0.1f, 0.1f}, {0.1f, 0.8f, 0.1f}, {0.1f, 0.1f, 0.9f}, {0.9f, 0.9f, 0.9f}};
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      photo.setpixel(x, y, colours[(y < height / 2 ? 0 : 2) + (x < width / 2 ? 0 : 1)], 3);
  return photo;
}

// The stored raster a camera writes for `upright` with EXIF orientation `o` (1..8): 2 mirrors,
// 3 turns 180 degrees, 4 flips, 5 transposes, 6 and 8 turn a quarter, 7 transverses (TIFF 6.0's
// table; the tests check it against ImageBufAlgo::reorient where that is right).
inline OIIO::ImageBuf storedFor(const OIIO::ImageBuf& upright, int o) {
  namespace A = OIIO::ImageBufAlgo;
  switch (o) {
    case 2:
      return A::flop(upright);
    case 3:
      return A::rotate180(upright);
    case 4:
      return A::flip(upright);
    case 5:
      return A::transpose(upright);
    case 6:
      return A::rotate270(upright);
    case 7:
      return A::flop(A::rotate270(upright));
    case 8:
      return A::rotate90(upright);
    default:
      return upright;
  }
}

// Writes `stored` (8-bit) to `path` with "Orientation" = o and, for JPEG, quality `quality`.
inline bool writeOriented(const std::string& path, const OIIO::ImageBuf& stored, int o,
                          int quality = 100) {
  OIIO::ImageSpec spec = stored.spec();
  spec.set_format(OIIO::TypeDesc::UINT8);  // ImageBufAlgo::transpose hands back float
  spec.attribute("Orientation", o);
  auto out = OIIO::ImageOutput::create(path);
  if (!out) return false;
  if (std::string(out->format_name()) == "jpeg") {
    spec.attribute("CompressionQuality", quality);
    spec.attribute("Compression", "jpeg:" + std::to_string(quality));
  }
  if (!out->open(path, spec)) return false;
  std::vector<std::uint8_t> pixels(spec.image_bytes());
  stored.get_pixels(stored.roi(), OIIO::TypeDesc::UINT8, pixels.data());
  return out->write_image(OIIO::TypeDesc::UINT8, pixels.data()) && out->close();
}

// The bytes of every DQT segment before the first scan: equal tables, equal quality.
inline std::string jpegQuantisationTables(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::string tables;
  auto at = [&](size_t k) { return static_cast<unsigned char>(bytes[k]); };
  for (size_t k = 2; k + 4 <= bytes.size() && at(k) == 0xFF;) {
    const unsigned marker = at(k + 1);
    if (marker == 0xDA || marker == 0xD9) break;
    const size_t length = at(k + 2) * 256u + at(k + 3);
    if (marker == 0xDB) tables += bytes.substr(k + 4, length - 2);
    k += 2 + length;
  }
  return tables;
}

// exiv2's reading of a file's metadata.
struct Exiv2Read {
  Exiv2::ExifData exif;
  Exiv2::IptcData iptc;
  Exiv2::XmpData xmp;
  std::string xmp_packet;
};
inline Exiv2Read readWithExiv2(const std::string& path) {
  auto image = Exiv2::ImageFactory::open(path);
  image->readMetadata();
  return {image->exifData(), image->iptcData(), image->xmpData(), image->xmpPacket()};
}
inline std::string exifText(const Exiv2Read& read, const char* key) {
  const auto at = read.exif.findKey(Exiv2::ExifKey(key));
  return at == read.exif.end() ? std::string("(none)") : at->toString();
}
inline std::string xmpText(const Exiv2Read& read, const char* key) {
  const auto at = read.xmp.findKey(Exiv2::XmpKey(key));
  return at == read.xmp.end() ? std::string("(none)") : at->toString();
}

// Adds an XMP packet (what a photo manager writes: rights, rating, usage terms) to `path`.
inline void addXmp(const std::string& path, const Exiv2::XmpData& xmp) {
  auto image = Exiv2::ImageFactory::open(path);
  image->readMetadata();
  image->setXmpData(xmp);
  image->writeMetadata();
}

}  // namespace artcam::test
