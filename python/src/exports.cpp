// SPDX-License-Identifier: Apache-2.0
#include "python/src/common.h"
namespace artcam::python {
void registerExports(py::module_&) {}
}  // namespace artcam::python
