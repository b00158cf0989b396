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

namespace {

// Channels [first, nchannels) of `in`'s current part, grouped (image_io.h, "Channels"): runs of
// one kind (depth-like, other sampled-nearest, or interpolated) cut at four, each read as float
// and turned upright as `info` says.
Result<ExtraChannels> readGroups(OIIO::ImageInput& in, int part, int first, const ImageInfo& info,
                                 const ReadImageOptions& options, const std::string& path) {
  using R = Result<ExtraChannels>;
  const OIIO::ImageSpec spec = in.spec();
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
      ok = in.read_image(part, 0, begin, end, OIIO::TypeDesc::FLOAT, stored.data.data());
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

}  // namespace

Result<ExtraChannels> readExtraChannels(const std::string& path, const ImageInfo& info,
                                        const ReadImageOptions& options) {
  using R = Result<ExtraChannels>;
  auto opened = io_input::openImageInput(path);
  if (!opened) return R::failure(opened.status.message);
  OIIO::ImageInput& in = **opened;
  const OIIO::ImageSpec spec = in.spec();
  if (const Status windows =
          io_input::dataWindowIsDisplayWindow(in, spec, path, options.data_window);
      !windows)
    return R::failure(windows.message);
  return readGroups(in, 0, io_input::keptChannels(spec), info, options, path);
}

Result<std::vector<ImagePart>> readOtherParts(const std::string& path, const ImageInfo& info,
                                              const ReadImageOptions& options) {
  using R = Result<std::vector<ImagePart>>;
  auto opened = io_input::openImageInput(path);
  if (!opened) return R::failure(opened.status.message);
  OIIO::ImageInput& in = **opened;
  const OIIO::ImageSpec first = in.spec();
  std::vector<ImagePart> parts;
  for (int part = 1; in.seek_subimage(part, 0); ++part) {
    const OIIO::ImageSpec& spec = in.spec();
    const std::string name = spec.get_string_attribute("name");
    ImagePart read{name.empty() ? "part " + std::to_string(part) : name, {}};
    // Camera pixels are the first part's: another data window would put this part's elsewhere.
    if (spec.x != first.x || spec.y != first.y || spec.width != first.width ||
        spec.height != first.height || spec.depth > 1)
      return R::failure(path + ": cannot read part \"" + read.name + "\": its data window (" +
                        std::to_string(spec.width) + "x" + std::to_string(spec.height) +
                        ") is not the first part's (" + std::to_string(first.width) + "x" +
                        std::to_string(first.height) + ")");
    auto channels = readGroups(in, part, 0, info, options, path);
    if (!channels) return R::failure(channels.status.message);
    read.channels = std::move(*channels.value);
    parts.push_back(std::move(read));
  }
  in.geterror();  // the failed seek past the last part
  return R::success(std::move(parts));
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

Result<std::vector<OIIO::ImageSpec>> partSpecs(OIIO::ImageSpec& first, const std::string& format,
                                               const std::vector<ImagePart>* parts,
                                               const std::string& path) {
  using R = Result<std::vector<OIIO::ImageSpec>>;
  std::vector<OIIO::ImageSpec> specs{first};
  if (!parts || parts->empty()) return R::success(std::move(specs));
  const std::string fail = path + ": cannot write: ";
  if (format != "openexr")
    return R::failure(fail + "the " + format + " format holds one part, not " +
                      std::to_string(parts->size() + 1));
  // Every part of a multi-part OpenEXR is named, each name its own.
  if (first.get_string_attribute("name").empty()) first.attribute("name", "rgba");
  specs.front() = first;
  std::set<std::string> names{first.get_string_attribute("name")};
  for (const ImagePart& part : *parts) {
    if (!names.insert(part.name).second)
      return R::failure(fail + "the part name \"" + part.name + "\" is used twice");
    OIIO::ImageSpec spec(first.width, first.height, 0, OIIO::TypeDesc::FLOAT);
    spec.x = first.x;
    spec.y = first.y;
    spec.full_x = first.full_x;
    spec.full_y = first.full_y;
    spec.full_width = first.full_width;
    spec.full_height = first.full_height;
    spec.channelnames.clear();
    spec.attribute("name", part.name);
    spec.attribute("compression", first.get_string_attribute("compression", "zip"));
    for (const ChannelGroup& g : part.channels.groups) {
      if (g.image.width != first.width || g.image.height != first.height)
        return R::failure(fail + "part \"" + part.name + "\" is not the image's size");
      for (size_t k = 0; k < g.names.size(); ++k) {
        spec.channelnames.push_back(g.names[k]);
        spec.channelformats.push_back(k < g.stored_types.size() && !g.stored_types[k].empty()
                                          ? OIIO::TypeDesc(g.stored_types[k])
                                          : OIIO::TypeDesc(OIIO::TypeDesc::FLOAT));
        ++spec.nchannels;
      }
    }
    if (spec.nchannels == 0) return R::failure(fail + "part \"" + part.name + "\" has no channels");
    specs.push_back(std::move(spec));
  }
  return R::success(std::move(specs));
}

bool writeParts(OIIO::ImageOutput& out, const std::string& temp,
                const std::vector<OIIO::ImageSpec>& specs, const std::vector<ImagePart>& parts) {
  std::vector<float> rows;
  for (size_t p = 1; p < specs.size(); ++p) {
    const OIIO::ImageSpec& spec = specs[p];
    if (!out.open(temp, spec, OIIO::ImageOutput::AppendSubimage)) return false;
    constexpr int kBand = 64;
    for (int y0 = 0; y0 < spec.height; y0 += kBand) {
      const int y1 = std::min(spec.height, y0 + kBand);
      interleaveRows(nullptr, 0, spec.width, y0, y1, parts[p - 1].channels, rows);
      if (!out.write_scanlines(spec.y + y0, spec.y + y1, 0, OIIO::TypeDesc::FLOAT, rows.data()))
        return false;
    }
  }
  return true;
}

void keepDisplayWindow(OIIO::ImageSpec& spec, const std::string& format,
                       const OIIO::ImageSpec* like) {
  if (format != "openexr" || !like) return;
  // An image of `like`'s data window that is not its display window (overscan kept): both
  // windows as they were.
  if ((like->x != like->full_x || like->y != like->full_y || like->width != like->full_width ||
       like->height != like->full_height) &&
      like->full_width > 0 && spec.width == like->width && spec.height == like->height) {
    spec.x = like->x;
    spec.y = like->y;
    spec.full_x = like->full_x;
    spec.full_y = like->full_y;
    spec.full_width = like->full_width;
    spec.full_height = like->full_height;
    return;
  }
  spec.x = spec.full_x = like->full_x;
  spec.y = spec.full_y = like->full_y;
  spec.full_width = spec.width;
  spec.full_height = spec.height;
}

}  // namespace io_extra
}  // namespace artcam
