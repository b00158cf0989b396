// SPDX-License-Identifier: Apache-2.0
// The writers' side of extra channels and windows (io room only: it exposes OpenImageIO):
// writeImage and writeStoredImage build their OIIO spec, then these add what image_io.h's
// "Channels" and "Data and display windows" decisions ask for, the same way in both.
#pragma once

#include "core/io/image_io.h"
#include "core/model/status.h"

#include <OpenImageIO/imageio.h>

#include <string>
#include <vector>

namespace artcam::io_extra {

// Appends `extra`'s channel names to `spec` (nchannels, channelnames; the spec's pixel type).
// Fails in one line naming `path` when the format is not OpenEXR, a name repeats one already
// there, or a group is not `spec`'s size. Null or empty `extra`: nothing to do.
Status addExtraChannels(OIIO::ImageSpec& spec, const std::string& format,
                        const ExtraChannels* extra, const std::string& path);

// Rows y0..y1 of the image's own channels (`main`: packed, `main_channels` floats per pixel)
// with every extra channel appended to each pixel, into `out` (resized).
void interleaveRows(const float* main, int main_channels, int width, int y0, int y1,
                    const ExtraChannels& extra, std::vector<float>& out);

// The specs of every part a writer opens: `first` (the image's, made the first part and named
// "rgba" when it has no name and parts follow), then one per part in `parts` at its windows,
// each channel in its stored type. Fails in one line naming `path` when the format is not
// OpenEXR, names repeat, or a part is not the image's size. Null or empty `parts`: {first}.
Result<std::vector<OIIO::ImageSpec>> partSpecs(OIIO::ImageSpec& first, const std::string& format,
                                               const std::vector<ImagePart>* parts,
                                               const std::string& path);

// After the first part's scanlines: each later part of `specs` appended and written from `parts`
// (specs[k] is parts[k - 1]'s). False on the writer's failure (its message in out.geterror()).
bool writeParts(OIIO::ImageOutput& out, const std::string& temp,
                const std::vector<OIIO::ImageSpec>& specs, const std::vector<ImagePart>& parts);

// An OpenEXR output's windows: display window at `like`'s display-window origin with the
// spec's size, data window equal to it. Other formats and a null `like` are left as they are.
void keepDisplayWindow(OIIO::ImageSpec& spec, const std::string& format,
                       const OIIO::ImageSpec* like);

}  // namespace artcam::io_extra
