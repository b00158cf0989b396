// SPDX-License-Identifier: Apache-2.0
// The module's entry point (oiio_io.h): its table of entry points, for io_module.cpp.
#include "core/io/oiio_io.h"

#include "core/io/colour_config.h"

namespace artcam::oiio_io {
Status checkColourSpace(const std::string& name, const std::string& option) {
  return io_colour::checkColourSpace(name, option);
}
}  // namespace artcam::oiio_io

extern "C" __attribute__((visibility("default"))) const artcam::oiio_io::Table* artcam_io_oiio_table() {
  static const artcam::oiio_io::Table table;
  return &table;
}
