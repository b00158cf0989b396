// SPDX-License-Identifier: Apache-2.0
// The module's entry point (oiio_io.h): its table of entry points, for io_module.cpp.
#include "core/io/oiio_io.h"

extern "C" __attribute__((visibility("default"))) const artcam::oiio_io::Table* artcam_io_oiio_table() {
  static const artcam::oiio_io::Table table;
  return &table;
}
