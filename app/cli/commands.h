#pragma once

namespace artcam::cli {
int run(int argc, char** argv);
}
