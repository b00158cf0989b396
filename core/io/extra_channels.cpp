// SPDX-License-Identifier: Apache-2.0
// Extra channels (image_io.h, "Channels"): reading them in groups, and the writers' helpers
// (extra_channels.h).
#include "core/io/extra_channels.h"
#include "core/io/oiio_io.h"

#include "core/io/image_input.h"
#include "core/io/io_text.h"
#include "core/io/orientation.h"

#include <algorithm>
#include <exception>
#include <filesystem>
#include <set>
#include <utility>

namespace artcam {

namespace oiio_io {

bool formatStoresExtraChannels(const std::string& path) {
  auto out = OIIO::ImageOutput::create(OIIO::string_view(path));
  if (!out) {
    OIIO::geterror();
    return false;
  }
  return std::string(out->format_name()) == "openexr";
}

Result<ExtraChannels> readExtraChannels(const std::string& path, const ImageInfo& info,
                                        const ReadImageOptions& options) {
  using R = Result<ExtraChannels>;
  auto opened = io_input::openImageInput(path);
  if (!opened) return R::failure(opened.status.message);
  OIIO::ImageInput& in = **opened;
  const OIIO::ImageSpec spec = in.spec();
  if (const Status windows = io_input::dataWindowIsDisplayWindow(in, spec, path); !windows)
    return R::failure(windows.message);
  const int first = io_input::keptChannels(spec);
  const auto nameOf = [&](int c) {
    return c < static_cast<int>(spec.channelnames.size()) &&
                   !spec.channelnames[static_cast<size_t>(c)].empty()
               ? spec.channelnames[static_cast<size_t>(c)]
               : "channel " + std::to_string(c);
  };
  const auto formatOf = [&](int c) {
    return c < static_cast<int>(spec.channelformats.size())
               ? spec.channelformats[static_cast<size_t>(c)]
               : spec.format;
  };
  const auto integerAt = [&](int c) {
    const OIIO::TypeDesc t = formatOf(c);
    return t.basetype != OIIO::TypeDesc::HALF && t.basetype != OIIO::TypeDesc::FLOAT &&
           t.basetype != OIIO::TypeDesc::DOUBLE;
  };
  // Runs of one kind (depth-like, other sampled-nearest, or interpolated), cut at four:
  // [begin, end) in the file's channels.
  const auto kindOf = [&](int c) {
    return isDepthChannel(nameOf(c)) ? 2 : sampledNearest(nameOf(c), integerAt(c)) ? 1 : 0;
  };
  std::vector<std::pair<int, int>> runs;
  for (int c = first; c < spec.nchannels; ++c) {
    if (runs.empty() || runs.back().second - runs.back().first == 4 ||
        kindOf(runs.back().first) != kindOf(c))
      runs.emplace_back(c, c + 1);
    else
      runs.back().second = c + 1;
  }
  ExtraChannels extra;
  const bool swap = orientationSwapsAxes(info.stored_orientation);
  for (size_t k = 0; k < runs.size(); ++k) {
    const auto [begin, end] = runs[k];
    const int n = end - begin;
    ChannelGroup group;
    for (int c = begin; c < end; ++c) group.names.push_back(nameOf(c));
    group.depth = kindOf(begin) == 2;
    group.nearest = kindOf(begin) != 0;
    for (int c = begin; c < end; ++c) group.stored_types.push_back(formatOf(c).c_str());
    ImageF stored(spec.width, spec.height, n, -1);
    bool ok = false;
    try {
      ok = in.read_image(0, 0, begin, end, OIIO::TypeDesc::FLOAT, stored.data.data());
    } catch (const std::exception& e) {
      return R::failure(path + ": cannot read: " + io_text::decoderFailure(e));
    }
    if (!ok) return R::failure(path + ": cannot read: " + io_text::oneLine(in.geterror()));
    if (const Status damage = io_input::decodeProblems(in, path); !damage)
      return R::failure(damage.message);
    if (info.stored_orientation != 1) {
      ImageF upright(swap ? stored.height : stored.width, swap ? stored.width : stored.height, n, -1);
      reorientPixels(stored.data.data(), stored.width, stored.height,
                     sizeof(float) * static_cast<size_t>(n), info.stored_orientation,
                     upright.data.data());
      stored = std::move(upright);
    }
    group.image = std::move(stored);
    extra.groups.push_back(std::move(group));
    if (options.progress && !options.progress(static_cast<double>(k + 1) / runs.size()))
      return R::failure(path + ": cannot read: cancelled");
  }
  return R::success(std::move(extra));
}

}  // namespace oiio_io

namespace io_extra {

Status addExtraChannels(OIIO::ImageSpec& spec, const std::string& format,
                        const ExtraChannels* extra, const std::string& path) {
  if (!extra || extra->empty()) return Status::success();
  const std::string fail = path + ": cannot write: ";
  if (format != "openexr")
    return Status::failure(fail + "the " + format + " format holds no extra channels (" +
                           std::to_string(extra->names().size()) + " given)");
  std::set<std::string> seen(spec.channelnames.begin(), spec.channelnames.end());
  for (const ChannelGroup& g : extra->groups) {
    if (g.image.width != spec.width || g.image.height != spec.height ||
        g.image.channels != static_cast<int>(g.names.size()))
      return Status::failure(fail + "the extra channels are not the image's size");
    for (const std::string& name : g.names) {
      if (!seen.insert(name).second)
        return Status::failure(fail + "the channel name \"" + name + "\" is used twice");
      spec.channelnames.push_back(name);
      ++spec.nchannels;
    }
  }
  // Each extra channel in the type the file stored it in (OpenImageIO converts the float rows
  // written to each channel's type); the image's own channels in the spec's.
  std::vector<OIIO::TypeDesc> formats(static_cast<size_t>(spec.nchannels) - extra->names().size(),
                                      spec.format);
  for (const ChannelGroup& g : extra->groups)
    for (size_t k = 0; k < g.names.size(); ++k)
      formats.push_back(k < g.stored_types.size() && !g.stored_types[k].empty()
                            ? OIIO::TypeDesc(g.stored_types[k])
                            : spec.format);
  const bool one_type = std::all_of(formats.begin(), formats.end(),
                                    [&](OIIO::TypeDesc t) { return t == spec.format; });
  spec.channelformats = one_type ? std::vector<OIIO::TypeDesc>{} : formats;
  return Status::success();
}

void interleaveRows(const float* main, int main_channels, int width, int y0, int y1,
                    const ExtraChannels& extra, std::vector<float>& out) {
  size_t total = static_cast<size_t>(main_channels);
  for (const ChannelGroup& g : extra.groups) total += static_cast<size_t>(g.image.channels);
  const size_t pixels = static_cast<size_t>(width) * static_cast<size_t>(y1 - y0);
  out.resize(pixels * total);
  float* dst = out.data();
  for (int y = y0; y < y1; ++y)
    for (int x = 0; x < width; ++x) {
      const float* m = main + (static_cast<size_t>(y - y0) * static_cast<size_t>(width) +
                               static_cast<size_t>(x)) * static_cast<size_t>(main_channels);
      dst = std::copy(m, m + main_channels, dst);
      for (const ChannelGroup& g : extra.groups) {
        const float* e = g.image.pixel(x, y);
        dst = std::copy(e, e + g.image.channels, dst);
      }
    }
}

void keepDisplayWindow(OIIO::ImageSpec& spec, const std::string& format,
                       const OIIO::ImageSpec* like) {
  if (format != "openexr" || !like) return;
  spec.x = spec.full_x = like->full_x;
  spec.y = spec.full_y = like->full_y;
  spec.full_width = spec.width;
  spec.full_height = spec.height;
}

}  // namespace io_extra
}  // namespace artcam
