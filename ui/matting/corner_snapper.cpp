// The studio's corner snap: core's checkerboard X-corner finder with its default options.
#include "ui/matting/insertion_studio.h"

#if __has_include("core/piecewise/corner_snap.h")
#include "core/piecewise/corner_snap.h"
#define ARTCAM_HAS_CORNER_SNAP 1
#endif

namespace artcam::ui {

CornerSnapper defaultCornerSnapper() {
#ifdef ARTCAM_HAS_CORNER_SNAP
  return [](const ImageF& photo, const Eigen::Vector2d& click) {
    return snapToGridCorner(photo, click);
  };
#else
  return {};
#endif
}

}  // namespace artcam::ui
