// SPDX-License-Identifier: Apache-2.0
// A photo's EXIF, IPTC and XMP carried to the files made from it, through exiv2.
//
// OpenImageIO carries only the metadata it parses into attributes (it drops the XMP packet:
// ratings, usage terms, Lightroom and darktable edits), so the readers keep the blocks exactly
// as exiv2 read them (ImageInfo::metadata) and the writers put them into the written file
// before it is renamed into place (atomic_file.h): a reader never sees the pixels without them.
//
// Decisions:
// - The writing program: Exif Software (and XMP tiff:Software where present) become
//   "artcam <version>", and the XMP history (xmpMM:History) records the photo's own tool as the
//   event that created it and this save as a "saved" event by artcam, so the photo's Software
//   is kept where exiftool lists it (HistorySoftwareAgent). A photo without XMP gets a packet
//   holding that history.
// - Verbatim except what no longer describes the written file: Exif and XMP orientation become
//   1 (the readers hand over the upright photo, orientation.h), pixel dimensions become the
//   written size, the EXIF thumbnail is removed (it shows the unwarped photo), the colour-space
//   tags (Exif ColorSpace, interoperability index) are removed when the transfer changed, and a
//   TIFF source's image-structure tags (size, strips, compression) give way to the written
//   file's own. An XMP packet that does not parse is copied byte for byte.
// - Formats exiv2 cannot write (OpenEXR, HDR, BMP…) keep what OpenImageIO carried.
// - A source whose metadata exiv2 cannot read is written without it (as before); a failure to
//   write metadata into a format exiv2 supports fails the save (no file is left), but for a
//   block the format cannot hold or an XMP packet that does not parse: those are left out with
//   one warning, and the photo is still written.
// - exiv2 0.27's XMP toolkit is not thread-safe: every exiv2 call here holds one mutex (batch
//   reads and writes on two threads).
#pragma once

#include "core/model/status.h"

#include <memory>
#include <string>
#include <vector>

namespace artcam {

struct PhotoMetadata;  // exiv2's Exif and IPTC data and the XMP packet as read

// "artcam <version>": the Software tag of every file artcam writes.
std::string writingSoftware();

// Null when `path` has no EXIF, IPTC or XMP, or exiv2 does not read its format or its metadata.
std::shared_ptr<const PhotoMetadata> readPhotoMetadata(const std::string& path);

// The photo's orientation as the Metadata Working Group orders it: the EXIF tag
// (Exif.Image.Orientation; a TIFF's own tag), else XMP's tiff:Orientation, else 0 (none).
int photoOrientation(const PhotoMetadata& metadata);

// What the photo's EXIF says about the camera and lens (empty / 0 where a tag is absent):
// Exif.Image.Make and Model, Exif.Photo.LensModel, Exif.Photo.FocalLength in mm,
// Exif.Photo.FNumber and Exif.Photo.SubjectDistance in metres. For choosing a lens of the
// lensfun database (core/lens/lens_database.h) and its vignetting.
struct PhotoLensTags {
  std::string camera_maker;
  std::string camera_model;
  std::string lens_model;
  double focal_mm = 0.0;
  double aperture = 0.0;
  double distance_m = 0.0;
};
PhotoLensTags photoLensTags(const PhotoMetadata& metadata);

struct MetadataUpdate {
  int width = 0;  // the written file's size in pixels
  int height = 0;
  bool same_transfer = true;  // false: the colour-space tags are removed
};

// Writes `metadata` into the finished image file `file` (an atomic save's temporary); errors
// name `shown_path`, the file the user asked for. Success without writing when exiv2 cannot
// write `file`'s format. A block the format cannot hold (over a JPEG segment's 64 KiB) or an
// XMP packet that does not parse is left out, not a failure: each is described in `left_out`
// (for the one warning line the writer gives, image_io.h), and the rest is written.
Status writePhotoMetadata(const std::string& file, const PhotoMetadata& metadata,
                          const MetadataUpdate& update, const std::string& shown_path,
                          std::vector<std::string>* left_out = nullptr);

// The same blocks, updated the same way, encoded for a writer that embeds them itself (HEIF,
// core/io/heif_write.h): EXIF as a big-endian TIFF structure, the XMP packet. `iptc` says the
// photo had IPTC, which such a format may have no place for; `left_out` what could not be
// encoded.
struct EncodedPhotoMetadata {
  std::vector<unsigned char> exif;
  std::string xmp;
  bool iptc = false;
  std::vector<std::string> left_out;
};
EncodedPhotoMetadata encodePhotoMetadata(const PhotoMetadata& metadata,
                                         const MetadataUpdate& update);

}  // namespace artcam
