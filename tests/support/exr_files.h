// SPDX-License-Identifier: Apache-2.0
// Multi-channel EXR files made in the tests with OpenImageIO directly (not through the engine):
// any channel names, an alpha among them, and a data and display window away from the origin.
#pragma once

#include <functional>
#include <string>
#include <vector>

namespace artcam::test {

// A float EXR of w×h texels, channels named `names` (alpha: the index of "A", or −1), its data
// and display window both at (x0, y0); channel c of texel (x, y) holds value(c, x, y).
bool writeFloatExr(const std::string& path, int w, int h, const std::vector<std::string>& names,
                   int alpha, int x0, int y0, const std::function<float(int, int, int)>& value);

}  // namespace artcam::test
