// SPDX-License-Identifier: Apache-2.0
#include "core/io/stmap_file.h"
#include "core/io/oiio_io.h"

#include "core/io/atomic_file.h"
#include "core/io/image_input.h"
#include "core/io/io_text.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>

namespace artcam {

namespace {

constexpr const char* kConventionAttribute = "artcam:convention";
constexpr const char* kSourceWidthAttribute = "artcam:source_width";
constexpr const char* kSourceHeightAttribute = "artcam:source_height";

int channelNamed(const OIIO::ImageSpec& spec, const std::string& name) {
  for (int c = 0; c < spec.nchannels; ++c)
    if (io_text::lower(std::string(spec.channel_name(c))) == name) return c;
  return -1;
}

}  // namespace

namespace oiio_io {

Status writeStmap(const std::string& path, const PositionMap& map, StmapConvention convention) {
  const int width = map.target_px.width, height = map.target_px.height;
  const bool st = convention == StmapConvention::StMap;
  const int channels = st ? 4 : 2;
  OIIO::ImageSpec spec(width, height, channels, OIIO::TypeDesc::FLOAT);
  // 32-bit float, never half: half keeps 11 bits, a third of a pixel at 2000 px.
  spec.channelnames =
      st ? std::vector<std::string>{"R", "G", "B", "A"} : std::vector<std::string>{"R", "G"};
  spec.alpha_channel = st ? 3 : -1;
  spec.attribute("compression", "zip");
  spec.attribute(kConventionAttribute, std::string(stmapConventionName(convention)));
  spec.attribute(kSourceWidthAttribute, map.source_px.width);
  spec.attribute(kSourceHeightAttribute, map.source_px.height);
  const double w = map.source_px.width, h = map.source_px.height;
  // Rows are converted and written in bands, so the file costs no second copy of the map.
  constexpr int kBand = 64;
  std::vector<float> band(static_cast<size_t>(width) * kBand * static_cast<size_t>(channels));
  const auto fillBand = [&](int y0, int y1) {
    std::fill(band.begin(), band.end(), 0.0f);
    for (int y = y0; y < y1; ++y)
      for (int x = 0; x < width; ++x) {
        const size_t k = map.index(x, y);
        float* p = &band[(static_cast<size_t>(y - y0) * static_cast<size_t>(width) +
                          static_cast<size_t>(x)) *
                         static_cast<size_t>(channels)];
        const double sx = map.x_px[k], sy = map.y_px[k];
        if (st) {
          // Zeros where there is no preimage: alpha 0 says so, and R = G = 0 keeps it finite.
          if (map.valid[k]) {
            p[0] = static_cast<float>(sx / w);
            p[1] = static_cast<float>(1.0 - sy / h);
            p[3] = 1.0f;
          }
        } else {
          p[0] = map.valid[k] ? static_cast<float>(sx - 0.5) : -1.0f;
          p[1] = map.valid[k] ? static_cast<float>(sy - 0.5) : -1.0f;
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
    if (!out->open(temp, spec)) return failure(out->geterror());
    for (int y0 = 0; y0 < height; y0 += kBand) {
      const int y1 = std::min(height, y0 + kBand);
      fillBand(y0, y1);
      if (!out->write_scanlines(y0, y1, 0, OIIO::TypeDesc::FLOAT, band.data())) {
        const std::string message = out->geterror();
        out->close();
        return failure(message);
      }
    }
    if (!out->close()) return failure(out->geterror());
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
  const int r = channelNamed(spec, "r"), g = channelNamed(spec, "g");
  if (r < 0 || g < 0) {
    std::string names;
    for (int c = 0; c < spec.nchannels; ++c)
      names += std::string(c ? ", " : "") + std::string(spec.channel_name(c));
    return R::failure(path + ": not an ST map: it needs channels R and G (s and t), it has " +
                      names);
  }
  // Only the StMap convention marks missing pixels with alpha; an OpenCv map uses −1.
  const int a = samples.convention == StmapConvention::StMap ? channelNamed(spec, "a") : -1;
  samples.has_alpha = a >= 0;
  if (options.source_px) {
    samples.source_px = *options.source_px;
  } else {
    const int sw = spec.get_int_attribute(kSourceWidthAttribute, 0);
    const int sh = spec.get_int_attribute(kSourceHeightAttribute, 0);
    samples.source_px = sw > 0 && sh > 0 ? FrameSize{sw, sh} : samples.map_px;
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
      if (a >= 0 && !(p[a] > 0.0f)) continue;
      Eigen::Vector2d source;
      if (samples.convention == StmapConvention::StMap) {
        source = {s * w, (1.0 - t) * h};
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
  return R::success(std::move(samples));
}

}  // namespace oiio_io
}  // namespace artcam
