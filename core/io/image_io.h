// SPDX-License-Identifier: Apache-2.0
// Images through OpenImageIO: every format it reads and writes (PNG, JPEG, TIFF 8/16-bit, EXR),
// loaded on first use (oiio_io.h); JPEG also without it where it can (jpeg_file.h).
//
// Inside the engine pixels are ImageF: float, linear light, premultiplied alpha
// (docs/architecture.md, "Images").
// readImage decodes sRGB (or through the file's ICC profile, or whatever OIIO reports as its
// colour space; 8/16-bit files without one are taken as sRGB, float files as linear) and
// premultiplies.
// writeImage does the reverse and keeps the input's pixel format and metadata when given
// them (ImageInfo from readImage), unless the options say otherwise. Saves are atomic: written
// to a temporary file beside the target, then renamed, so no partial file is ever left.
//
// Decisions:
// - Colour space: OIIO's "oiio:ColorSpace" when it names a transfer we know (sRGB, Linear,
//   Rec709, GammaCorrectedX); else 8/16-bit = sRGB, half/float = linear. Alpha is never encoded.
// - ICC profiles: an embedded profile ("ICCProfile") is the file's full description and wins
//   over the transfer. One that decodes like sRGB (IccProfile::equivalentToSrgb) takes the exact
//   sRGB path; any other (Adobe RGB, Display P3, a grey gamma) is converted with lcms2 into the
//   working space (icc_profile.h), for every pixel type, so colours outside sRGB come out with
//   negative components rather than relabelled. A damaged profile, or one that does not
//   describe the pixels (CMYK on RGB), refuses the read in one line: guessing would mislabel.
//   A CMYK JPEG's profile, once the reader has made RGB of its inks, is dropped instead
//   (ImageInfo::profile_dropped): not applied, not carried into any output. Every reader, the
//   stored-value ones too, takes this one decision (embedded_profile.h), so a profile an
//   output carries always describes the values written.
// - Chromaticities (OpenEXR): a file whose "chromaticities" attribute names primaries or a white
//   other than the working space's (an ACEScg plate: AP1, D60) is converted from them into the
//   working space by readImage (chromaticities.h: RGB → XYZ, Bradford to D65, XYZ → Rec.709);
//   ImageInfo::chromaticities records them. Chromaticities that make no RGB space are refused
//   in one line. The stored-value readers keep the values in them, so only an OpenEXR output
//   (which names them again) takes the stored path for such a file.
// - Output colour (WriteImageOptions::colour_space): float/half files hold the working space as
//   it is, and EXR says so with the "chromaticities" attribute (Rec.709 primaries, D65), except
//   that an OpenEXR output of an input in other primaries is converted back into them and says
//   so (Input, the default; Srgb keeps the working space); they never carry an ICC profile.
//   A named OpenColorIO colour space (ocio_colour_space, colour_spaces.h) overrides all this.
//   Integer files, by default (Input), are encoded back into the profile `like` was converted from,
//   with that profile embedded (an Adobe RGB photo stays Adobe RGB; values round-trip to the
//   quantisation step, or to ~1e-6 in linear light where a pure power curve's slope at 0 magnifies
//   float rounding); Srgb encodes sRGB and embeds an sRGB profile. Otherwise (Input, `like` had no
//   converting profile) see "Write" below.
// - Channels: colour and alpha (Y, YA, RGB, RGBA) make the image: the channels up to alpha
//   when the file has one among its first four, else its first three (one when it has fewer).
//   Every other channel of a file (an EXR's Z, N.x, diffuse.R, …; with or without alpha) is
//   not part of it. readExtraChannels reads them on request, as the
//   stored float values (no transfer, no premultiplication: an EXR's channels are stored
//   premultiplied already, and data channels carry no colour), in groups of at most four so
//   each group renders like a photo of its own; WriteImageOptions::extra_channels writes them
//   back, by name, after the image's own channels. Only OpenEXR holds named extra channels
//   (formatStoresExtraChannels): a writer asked to put them into another format refuses.
// - Depth-like extra channels (isDepthChannel: Z, ZBack, depth) and ID-like ones
//   (sampledNearest: *.id, *.index, Cryptomatte layers, integer channels) are grouped apart from
//   the others, so a caller can resample them with the nearest filter (ChannelGroup::nearest).
//   Each extra channel keeps its stored type in an OpenEXR output (ChannelGroup::stored_types),
//   and the image's own channels theirs (a half RGBA beside a float Z stays half).
// - Multi-part OpenEXR: the readers hand over the first part; the others are named in
//   ImageInfo::other_parts and read on request (readOtherParts) as extra channels are, each
//   part of the first part's data window; WriteImageOptions::other_parts writes them back as
//   parts after the image's. Commands that cannot write them say so in one warning line.
// - Data and display windows (OpenEXR): camera pixel coordinates are display-window pixels,
//   pixel (0, 0) being the display window's top-left one (the OpenEXR and Nuke convention).
//   The readers hand over the data window's pixels, so they refuse a file whose data window
//   is not its display window (one line naming both and the fix, oiiotool --croptofull):
//   placing the pixels anywhere else would move them silently; unless the caller asks for the
//   data window (ReadImageOptions::data_window) and places them by ImageInfo::data_origin (warp
//   and batch re-express the camera for them, core/model/frames.h reframeToRegions). On write,
//   an OpenEXR output of `like`'s data-window size keeps both of `like`'s windows (overscan
//   kept); otherwise it gets `like`'s display-window origin, its size being the image's, and a
//   data window equal to it: a warp of the whole frame keeps the input's display window, and
//   an image of another size starts where the input's frame did.
// - Write: the format follows the extension. Pixel type = options, else `like`'s, else the
//   format's natural one, then fitted to what the format stores (EXR has no 8/16-bit: half;
//   PNG has no float: uint16; JPEG/BMP/TGA/GIF/WebP: uint8). Float/half files are written
//   linear; integer files in `like`'s transfer if it was an integer file, else sRGB. Integers
//   are rounded to nearest and clamped. EXR keeps premultiplied alpha; other formats get
//   unpremultiplied colour (alpha 0 -> colour 0). A format without alpha (JPEG) gets the
//   image composited over black.
// - Metadata of `like` is carried over except what no longer applies: "oiio:*" and other
//   format-private attributes ("tiff:*", "png:*", "openexr:*", …), thumbnails, Exif pixel
//   dimensions, compression settings unless the format is the same, and the ICC profile and
//   Exif:ColorSpace unless the encoding is the same (the output's own profile replaces it).
//   Then exiv2 writes `like`'s EXIF, IPTC and XMP packet as read into the temporary, before the
//   rename (photo_metadata.h). What the output format cannot hold (a block over a JPEG
//   segment's 64 KiB) and an XMP packet that does not parse are left out with one warning
//   line per save (WriteImageOptions::warning), never a failure: the photo is written.
// - Write errors (a full disk, a file-size limit, a failed close or fsync) fail the save before
//   the rename, naming the file and errno's text (checked_output.h, atomic_file.h).
// - Orientation: readImage honours the file's EXIF orientation and hands over the upright
//   photo (orientation.h); what is written is upright and says Orientation 1.
// - JPEG quality: WriteImageOptions::jpeg_quality, else `like`'s estimated quality when both
//   are JPEG (a photo keeps its compression), else 95.
#pragma once

#include "core/colour/chromaticities.h"
#include "core/colour/stored_encoding.h"
#include "core/model/image.h"
#include "core/model/status.h"

#include <cstdio>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace artcam {

struct PhotoMetadata;  // photo_metadata.h
class IccProfile;      // core/colour/icc_profile.h

// What a file said about itself, kept so export can write the same format and metadata.
// Opaque to callers: holds an OpenImageIO ImageSpec without exposing OIIO in this header.
struct ImageInfo {
  std::string path;
  std::string format_name;  // "png", "jpeg", "openexr", …
  std::string pixel_type;   // "uint8", "uint16", "half", "float"
  bool srgb = true;         // the file's values were sRGB-encoded
  std::string
      colour_space;  // transfer decoded on read: "sRGB", "Linear", "Rec709", "GammaCorrected2.2"
  // OIIO::ImageSpec of the file (metadata to carry over); null for a JPEG read without
  // OpenImageIO (jpeg_file.h), whose writers read the header again from `path` if they need it.
  std::shared_ptr<const void> spec;
  // The EXIF orientation the stored raster was turned upright from (orientation.h); the image
  // handed over is upright and `spec` says Orientation 1.
  int stored_orientation = 1;
  int jpeg_quality = 0;  // a JPEG's estimated quality (jpeg_quality.h); 0: not JPEG, unknown
  std::string jpeg_subsampling;  // a colour JPEG's, "4:2:0" etc. (jpeg_quality.h); "": none
  std::shared_ptr<const PhotoMetadata> metadata;  // EXIF, IPTC, XMP as read; null: none
  // Channels beyond the four a reader keeps (an EXR's Z, AOVs, a fifth TIFF channel), by name:
  // not part of the image; readExtraChannels reads them, and commands that write the image
  // without them say they are left out.
  std::vector<std::string> dropped_channels;
  // The ICC profile readImage converted the colour from (colour_space is then "ICC: " and its
  // description, srgb false); null when the file had none or one equivalent to sRGB.
  std::shared_ptr<const IccProfile> icc;
  // Why the file's embedded profile was neither applied nor is carried into outputs: it does
  // not describe the pixels as read (embedded_profile.h); empty when none was dropped. Commands
  // say it in one warning line.
  std::string profile_dropped;
  // The primaries and white of the file's RGB when they are not the working space's (an EXR's
  // chromaticities attribute, e.g. ACEScg's AP1 and D60): readImage converted the colour from
  // them into the working space, the stored-value readers keep the values in them.
  std::optional<Chromaticities> chromaticities;
  // The OpenColorIO colour space readImage converted the colour from (ReadImageOptions::
  // colour_space; colour_space is then "OCIO: " and it); empty: none.
  std::string ocio_colour_space;
  // The names of a multi-part OpenEXR's parts after the first (their "name" attribute, else
  // "part N"): the readers hand over the first part only, and commands name the rest as left
  // out in one warning line.
  std::vector<std::string> other_parts;
  // Where the pixels handed over lie in the frame camera pixels are in (an OpenEXR's display
  // window): the data window's origin relative to the display window's, and the display
  // window's size. (0, 0) and the image's size unless ReadImageOptions::data_window took an
  // overscan file; display_width 0: not recorded (the image's size).
  int data_origin_x = 0, data_origin_y = 0;
  int display_width = 0, display_height = 0;
};

struct ReadImageOptions {
  // Progress in [0, 1]; return false to cancel (the read then fails with "cancelled").
  std::function<bool(double)> progress;
  // An OpenColorIO colour space the file's values are in (colour_spaces.h), over what the file
  // says of itself; empty: as the file says. readImage only: the stored-value readers keep the
  // stored numbers.
  std::string colour_space = {};
  // Take an OpenEXR whose data window is not its display window (overscan), handing over the
  // data window's pixels, instead of refusing it: for callers that place them by
  // ImageInfo::data_origin (artcam warp and batch re-express the camera for them). readImage,
  // readExtraChannels and readOtherParts only.
  bool data_window = false;
};

// Channels beyond the image's own, as their stored float values, each group holding 1..4 of
// them interleaved (ImageF without alpha) at the image's size, in the file's channel order
// within each group.
struct ChannelGroup {
  std::vector<std::string> names;  // the file's names of the group's channels
  ImageF image;
  bool depth = false;  // every channel is depth-like (isDepthChannel)
  // Every channel is sampled, not interpolated (sampledNearest: depth and ID-like channels).
  bool nearest = false;
  // Each channel's type as the file stores it ("half", "float", "uint32"; empty: unknown): an
  // OpenEXR output writes the channel in it again.
  std::vector<std::string> stored_types = {};
};
struct ExtraChannels {
  std::vector<ChannelGroup> groups;
  std::vector<std::string> names() const;  // every group's names, in group order
  bool empty() const { return groups.empty(); }
};

// Depth-like channel names: OpenEXR's "Z" and "ZBack" (exactly: "N.z" is a normal's
// component) and "depth" (any case), also as the last part of a layer's name ("beauty.Z",
// "pass.depth"). A depth interpolated across an edge is a depth no
// surface has (half-way between foreground and background), so depth is resampled with the
// nearest filter: a real sample at the nearest texel of the same source position. Everything
// else (normals, AOV colour, masks) takes the image's filter, as Nuke's STMap does.
bool isDepthChannel(const std::string& name);

// ID-like channel names, whose values are labels, not quantities: an interpolated ID names no
// object (half-way between IDs 3 and 5 is object 4), and a Cryptomatte hash interpolated is no
// object's hash. "id" and "index" as the last part of the name ("crypto.id", "obj.index",
// "id"), and every channel of a Cryptomatte layer (a part of the name starting "crypto", any
// case: "CryptoObject00.R"). Together with depth-like channels and integer-typed ones (`integer`:
// the file stores the channel as an integer), they are sampled at the nearest texel.
bool sampledNearest(const std::string& name, bool integer);

// The extra channels of `path` (ImageInfo::dropped_channels, in that order), upright as the
// image `info` describes (its stored_orientation): depth-like and other channels in groups of
// their own, each consecutive run of one kind cut into groups of at most four. Empty when the
// file has none. Fails in one line naming the file.
Result<ExtraChannels> readExtraChannels(const std::string& path, const ImageInfo& info,
                                        const ReadImageOptions& options = {});

// A later part of a multi-part OpenEXR (ImageInfo::other_parts): its name and every channel of
// it, read as readExtraChannels reads extra channels (stored floats, upright, grouped).
struct ImagePart {
  std::string name;
  ExtraChannels channels;
};

// The parts of `path` after the first, in the file's order. Fails in one line naming the file and
// the part when a part's data window is not the first part's (its pixels would not lie on the
// image's) or cannot be read.
Result<std::vector<ImagePart>> readOtherParts(const std::string& path, const ImageInfo& info,
                                              const ReadImageOptions& options = {});

// Whether `path`'s format holds named channels beyond RGBA (OpenEXR).
bool formatStoresExtraChannels(const std::string& path);

struct LoadedImage {
  ImageF image;
  ImageInfo info;
};

Result<LoadedImage> readImage(const std::string& path, const ReadImageOptions& options = {});

// How readImage decoded the file's stored values into linear light (its ICC profile, else its
// transfer): what a render of the linear copy needs to resample as the stored photo would be
// (core/pipeline/render.h, RenderInputs::encoding).
StoredEncoding storedEncodingOf(const ImageInfo& info);

struct WriteImageOptions {
  // Empty: the input's pixel type if `like` is given, else the format's natural one
  // (uint8 for PNG/JPEG, half for EXR). Else "uint8", "uint16", "half" or "float".
  std::string pixel_type;
  // 1..100. Empty: `like`'s quality when it is a JPEG too (ImageInfo::jpeg_quality), else 95.
  std::optional<int> jpeg_quality;
  // "4:4:4", "4:2:2" or "4:2:0". Empty: `like`'s when it is a JPEG too (so a 4:4:4 photo stays
  // 4:4:4), else libjpeg's default 4:2:0.
  std::string jpeg_subsampling = {};
  // Fraction of rows written, between bands; return false to cancel (the write then fails with
  // "cancelled" and no file is left: the save is atomic).
  std::function<bool(double)> progress = {};
  // What integer outputs are encoded in (float outputs are always the working space; see the
  // decisions above). Input: `like`'s ICC profile when readImage converted from one, else as
  // before. Srgb: sRGB, with an sRGB ICC profile embedded.
  enum class ColourSpace { Input, Srgb };
  ColourSpace colour_space = ColourSpace::Input;
  // Channels written after the image's own, by name, as they are (float, or half when `like`
  // was half): each group of the image's size. Only OpenEXR outputs take them; another format
  // refuses the write. Null or empty: none.
  const ExtraChannels* extra_channels = nullptr;
  // Parts written after the image's own (a multi-part OpenEXR's later parts, warped), each of
  // the image's size, in its windows; the image's part keeps `like`'s name, else "rgba". Only
  // OpenEXR outputs take them; another format refuses the write. Null or empty: none.
  const std::vector<ImagePart>* other_parts = nullptr;
  // Names of the image's own channels, one per channel (a depth map's "Z", as compositors
  // name depth). Empty: `like`'s names, else R, G, B, A (Y for one colour channel).
  std::vector<std::string> channel_names = {};
  // An OpenColorIO colour space the output is encoded in from the working space (colour_spaces.h),
  // over colour_space; empty: none.
  std::string ocio_colour_space = {};
  // Where a save's one warning line goes (metadata left out), whole, without a prefix.
  // Empty: standard error, as "warning: LINE".
  std::function<void(const std::string&)> warning = {};
};

// "<path>: metadata left out: A; B" to options.warning (or standard error) when `left_out`
// holds anything: the one warning line of a save.
inline void warnMetadataLeftOut(const WriteImageOptions& options, const std::string& path,
                                const std::vector<std::string>& left_out) {
  if (left_out.empty()) return;
  std::string line = path + ": metadata left out: ";
  for (size_t k = 0; k < left_out.size(); ++k) line += (k ? "; " : "") + left_out[k];
  if (options.warning)
    options.warning(line);
  else
    std::fprintf(stderr, "warning: %s\n", line.c_str());
}

// The JPEG quality a write uses: options.jpeg_quality clamped to 1..100, else `like`'s estimate
// when `like` is a JPEG, else 95.
int jpegQualityFor(const WriteImageOptions& options, const ImageInfo* like);
// The chroma subsampling a JPEG write uses, by the same rule: options', else `like`'s when it
// is a JPEG with one of the three, else "4:2:0".
std::string jpegSubsamplingFor(const WriteImageOptions& options, const ImageInfo* like);

// `like` (may be null) supplies metadata and the default pixel type.
Status writeImage(const std::string& path, const ImageF& image, const ImageInfo* like = nullptr,
                  const WriteImageOptions& options = {});

}  // namespace artcam
