#include "core/io/image_input.h"

#include "core/io/io_text.h"

#include <filesystem>
#include <system_error>

namespace artcam::io_input {

Result<OIIO::ImageInput::unique_ptr> openImageInput(const std::string& path) {
  using R = Result<OIIO::ImageInput::unique_ptr>;
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error))
    return R::failure(path + ": cannot read: " +
                      (std::filesystem::exists(path, error) ? "not a file" : "no such file"));
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  auto in = OIIO::ImageInput::open(path, &config);
  if (!in) return R::failure(path + ": cannot read: " + io_text::oneLine(OIIO::geterror()));
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0)
    return R::failure(path + ": cannot read: the image is empty");
  if (spec.depth > 1) return R::failure(path + ": cannot read: volume images are not supported");
  return R::success(std::move(in));
}

}  // namespace artcam::io_input
