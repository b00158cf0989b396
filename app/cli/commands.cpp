#include "app/cli/commands.h"

#include <cstdio>

namespace artcam::cli {
int run(int, char**) {
  std::puts("artcam: not yet");
  return 0;
}
}  // namespace artcam::cli
