// SPDX-License-Identifier: Apache-2.0
// The image-file entry points that need OpenImageIO, as the module libartcam_io_oiio.so
// implements them (io room only). OpenImageIO pulls some 250 shared libraries into a process
// (codecs, OpenVDB, ffmpeg, DICOM, …) and resolving their symbols would delay every `artcam`
// run, whether or not it touched an image; so the engine links it only through this
// module, which io_module.cpp loads with dlopen the first time an image is read or written.
//
// Each function here is the one its public declaration (image_io.h, stored_image.h, …)
// forwards to: same contract, same messages. Code inside the module calls these directly.
// `Table` is what the module hands the loader: the build makes both halves from one tree, so
// `kTableVersion` and the struct's size only catch a module from another build.
#pragma once

#include "core/io/colour_spaces.h"
#include "core/io/depth_file.h"
#include "core/io/image_io.h"
#include "core/io/stmap_file.h"
#include "core/io/stored_image.h"

#include <cstddef>
#include <memory>
#include <optional>
#include <string>

namespace artcam::oiio_io {

Result<LoadedImage> readImage(const std::string& path, const ReadImageOptions& options);
Status writeImage(const std::string& path, const ImageF& image, const ImageInfo* like,
                  const WriteImageOptions& options);
Result<ExtraChannels> readExtraChannels(const std::string& path, const ImageInfo& info,
                                        const ReadImageOptions& options);
bool formatStoresExtraChannels(const std::string& path);
Result<std::vector<ImagePart>> readOtherParts(const std::string& path, const ImageInfo& info,
                                              const ReadImageOptions& options);

Result<StoredImage> readStoredImage(const std::string& path, const ReadImageOptions& options);
Result<StoredShape> readStoredShape(const std::string& path);
Result<std::unique_ptr<StoredImageReader>> openStoredImageReader(const std::string& path);
bool storedWriteKeepsEncoding(const std::string& path, PixelType type);
bool formatStoresAlpha(const std::string& path);
Status writeStoredImage(const std::string& path, const ConstImageView& image,
                        const ImageInfo* like, const WriteImageOptions& options);
Status writeStoredImageBands(const std::string& path, const ConstImageView& shape,
                             const ImageInfo* like, const WriteImageOptions& options,
                             const StoredBandSource& band_rows);

bool imageExtensionWritable(const std::string& extension);
Status writeStmap(const std::string& path, const std::vector<StmapLayer>& layers,
                  StmapConvention convention);
Result<StmapSamples> readStmapSamples(const std::string& path, const StmapSampleOptions& options);
Result<ImageF> readDepthFile(const std::string& path, const DepthFileOptions& options,
                             DepthFileSummary* summary);

Status checkColourSpace(const std::string& name, const std::string& option);

constexpr int kTableVersion = 4;

struct Table {
  int version = kTableVersion;
  std::size_t size = sizeof(Table);
  decltype(&readImage) read_image = &readImage;
  decltype(&writeImage) write_image = &writeImage;
  decltype(&readExtraChannels) read_extra_channels = &readExtraChannels;
  decltype(&formatStoresExtraChannels) format_stores_extra_channels = &formatStoresExtraChannels;
  decltype(&readStoredImage) read_stored_image = &readStoredImage;
  decltype(&readStoredShape) read_stored_shape = &readStoredShape;
  decltype(&openStoredImageReader) open_stored_image_reader = &openStoredImageReader;
  decltype(&storedWriteKeepsEncoding) stored_write_keeps_encoding = &storedWriteKeepsEncoding;
  decltype(&formatStoresAlpha) format_stores_alpha = &formatStoresAlpha;
  decltype(&writeStoredImage) write_stored_image = &writeStoredImage;
  decltype(&writeStoredImageBands) write_stored_image_bands = &writeStoredImageBands;
  decltype(&imageExtensionWritable) image_extension_writable = &imageExtensionWritable;
  decltype(&writeStmap) write_stmap = &writeStmap;
  decltype(&readStmapSamples) read_stmap_samples = &readStmapSamples;
  decltype(&readDepthFile) read_depth_file = &readDepthFile;
  decltype(&checkColourSpace) check_colour_space = &checkColourSpace;
  decltype(&readOtherParts) read_other_parts = &readOtherParts;
};

}  // namespace artcam::oiio_io

// The module's one exported symbol: its table, for io_module.cpp's dlsym.
extern "C" const artcam::oiio_io::Table* artcam_io_oiio_table();
