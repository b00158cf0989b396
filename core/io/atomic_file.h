// Atomic saves (DESIGN §5): write to a temporary file in the target's folder, flush, then
// rename over the target. On any failure the temporary is removed and the target untouched.
#pragma once

#include "core/model/status.h"

#include <functional>
#include <string>

namespace artcam {

// `write` receives the temporary path (same folder and extension as `path`) and returns
// whether it succeeded; its message is passed on.
Status writeAtomically(const std::string& path,
                       const std::function<Status(const std::string& temp_path)>& write);
Status writeTextAtomically(const std::string& path, const std::string& text);

}  // namespace artcam
