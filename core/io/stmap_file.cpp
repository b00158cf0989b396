// SPDX-License-Identifier: Apache-2.0
#include "core/io/stmap_file.h"
#include "core/io/oiio_io.h"

#include "core/fit/normalize.h"
#include "core/io/atomic_file.h"
#include "core/io/checked_output.h"
#include "core/io/image_input.h"
#include "core/io/io_text.h"
#include "core/model/artcam.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace artcam {

namespace {

constexpr const char* kConventionAttribute = "artcam:convention";
constexpr const char* kSourceWidthAttribute = "artcam:source_width";
constexpr const char* kSourceHeightAttribute = "artcam:source_height";
constexpr const char* kLayersAttribute = "artcam:layers";

int channelNamed(const OIIO::ImageSpec& spec, const std::string& name) {
  for (int c = 0; c < spec.nchannels; ++c)
    if (io_text::lower(std::string(spec.channel_name(c))) == name) return c;
  return -1;
}

}  // namespace

namespace oiio_io {

Status writeStmap(const std::string& path, const std::vector<StmapLayer>& layers,
                  StmapConvention convention) {
  if (layers.empty() || !layers[0].map)
    throw std::invalid_argument("writeStmap: no map to write");
  const PositionMap& first = *layers[0].map;
  const int width = first.target_px.width, height = first.target_px.height;
  for (const StmapLayer& layer : layers)
    if (!layer.map || layer.map->target_px != first.target_px ||
        layer.map->source_px != first.source_px || (layers.size() > 1 && layer.name.empty()))
      throw std::invalid_argument("writeStmap: layers of different frames, or an unnamed layer");
  const bool st = convention == StmapConvention::StMap;
  const int per_layer = stmapChannelCount(convention);
  const int channels = per_layer * static_cast<int>(layers.size());
  OIIO::ImageSpec spec(width, height, channels, OIIO::TypeDesc::FLOAT);
  // 32-bit float, never half: half keeps 11 bits, a third of a pixel at 2000 px.
  spec.channelnames.clear();
  std::string layer_names;
  for (const StmapLayer& layer : layers) {
    const std::string prefix = layer.name.empty() ? "" : layer.name + ".";
    for (const char* c : {"R", "G", "B", "A"}) {
      if (!st && (c[0] == 'B' || c[0] == 'A')) continue;
      spec.channelnames.push_back(prefix + c);
    }
    layer_names += (layer_names.empty() ? "" : ",") + layer.name;
  }
  spec.alpha_channel = st && layers.size() == 1 ? 3 : -1;
  spec.attribute("compression", "zip");
  spec.attribute(kConventionAttribute, std::string(stmapConventionName(convention)));
  spec.attribute(kSourceWidthAttribute, first.source_px.width);
  spec.attribute(kSourceHeightAttribute, first.source_px.height);
  if (layers.size() > 1) spec.attribute(kLayersAttribute, layer_names);
  // Rows are converted and written in bands, so the file costs no second copy of the map.
  constexpr int kBand = 64;
  std::vector<float> band(static_cast<size_t>(width) * kBand * static_cast<size_t>(channels));
  const auto fillBand = [&](int y0, int y1) {
    std::fill(band.begin(), band.end(), 0.0f);
    for (int y = y0; y < y1; ++y)
      for (int x = 0; x < width; ++x) {
        float* p = &band[(static_cast<size_t>(y - y0) * static_cast<size_t>(width) +
                          static_cast<size_t>(x)) *
                         static_cast<size_t>(channels)];
        for (const StmapLayer& layer : layers) {
          const PositionMap& map = *layer.map;
          stmapPixel(map, map.index(x, y), convention, p);
          p += per_layer;
        }
      }
  };
  return writeAtomically(path, [&](const std::string& temp) {
    auto failure = [&](const std::string& message) {
      return Status::failure(path + ": cannot write the map: " +
                             io_text::replaceAll(io_text::oneLine(message), temp, path));
    };
    auto out = OIIO::ImageOutput::create(temp);
    if (!out) return failure(OIIO::geterror());
    // Float maps with named channels and header attributes: OpenEXR is what every tool reads.
    if (out->format_name() != std::string("openexr"))
      return Status::failure(path + ": an ST map is written as OpenEXR (name it .exr)");
    io_checked::CheckedWrite checked(std::move(out));
    if (!checked.open(temp, spec)) return failure(checked.cause());
    for (int y0 = 0; y0 < height; y0 += kBand) {
      const int y1 = std::min(height, y0 + kBand);
      fillBand(y0, y1);
      if (!checked.output().write_scanlines(y0, y1, 0, OIIO::TypeDesc::FLOAT, band.data()))
        return failure(checked.cause());
    }
    if (!checked.close()) return failure(checked.cause());
    return Status::success();
  });
}

Result<StmapSamples> readStmapSamples(const std::string& path, const StmapSampleOptions& options) {
  using R = Result<StmapSamples>;
  auto opened = io_input::openImageInput(path);
  if (!opened) return R::failure(opened.status.message);
  OIIO::ImageInput& in = **opened;
  const OIIO::ImageSpec spec = in.spec();
  StmapSamples samples;
  // The frame is the display window (an EXR's data window may be larger, overscan, or smaller).
  samples.map_px = spec.full_width > 0 && spec.full_height > 0
                       ? FrameSize{spec.full_width, spec.full_height}
                       : FrameSize{spec.width, spec.height};
  const std::string convention_name = spec.get_string_attribute(kConventionAttribute, "stmap");
  const auto convention = stmapConventionFromName(convention_name);
  if (!convention)
    return R::failure(path + ": unknown " + kConventionAttribute + " \"" + convention_name +
                      "\" (stmap or opencv)");
  samples.convention = *convention;
  // A layered map (one per colour channel): the layer asked for, by name.
  const std::string layers = spec.get_string_attribute(kLayersAttribute, "");
  std::string prefix;
  if (!options.layer.empty()) {
    prefix = io_text::lower(options.layer) + ".";
    if (channelNamed(spec, prefix + "r") < 0)
      return R::failure(path + ": no layer \"" + options.layer + "\" in the map" +
                        (layers.empty() ? " (it has one map, not layers)"
                                        : " (its layers: " + layers + ")"));
  } else if (!layers.empty() && channelNamed(spec, "r") < 0) {
    return R::failure(path + ": a layered map (layers " + layers +
                      ": one per colour channel); name the one to fit (--layer NAME)");
  }
  const int r = channelNamed(spec, prefix + "r"), g = channelNamed(spec, prefix + "g");
  if (r < 0 || g < 0) {
    std::string names;
    for (int c = 0; c < spec.nchannels; ++c)
      names += std::string(c ? ", " : "") + std::string(spec.channel_name(c));
    return R::failure(path + ": not an ST map: it needs channels R and G (s and t), it has " +
                      names);
  }
  // Only the StMap convention marks missing pixels with alpha; an OpenCv map uses −1.
  const int a = samples.convention == StmapConvention::StMap ? channelNamed(spec, prefix + "a") : -1;
  samples.has_alpha = a >= 0;
  if (options.source_px) {
    samples.source_px = *options.source_px;
  } else {
    const int sw = spec.get_int_attribute(kSourceWidthAttribute, 0);
    const int sh = spec.get_int_attribute(kSourceHeightAttribute, 0);
    samples.source_px = sw > 0 && sh > 0 ? FrameSize{sw, sh} : samples.map_px;
    // The header's claim becomes the camera's source frame: refused here, where the option
    // that replaces it can be named, rather than by the camera file the fit would write.
    if (samples.source_px.width > kMaxFrameSide || samples.source_px.height > kMaxFrameSide)
      return R::failure(path + ": " + kSourceWidthAttribute + "/" + kSourceHeightAttribute + " " +
                        std::to_string(samples.source_px.width) + "x" +
                        std::to_string(samples.source_px.height) + " has a side beyond the " +
                        std::to_string(kMaxFrameSide) +
                        " pixels a camera's frame may have; give the photo's size (--size WxH)");
  }
  // Rows are read one at a time, only those on the grid: a map's memory never grows with its
  // height, and a hostile header cannot ask for gigabytes.
  if (spec.width > (1 << 20) || spec.height > (1 << 20) || spec.nchannels > 64)
    return R::failure(path + ": the map is too large (" + std::to_string(spec.width) + "x" +
                      std::to_string(spec.height) + ", " + std::to_string(spec.nchannels) +
                      " channels)");
  int step = options.step;
  if (step <= 0) {
    step = 1;
    while ((static_cast<long long>(spec.width + step - 1) / step) *
               ((spec.height + step - 1) / step) >
           options.max_matches)
      ++step;
  }
  samples.step = step;
  const double w = samples.source_px.width, h = samples.source_px.height;
  // Pixel (i, j) of the data window is display pixel (x0 + i, y0 + j): an overscan map's
  // pixels outside the display window are matches too, with targets outside the frame.
  const int x0 = spec.x - spec.full_x, y0 = spec.y - spec.full_y;
  const size_t channels = static_cast<size_t>(spec.nchannels);
  std::vector<float> row(static_cast<size_t>(spec.width) * channels);
  // The grid starts half a step in, so it is centred on the map.
  for (int j = step / 2; j < spec.height; j += step) {
    if (!in.read_scanlines(0, 0, spec.y + j, spec.y + j + 1, spec.z, 0, spec.nchannels,
                           OIIO::TypeDesc::FLOAT, row.data()))
      return R::failure(path + ": cannot read: row " + std::to_string(spec.y + j) + ": " +
                        io_text::oneLine(in.geterror()));
    for (int i = step / 2; i < spec.width; i += step) {
      const float* p = &row[static_cast<size_t>(i) * channels];
      const double s = p[r], t = p[g];
      if (!std::isfinite(s) || !std::isfinite(t)) continue;
      Eigen::Vector2d source;
      if (samples.convention == StmapConvention::StMap) {
        source = {s * w, (1.0 - t) * h};
        // Alpha 0: the warp reads nothing there (position_map.h). A position beyond the photo
        // is still the camera's geometry and is kept; one inside it (R = G = 0, or a foreign
        // map's masked pixel) is no preimage.
        if (a >= 0 && !(p[a] > 0.0f) &&
            preimageAt(static_cast<float>(source.x()), static_cast<float>(source.y()),
                       samples.source_px) != Preimage::OutsidePhoto)
          continue;
      } else {
        if (s == -1.0 && t == -1.0) continue;
        source = {s + 0.5, t + 0.5};
      }
      PointMatch m;
      m.source = source;
      m.target = Eigen::Vector2d(x0 + i + 0.5, y0 + j + 0.5);
      samples.matches.push_back(std::move(m));
    }
  }
  if (const Status st = io_input::decodeProblems(in, path); !st) return R::failure(st.message);
  if (samples.matches.empty())
    return R::failure(path + ": no pixel of the map has a source position (alpha is 0 " +
                      "everywhere on the sampling grid)");
  // A camera's inverse map reads a different source place for each pixel, spread over the
  // plane. Samples at one point (a constant map) or on one line hold no camera: a fit would
  // only average them (a translation off by the map's own size) and call that a camera.
  Points sources(2, static_cast<Eigen::Index>(samples.matches.size()));
  for (size_t k = 0; k < samples.matches.size(); ++k)
    sources.col(static_cast<Eigen::Index>(k)) = samples.matches[k].source.head<2>();
  if (spreadRatio(sources) < 1e-7)
    return R::failure(path + ": every sample of the map reads " +
                      (countDistinct(sources, 2) < 2 ? "the same source point (a constant map)"
                                                     : "source points on one line") +
                      ": an ST map of a camera reads a different place for each pixel");
  return R::success(std::move(samples));
}

}  // namespace oiio_io
}  // namespace artcam
