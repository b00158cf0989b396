// SPDX-License-Identifier: Apache-2.0
#include "core/io/photo_metadata.h"

#include "core/io/io_text.h"

#include <exiv2/exiv2.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <exception>
#include <mutex>
#include <set>

namespace artcam {

struct PhotoMetadata {
  Exiv2::ExifData exif;
  Exiv2::IptcData iptc;
  std::string xmp_packet;
};

namespace {

// Holds the one lock of every exiv2 call; initialises the XMP toolkit and mutes exiv2's
// warnings on stderr (a command's output stays its own) the first time.
std::unique_lock<std::mutex> exiv2Lock() {
  static std::mutex mutex;
  std::unique_lock<std::mutex> lock(mutex);
  static const bool initialised = [] {
    Exiv2::LogMsg::setLevel(Exiv2::LogMsg::mute);
    Exiv2::XmpParser::initialize();
    return true;
  }();
  (void)initialised;
  // exiv2 asks for XmpParser::terminate at the end: it frees the namespaces registered on the
  // way (each XMP packet with a namespace of its own registers one), which otherwise outlive
  // their registry and show as leaks. Made after exiv2's own statics, so undone before them.
  struct Terminate {
    ~Terminate() { Exiv2::XmpParser::terminate(); }
  };
  static const Terminate at_exit;
  return lock;
}

// TIFF tags that describe the raster, not the photo: the written file has its own.
bool isStructureTag(const std::string& key) {
  static const std::set<std::string> kTags{"Exif.Image.NewSubfileType",
                                           "Exif.Image.SubfileType",
                                           "Exif.Image.ImageWidth",
                                           "Exif.Image.ImageLength",
                                           "Exif.Image.BitsPerSample",
                                           "Exif.Image.Compression",
                                           "Exif.Image.PhotometricInterpretation",
                                           "Exif.Image.FillOrder",
                                           "Exif.Image.StripOffsets",
                                           "Exif.Image.SamplesPerPixel",
                                           "Exif.Image.RowsPerStrip",
                                           "Exif.Image.StripByteCounts",
                                           "Exif.Image.PlanarConfiguration",
                                           "Exif.Image.Predictor",
                                           "Exif.Image.TileWidth",
                                           "Exif.Image.TileLength",
                                           "Exif.Image.TileOffsets",
                                           "Exif.Image.TileByteCounts",
                                           "Exif.Image.SubIFDs",
                                           "Exif.Image.ExtraSamples",
                                           "Exif.Image.SampleFormat",
                                           "Exif.Image.JPEGTables",
                                           "Exif.Image.InterColorProfile",
                                           "Exif.Image.XMLPacket",
                                           "Exif.Image.IPTCNAA",
                                           "Exif.Image.ImageResources"};
  return kTags.count(key) > 0;
}

void setIfPresent(Exiv2::ExifData& exif, const char* key, std::uint32_t value) {
  // Assigned as LONG: a SHORT field could not hold a size over 65535.
  if (exif.findKey(Exiv2::ExifKey(key)) != exif.end()) exif[key] = value;
}

void eraseKey(Exiv2::ExifData& exif, const char* key) {
  auto at = exif.findKey(Exiv2::ExifKey(key));
  if (at != exif.end()) exif.erase(at);
}

std::string softwareName() { return writingSoftware(); }

// The tool the photo came from: EXIF Software, else XMP's tiff:Software or xmp:CreatorTool.
std::string priorSoftware(const PhotoMetadata& metadata, const Exiv2::XmpData* xmp) {
  const auto exif = metadata.exif.findKey(Exiv2::ExifKey("Exif.Image.Software"));
  if (exif != metadata.exif.end() && !exif->toString().empty()) return exif->toString();
  if (!xmp) return "";
  for (const char* key : {"Xmp.tiff.Software", "Xmp.xmp.CreatorTool"}) {
    const auto at = xmp->findKey(Exiv2::XmpKey(key));
    if (at != xmp->end() && !at->toString().empty()) return at->toString();
  }
  return "";
}

// XMP's own record of the tools a file went through (xmpMM:History, a sequence of stEvt
// events, what Adobe's and darktable's writers keep and exiftool lists as HistoryAction,
// HistorySoftwareAgent, HistoryWhen): the photo's tool, when the history does not name one yet,
// as the event that created it, then this save, "saved" with "changed /" (the whole image, a
// warp moves every pixel).
void addHistory(Exiv2::XmpData& xmp, const std::string& prior) {
  int events = 0;
  for (const Exiv2::Xmpdatum& d : xmp) {
    const std::string key = d.key();
    const std::string head = "Xmp.xmpMM.History[";
    if (key.rfind(head, 0) != 0) continue;
    events = std::max(events, std::atoi(key.c_str() + head.size()));
  }
  if (events == 0) {
    Exiv2::XmpTextValue seq;
    seq.setXmpArrayType(Exiv2::XmpValue::xaSeq);
    xmp.add(Exiv2::XmpKey("Xmp.xmpMM.History"), &seq);
  }
  const auto event = [&xmp](int k, const char* field, const std::string& value) {
    xmp["Xmp.xmpMM.History[" + std::to_string(k) + "]/stEvt:" + field] = value;
  };
  if (events == 0 && !prior.empty()) {
    event(++events, "action", "created");
    event(events, "softwareAgent", prior);
  }
  // SOURCE_DATE_EPOCH (reproducible-builds.org's convention: seconds since 1970, digits only)
  // stands for the time of saving when set, so a render farm's retried frame, or a test, writes
  // the very bytes of the first run; otherwise the clock.
  std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  if (const char* epoch = std::getenv("SOURCE_DATE_EPOCH");
      epoch && *epoch && std::strlen(epoch) <= 12 &&
      std::strspn(epoch, "0123456789") == std::strlen(epoch))
    now = static_cast<std::time_t>(std::strtoll(epoch, nullptr, 10));
  std::tm utc{};
  gmtime_r(&now, &utc);
  char when[32];
  std::strftime(when, sizeof when, "%Y-%m-%dT%H:%M:%SZ", &utc);
  event(++events, "action", "saved");
  event(events, "changed", "/");
  event(events, "softwareAgent", softwareName());
  event(events, "when", when);
}

Exiv2::ExifData updatedExif(const PhotoMetadata& metadata, const MetadataUpdate& update,
                            const Exiv2::ExifData& written) {
  Exiv2::ExifData exif;
  for (const Exiv2::Exifdatum& d : metadata.exif)
    if (!isStructureTag(d.key()) && d.groupName().rfind("Thumbnail", 0) != 0) exif.add(d);
  // The written file's own raster tags (a TIFF's; exiv2 keeps them in any case).
  for (const Exiv2::Exifdatum& d : written)
    if (isStructureTag(d.key()) && d.key() != "Exif.Image.XMLPacket" &&
        d.key() != "Exif.Image.IPTCNAA" && d.key() != "Exif.Image.ImageResources")
      exif.add(d);
  Exiv2::ExifThumb(exif).erase();
  setIfPresent(exif, "Exif.Image.Orientation", 1);
  setIfPresent(exif, "Exif.Photo.PixelXDimension", static_cast<std::uint32_t>(update.width));
  setIfPresent(exif, "Exif.Photo.PixelYDimension", static_cast<std::uint32_t>(update.height));
  if (!update.same_transfer) {
    eraseKey(exif, "Exif.Photo.ColorSpace");
    eraseKey(exif, "Exif.Iop.InteroperabilityIndex");
  }
  // The writing program, the photo's kept in the XMP history (addHistory).
  exif["Exif.Image.Software"] = softwareName();
  return exif;
}

// The packet with its stale fields updated, or `packet` itself (changed false) when none is
// stale or it does not parse: then it is copied byte for byte.
// Every save adds its history event (addHistory), so a packet that parses always changes; one
// that does not is copied byte for byte; a photo without XMP gets a packet holding the history.
std::string updatedXmpPacket(const PhotoMetadata& metadata, const MetadataUpdate& update,
                             bool& changed) {
  const std::string& packet = metadata.xmp_packet;
  changed = false;
  Exiv2::XmpData xmp;
  if (!packet.empty() && Exiv2::XmpParser::decode(xmp, packet) != 0) return packet;  // verbatim
  addHistory(xmp, priorSoftware(metadata, &xmp));
  if (xmp.findKey(Exiv2::XmpKey("Xmp.tiff.Software")) != xmp.end())
    xmp["Xmp.tiff.Software"] = softwareName();
  changed = true;
  const std::pair<const char*, std::string> fields[] = {
      {"Xmp.tiff.Orientation", "1"},
      {"Xmp.exif.PixelXDimension", std::to_string(update.width)},
      {"Xmp.exif.PixelYDimension", std::to_string(update.height)},
      {"Xmp.tiff.ImageWidth", std::to_string(update.width)},
      {"Xmp.tiff.ImageLength", std::to_string(update.height)}};
  for (const auto& [key, value] : fields) {
    auto at = xmp.findKey(Exiv2::XmpKey(key));
    if (at == xmp.end() || at->toString() == value) continue;
    at->setValue(value);
    changed = true;
  }
  if (!update.same_transfer) {
    auto at = xmp.findKey(Exiv2::XmpKey("Xmp.exif.ColorSpace"));
    if (at != xmp.end()) xmp.erase(at), changed = true;
  }
  std::string out;
  if (Exiv2::XmpParser::encode(out, xmp, Exiv2::XmpParser::useCompactFormat) != 0) {
    changed = false;
    return packet;
  }
  return out;
}

}  // namespace

std::string writingSoftware() { return std::string("artcam ") + ARTCAM_VERSION; }

std::shared_ptr<const PhotoMetadata> readPhotoMetadata(const std::string& path) {
  const auto lock = exiv2Lock();
  try {
    if (Exiv2::ImageFactory::getType(path) == Exiv2::ImageType::none) return nullptr;
    auto image = Exiv2::ImageFactory::open(path);
    if (!image.get()) return nullptr;
    image->readMetadata();
    auto metadata = std::make_shared<PhotoMetadata>();
    metadata->exif = image->exifData();
    metadata->iptc = image->iptcData();
    metadata->xmp_packet = image->xmpPacket();
    if (metadata->exif.empty() && metadata->iptc.empty() && metadata->xmp_packet.empty())
      return nullptr;
    return metadata;
  } catch (const std::exception&) {
    return nullptr;  // metadata exiv2 cannot parse is left behind, the pixels are not
  }
}

int photoOrientation(const PhotoMetadata& metadata) {
  const auto lock = exiv2Lock();
  try {
    const auto exif = metadata.exif.findKey(Exiv2::ExifKey("Exif.Image.Orientation"));
    if (exif != metadata.exif.end() && exif->count() > 0) return static_cast<int>(exif->toLong());
    if (metadata.xmp_packet.empty()) return 0;
    Exiv2::XmpData xmp;
    if (Exiv2::XmpParser::decode(xmp, metadata.xmp_packet) != 0) return 0;
    const auto at = xmp.findKey(Exiv2::XmpKey("Xmp.tiff.Orientation"));
    return at == xmp.end() || at->count() == 0 ? 0 : static_cast<int>(at->toLong());
  } catch (const std::exception&) {
    return 0;
  }
}

PhotoLensTags photoLensTags(const PhotoMetadata& metadata) {
  const auto lock = exiv2Lock();
  PhotoLensTags tags;
  const auto text = [&](const char* key) -> std::string {
    try {
      const auto at = metadata.exif.findKey(Exiv2::ExifKey(key));
      if (at == metadata.exif.end() || at->count() == 0) return {};
      std::string v = at->toString();
      // EXIF ASCII values are often padded with spaces or NULs.
      while (!v.empty() && (v.back() == ' ' || v.back() == '\0')) v.pop_back();
      return v;
    } catch (const std::exception&) {
      return {};
    }
  };
  tags.camera_maker = text("Exif.Image.Make");
  tags.camera_model = text("Exif.Image.Model");
  tags.lens_model = text("Exif.Photo.LensModel");
  // OpenImageIO 2.4 writes LensModel (tag 0xa434) into IFD0 rather than the Exif IFD, so
  // files it wrote (ours among them) carry it there.
  if (tags.lens_model.empty()) tags.lens_model = text("Exif.Image.0xa434");
  const auto positive = [&](const char* key) {
    try {
      const auto at = metadata.exif.findKey(Exiv2::ExifKey(key));
      if (at != metadata.exif.end() && at->count() > 0) {
        // EXIF stores these as rationals: divided in double, 2.8 stays 2.8 (toFloat's float
        // would make it 2.7999999).
        // The tags are unsigned: read as such (toRational's signed pair turns a numerator past
        // 2^31 negative).
        double f = static_cast<double>(at->toFloat());
        if (const auto* u = dynamic_cast<const Exiv2::URationalValue*>(&at->value());
            u && !u->value_.empty() && u->value_[0].second != 0)
          f = double(u->value_[0].first) / double(u->value_[0].second);
        else if (const Exiv2::Rational r = at->toRational(); r.second != 0)
          f = double(r.first) / double(r.second);
        if (std::isfinite(f) && f > 0) return f;
      }
    } catch (const std::exception&) {
    }
    return 0.0;
  };
  tags.focal_mm = positive("Exif.Photo.FocalLength");
  tags.aperture = positive("Exif.Photo.FNumber");
  tags.distance_m = positive("Exif.Photo.SubjectDistance");
  return tags;
}

EncodedPhotoMetadata encodePhotoMetadata(const PhotoMetadata& metadata,
                                         const MetadataUpdate& update) {
  const auto lock = exiv2Lock();
  EncodedPhotoMetadata out;
  out.iptc = !metadata.iptc.empty();
  try {
    const Exiv2::ExifData exif = updatedExif(metadata, update, Exiv2::ExifData());
    Exiv2::Blob blob;
    Exiv2::ExifParser::encode(blob, Exiv2::bigEndian, exif);
    out.exif.assign(blob.begin(), blob.end());
  } catch (const std::exception&) {
    out.exif.clear();
    out.left_out.push_back("the EXIF block (exiv2 cannot encode it)");
  }
  bool parses = metadata.xmp_packet.empty();
  if (!parses) {
    Exiv2::XmpData parsed;
    try {
      parses = Exiv2::XmpParser::decode(parsed, metadata.xmp_packet) == 0;
    } catch (const std::exception&) {
    }
  }
  if (parses) {
    bool changed = false;
    out.xmp = updatedXmpPacket(metadata, update, changed);
  } else {
    out.left_out.push_back("the XMP packet (" + std::to_string(metadata.xmp_packet.size()) +
                           " bytes, it does not parse)");
  }
  return out;
}

Status writePhotoMetadata(const std::string& file, const PhotoMetadata& metadata,
                          const MetadataUpdate& update, const std::string& shown_path,
                          std::vector<std::string>* left_out) {
  const auto lock = exiv2Lock();
  auto leaveOut = [&](const std::string& what) {
    if (left_out) left_out->push_back(what);
  };
  bool with_exif = true, with_iptc = true;
  bool with_xmp = true;  // a packet without one: the history alone (updatedXmpPacket)
  const std::string xmp_bytes = std::to_string(metadata.xmp_packet.size()) + " bytes";
  // exiv2 parses a packet it is given (setXmpPacket): one its XMP toolkit cannot parse (broken
  // XML, an entity bomb the parser stops) would fail the save, so it is left out.
  if (!metadata.xmp_packet.empty()) {
    Exiv2::XmpData parsed;
    bool parses = false;
    try {
      parses = Exiv2::XmpParser::decode(parsed, metadata.xmp_packet) == 0;
    } catch (const std::exception&) {
    }
    if (!parses) {
      with_xmp = false;
      leaveOut("the XMP packet (" + xmp_bytes + ", it does not parse)");
    }
  }
  // A block larger than the format holds (a JPEG segment, 64 KiB: a long edit history in the
  // XMP, a big maker note) is left out and the save tried again without it: exiv2 refuses it
  // before it touches the file. Three blocks, so at most three retries.
  for (int attempt = 0; attempt < 4; ++attempt) {
    try {
      const int type = Exiv2::ImageFactory::getType(file);
      if (type == Exiv2::ImageType::none) return Status::success();
      auto image = Exiv2::ImageFactory::open(file);
      if (!image.get()) return Status::success();
      image->readMetadata();  // the written file's own: ICC profile, a TIFF's raster tags
      if (with_exif && Exiv2::ImageFactory::checkMode(type, Exiv2::mdExif) & Exiv2::amWrite)
        image->setExifData(updatedExif(metadata, update, image->exifData()));
      if (with_iptc && Exiv2::ImageFactory::checkMode(type, Exiv2::mdIptc) & Exiv2::amWrite)
        image->setIptcData(metadata.iptc);
      if (with_xmp && Exiv2::ImageFactory::checkMode(type, Exiv2::mdXmp) & Exiv2::amWrite) {
        bool changed = false;
        const std::string packet = updatedXmpPacket(metadata, update, changed);
        image->setXmpPacket(packet);
        image->writeXmpFromPacket(true);  // as read, not re-serialised from XmpData
      }
      image->writeMetadata();
      return Status::success();
    } catch (const Exiv2::AnyError& e) {
      const std::string what = e.what();
      const bool too_large = e.code() == Exiv2::kerTooLargeJpegSegment;
      const std::string segment = " is larger than a JPEG segment holds (64 KiB)";
      if (too_large && with_xmp && what.find("XMP") != std::string::npos) {
        with_xmp = false;
        leaveOut("the XMP packet (" + xmp_bytes + ")" + segment);
      } else if (too_large && with_exif && what.find("Exif") != std::string::npos) {
        with_exif = false;
        leaveOut("the EXIF block" + segment);
      } else if (too_large && with_iptc && what.find("IPTC") != std::string::npos) {
        with_iptc = false;
        leaveOut("the IPTC block" + segment);
      } else {
        return Status::failure(shown_path + ": cannot write the metadata: " +
                               io_text::replaceAll(io_text::oneLine(what), file, shown_path));
      }
    } catch (const std::exception& e) {
      return Status::failure(shown_path + ": cannot write the metadata: " +
                             io_text::replaceAll(io_text::oneLine(e.what()), file, shown_path));
    }
  }
  return Status::failure(shown_path + ": cannot write the metadata");
}

}  // namespace artcam
