// SPDX-License-Identifier: Apache-2.0
// The engine's side of the image-file entry points that need OpenImageIO (oiio_io.h says why
// they live in a module): each loads libartcam_io_oiio.so on first use and forwards to it.
//
// Where the module is: $ARTCAM_IO_MODULE when set (a path), else beside this library
// (libartcam_core.so's own directory, found with dladdr: the build puts both in <build>/lib,
// an install in <libdir>/artcam, /usr/lib/artcam in the package). A module that cannot be loaded makes every
// image read and write fail in one line naming it and why, never a crash.
//
// JPEG files the codec path takes are read and written without the module (jpeg_file.h).
#include "core/io/oiio_io.h"

#include "core/io/jpeg_file.h"
#include "core/io/standard_streams.h"
#include "core/util/module_path.h"

#include <dlfcn.h>

#include <cstdlib>
#include <mutex>
#include <string>

namespace artcam {
namespace {

constexpr const char* kModuleName = "libartcam_io_oiio.so";

struct Loaded {
  const oiio_io::Table* table = nullptr;
  std::string why;  // why not, when table is null
};

const Loaded& loaded() {
  static const Loaded result = [] {
    Loaded l;
    const char* forced = std::getenv("ARTCAM_IO_MODULE");
    const std::string path =
        forced && *forced ? std::string(forced) : engineModuleDirectory() + kModuleName;
    // RTLD_LOCAL: the module's ~250 libraries stay out of the global scope that later lookups
    // search.
    void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) {
      const char* error = dlerror();
      l.why = "the image module " + path + " cannot be loaded (" + (error ? error : "unknown error") +
              "); reinstall ARTcam Studio";
      return l;
    }
    using Entry = const oiio_io::Table* (*)();
    const auto entry = reinterpret_cast<Entry>(dlsym(handle, "artcam_io_oiio_table"));
    const oiio_io::Table* table = entry ? entry() : nullptr;
    if (!table || table->version != oiio_io::kTableVersion || table->size != sizeof(oiio_io::Table)) {
      l.why = "the image module " + path + " is from another build of ARTcam Studio; reinstall it";
      return l;
    }
    l.table = table;
    return l;
  }();
  return result;
}

// The table, or a failure naming `path` (the verb as the module's own messages say it).
template <class R>
const oiio_io::Table* tableOr(R& failure, const std::string& path, const char* verb) {
  const Loaded& l = loaded();
  if (!l.table) failure = R::failure(path + ": cannot " + verb + ": " + l.why);
  return l.table;
}

}  // namespace

Result<LoadedImage> readImage(const std::string& path, const ReadImageOptions& options) {
  // A named colour space is converted by the module (colour_spaces.h).
  if (options.colour_space.empty())
    if (auto jpeg = jpeg_file::readFloat(path, options)) return std::move(*jpeg);
  Result<LoadedImage> failed;
  const auto* t = tableOr(failed, path, "read");
  return t ? t->read_image(path, options) : std::move(failed);
}

Status writeImage(const std::string& path, const ImageF& image, const ImageInfo* like,
                  const WriteImageOptions& options) {
  Status failed;
  const auto* t = tableOr(failed, path, "write");
  return t ? t->write_image(path, image, like, options) : std::move(failed);
}

Result<ExtraChannels> readExtraChannels(const std::string& path, const ImageInfo& info,
                                        const ReadImageOptions& options) {
  Result<ExtraChannels> failed;
  const auto* t = tableOr(failed, path, "read");
  return t ? t->read_extra_channels(path, info, options) : std::move(failed);
}

Result<std::vector<ImagePart>> readOtherParts(const std::string& path, const ImageInfo& info,
                                              const ReadImageOptions& options) {
  Result<std::vector<ImagePart>> failed;
  const auto* t = tableOr(failed, path, "read");
  return t ? t->read_other_parts(path, info, options) : std::move(failed);
}

bool formatStoresExtraChannels(const std::string& path) {
  if (jpeg_file::jpegExtension(path)) return false;
  const auto* t = loaded().table;
  return t && t->format_stores_extra_channels(path);
}

Result<StoredImage> readStoredImage(const std::string& path, const ReadImageOptions& options) {
  if (auto jpeg = jpeg_file::readStored(path, options)) return std::move(*jpeg);
  Result<StoredImage> failed;
  const auto* t = tableOr(failed, path, "read");
  return t ? t->read_stored_image(path, options) : std::move(failed);
}

Result<StoredShape> readStoredShape(const std::string& path) {
  if (auto jpeg = jpeg_file::readShape(path)) return std::move(*jpeg);
  Result<StoredShape> failed;
  const auto* t = tableOr(failed, path, "read");
  return t ? t->read_stored_shape(path) : std::move(failed);
}

Result<std::unique_ptr<StoredImageReader>> StoredImageReader::open(const std::string& path) {
  Result<std::unique_ptr<StoredImageReader>> failed;
  const auto* t = tableOr(failed, path, "read");
  return t ? t->open_stored_image_reader(path) : std::move(failed);
}

bool storedWriteKeepsEncoding(const std::string& path, PixelType type) {
  if (jpeg_file::jpegExtension(path)) return type != PixelType::Float;  // 8-bit integers only
  const auto* t = loaded().table;
  return t && t->stored_write_keeps_encoding(path, type);
}

bool formatStoresAlpha(const std::string& path) {
  if (jpeg_file::jpegExtension(path)) return false;
  const auto* t = loaded().table;
  return t && t->format_stores_alpha(path);
}

Status writeStoredImage(const std::string& path, const ConstImageView& image, const ImageInfo* like,
                        const WriteImageOptions& options) {
  const auto whole = [&image](int y0, int y1, ConstImageView& rows) {
    rows = image;
    rows.data = image.row(y0);
    rows.height = y1 - y0;
    return Status::success();
  };
  if (auto jpeg = jpeg_file::writeBands(path, image, like, options, whole)) return *jpeg;
  Status failed;
  const auto* t = tableOr(failed, path, "write");
  return t ? t->write_stored_image(path, image, like, options) : std::move(failed);
}

Status writeStoredImageBands(const std::string& path, const ConstImageView& shape,
                             const ImageInfo* like, const WriteImageOptions& options,
                             const StoredBandSource& band_rows) {
  if (auto jpeg = jpeg_file::writeBands(path, shape, like, options, band_rows)) return *jpeg;
  Status failed;
  const auto* t = tableOr(failed, path, "write");
  return t ? t->write_stored_image_bands(path, shape, like, options, band_rows) : std::move(failed);
}

bool imageExtensionWritable(const std::string& extension) {
  const auto* t = loaded().table;
  return t && t->image_extension_writable(extension);
}

Status writeStmap(const std::string& path, const std::vector<StmapLayer>& layers,
                  StmapConvention convention) {
  Status failed;
  const auto* t = tableOr(failed, path, "write");
  return t ? t->write_stmap(path, layers, convention) : std::move(failed);
}

Result<StmapSamples> readStmapSamples(const std::string& path, const StmapSampleOptions& options) {
  Result<StmapSamples> failed;
  const auto* t = tableOr(failed, path, "read");
  return t ? t->read_stmap_samples(path, options) : std::move(failed);
}

Result<ImageF> readDepthFile(const std::string& path, const DepthFileOptions& options,
                             DepthFileSummary* summary) {
  Result<ImageF> failed;
  const auto* t = tableOr(failed, path, "read");
  return t ? t->read_depth_file(path, options, summary) : std::move(failed);
}

Status checkColourSpace(const std::string& name, const std::string& option) {
  Status failed;
  const auto* t = tableOr(failed, option, "use a colour space");
  return t ? t->check_colour_space(name, option) : std::move(failed);
}

}  // namespace artcam
