// SPDX-License-Identifier: Apache-2.0
#include "core/io/heif_write.h"

#include "core/io/io_text.h"

#include <OpenImageIO/imageio.h>
#include <libheif/heif.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <memory>

namespace artcam::io_heif {

namespace {

template <class T, auto Release>
struct Releaser {
  void operator()(T* p) const {
    if (p) Release(p);
  }
};
using Context = std::unique_ptr<heif_context, Releaser<heif_context, heif_context_free>>;
using Encoder = std::unique_ptr<heif_encoder, Releaser<heif_encoder, heif_encoder_release>>;
using Image = std::unique_ptr<heif_image, Releaser<heif_image, heif_image_release>>;
using Handle =
    std::unique_ptr<heif_image_handle, Releaser<heif_image_handle, heif_image_handle_release>>;

}  // namespace

bool writesHeif(const std::string& format) { return format == "heif"; }

Status writeHeif(const std::string& file, const std::string& shown_path, const HeifImage& image,
                 std::optional<int> quality, const HeifMetadata& metadata) {
  const std::string fail = shown_path + ": cannot write: ";
  auto failed = [&](const heif_error& e) {
    return Status::failure(fail + io_text::oneLine(e.message ? e.message : "libheif failed"));
  };
  if (image.width < 1 || image.height < 1 || image.channels < 1 || image.channels > 4 ||
      !image.pixels)
    return Status::failure(fail + "the image is empty or malformed");
  const std::string extension =
      io_text::lower(std::filesystem::path(shown_path).extension().string());
  const heif_compression_format codec =
      extension == ".avif" ? heif_compression_AV1 : heif_compression_HEVC;
  if (!heif_have_encoder_for_format(codec))
    return Status::failure(fail + "this libheif has no " +
                           (codec == heif_compression_AV1 ? "AV1" : "HEVC") + " encoder");

  Context context(heif_context_alloc());
  heif_encoder* raw_encoder = nullptr;
  if (heif_error e = heif_context_get_encoder_for_format(context.get(), codec, &raw_encoder);
      e.code)
    return failed(e);
  Encoder encoder(raw_encoder);
  if (quality) heif_encoder_set_lossy_quality(encoder.get(), std::clamp(*quality, 1, 100));

  const bool alpha = image.has_alpha;
  const int out_channels = alpha ? 4 : 3;
  heif_image* raw_image = nullptr;
  if (heif_error e = heif_image_create(
          image.width, image.height, heif_colorspace_RGB,
          alpha ? heif_chroma_interleaved_RGBA : heif_chroma_interleaved_RGB, &raw_image);
      e.code)
    return failed(e);
  Image picture(raw_image);
  if (heif_error e = heif_image_add_plane(picture.get(), heif_channel_interleaved, image.width,
                                          image.height, 8);
      e.code)
    return failed(e);
  int stride = 0;
  std::uint8_t* plane = heif_image_get_plane(picture.get(), heif_channel_interleaved, &stride);
  if (!plane) return Status::failure(fail + "libheif gave no image plane");
  const int colours = image.channels - (alpha ? 1 : 0);
  for (int y = 0; y < image.height; ++y) {
    const std::uint8_t* src = image.pixels + static_cast<std::size_t>(y) *
                                                 static_cast<std::size_t>(image.width) *
                                                 static_cast<std::size_t>(image.channels);
    std::uint8_t* dst = plane + static_cast<std::ptrdiff_t>(y) * stride;
    for (int x = 0; x < image.width; ++x, src += image.channels, dst += out_channels) {
      for (int c = 0; c < 3; ++c) dst[c] = src[colours == 1 ? 0 : c];  // grey as RGB
      if (alpha) dst[3] = src[image.channels - 1];
    }
  }
  if (!image.icc.empty())
    if (heif_error e = heif_image_set_raw_color_profile(picture.get(), "prof", image.icc.data(),
                                                        image.icc.size());
        e.code)
      return failed(e);

  heif_image_handle* raw_handle = nullptr;
  if (heif_error e = heif_context_encode_image(context.get(), picture.get(), encoder.get(), nullptr,
                                               &raw_handle);
      e.code)
    return failed(e);
  Handle handle(raw_handle);
  if (!metadata.exif.empty())
    if (heif_error e =
            heif_context_add_exif_metadata(context.get(), handle.get(), metadata.exif.data(),
                                           static_cast<int>(metadata.exif.size()));
        e.code)
      return failed(e);
  if (!metadata.xmp.empty())
    if (heif_error e =
            heif_context_add_XMP_metadata(context.get(), handle.get(), metadata.xmp.data(),
                                          static_cast<int>(metadata.xmp.size()));
        e.code)
      return failed(e);
  if (heif_error e = heif_context_write_to_file(context.get(), file.c_str()); e.code)
    return failed(e);
  return Status::success();
}

Status writeHeifPhoto(const std::string& file, const std::string& shown_path, HeifImage image,
                      const void* icc_spec, std::optional<int> quality,
                      const PhotoMetadata* metadata, const MetadataUpdate& update,
                      std::vector<std::string>& left_out) {
  if (icc_spec) {
    const auto& spec = *static_cast<const OIIO::ImageSpec*>(icc_spec);
    if (const OIIO::ParamValue* p = spec.find_attribute("ICCProfile"))
      image.icc.assign(static_cast<const unsigned char*>(p->data()),
                       static_cast<const unsigned char*>(p->data()) + p->datasize());
  }
  HeifMetadata blocks;
  if (metadata) {
    EncodedPhotoMetadata encoded = encodePhotoMetadata(*metadata, update);
    blocks.exif = std::move(encoded.exif);
    blocks.xmp = std::move(encoded.xmp);
    left_out.insert(left_out.end(), encoded.left_out.begin(), encoded.left_out.end());
    if (encoded.iptc) left_out.push_back("the IPTC block (HEIF has no place for it)");
  }
  return writeHeif(file, shown_path, image, quality, blocks);
}

}  // namespace artcam::io_heif
