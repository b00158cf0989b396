// SPDX-License-Identifier: Apache-2.0
#include "core/util/module_path.h"

#include <dlfcn.h>

namespace artcam {

std::string engineModuleDirectory() {
  Dl_info self{};
  if (dladdr(reinterpret_cast<void*>(&engineModuleDirectory), &self) == 0 || !self.dli_fname)
    return {};
  const std::string path = self.dli_fname;
  const size_t slash = path.rfind('/');
  return slash == std::string::npos ? std::string() : path.substr(0, slash + 1);
}

}  // namespace artcam
