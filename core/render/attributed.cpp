// SPDX-License-Identifier: Apache-2.0
// Attributed rendering (attributed.h): the colour-only and gather paths, the path choice and
// layers; the splat path is splat.cpp.
#include "core/render/attributed.h"

#include "core/model/analysed_cameras.h"
#include "core/model/frames.h"
#include "core/mapping/coordinates.h"
#include "core/util/parallel.h"
#include "core/sampling/sampling.h"
#include "core/render/depth_coverage.h"
#include "core/render/splat.h"
#include "core/render/warp.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <initializer_list>
#include <optional>
#include <stdexcept>
#include <vector>

namespace artcam {

std::string_view attributedPathName(AttributedPath path) {
  switch (path) {
    case AttributedPath::Geometry: return "geometry";
    case AttributedPath::ColourOnly: return "colour-only";
    case AttributedPath::Gather: return "gather";
    case AttributedPath::Splat: return "splat";
  }
  return "unknown";
}

namespace {

// The output elements that depend on the input elements `seeds` through every stage: an output
// is tainted when its Q_i couples a tainted element with anything, and eq 5 divides each block
// by its own weight, so one tainted element taints its whole block at each re-homogenisation.
std::vector<bool> taintedOutputs(const Camera& camera, std::initializer_list<int> seeds) {
  const BlockLayout& layout = camera.layout();
  const int n = layout.dimension;
  std::vector<bool> tainted(static_cast<size_t>(n), false);
  for (int s : seeds) tainted[static_cast<size_t>(s)] = true;
  for (const Stage& stage : camera.stages()) {
    std::vector<bool> next(static_cast<size_t>(n), false);
    for (int i = 0; i < n; ++i)
      for (int r = 0; r < n && !next[static_cast<size_t>(i)]; ++r)
        for (int c = 0; c < n; ++c)
          if ((tainted[static_cast<size_t>(r)] || tainted[static_cast<size_t>(c)]) &&
              stage.q[static_cast<size_t>(i)](r, c) != 0.0) {
            next[static_cast<size_t>(i)] = true;
            break;
          }
    for (size_t b = 0; b < layout.blocks.size(); ++b) {
      const int off = layout.offsets[b], size = layout.blocks[b].size;
      bool any = false;
      for (int k = off; k < off + size; ++k) any = any || next[static_cast<size_t>(k)];
      for (int k = off; k < off + size; ++k) next[static_cast<size_t>(k)] = any;
    }
    tainted = std::move(next);
  }
  return tainted;
}

}  // namespace

AttributeEvaluator::AttributeEvaluator(const Camera& camera) : compiled_(camera) {
  const BlockLayout& layout = camera.layout();
  const int p = layout.find(BlockKind::Position);
  if (p < 0 || layout.blocks[p].size != 3)
    throw std::invalid_argument("attributed rendering needs a camera with a 2D image position block");
  position_ = layout.offsets[p];
  if (const int c = layout.find(BlockKind::Colour); c >= 0) colour_ = layout.offsets[c];
  if (const int d = layout.find(BlockKind::Depth); d >= 0) depth_ = layout.offsets[d];
  if (const int b = layout.find(BlockKind::SecondColour); b >= 0) second_ = layout.offsets[b];
  if (const int s = layout.find(BlockKind::Shading); s >= 0) shading_ = layout.offsets[s];
  if (depth_ >= 0) {
    const std::vector<bool> from_depth = taintedOutputs(camera, {depth_, depth_ + 1});
    if (colour_ >= 0) colour_reads_depth_ = from_depth[static_cast<size_t>(colour_)];
    geometry_reads_depth_ = taintedOutputs(camera, {depth_})[static_cast<size_t>(position_)];
  }
  if (colour_ >= 0)
    for (int k = 0; k < 4; ++k)
      geometry_reads_colour_[k] = taintedOutputs(camera, {colour_ + k})[static_cast<size_t>(position_)];
}

void AttributeEvaluator::evaluate(double u_n, double v_n, const float* rgba, double depth,
                                  Output& out, const float* second) const {
  CompiledCamera::Vector x{}, z{};
  x[position_] = u_n;
  x[position_ + 1] = v_n;
  x[position_ + 2] = 1.0;
  if (colour_ >= 0)
    for (int k = 0; k < 4; ++k) x[colour_ + k] = rgba[k];
  if (depth_ >= 0) {
    x[depth_] = depth;
    x[depth_ + 1] = 1.0;
  }
  if (second_ >= 0 && second)
    for (int k = 0; k < 4; ++k) x[second_ + k] = second[k];
  if (shading_ >= 0) x[shading_ + 1] = 1.0;  // (0, 1): computed by the camera (camera.h)
  compiled_.evaluateHomogeneous(x, z);  // eq 3 (through every stage)

  // eq 5, block by block.
  const double w = z[position_ + 2];
  out.position_weight = w;
  out.position[0] = z[position_] / w;
  out.position[1] = z[position_ + 1] / w;
  out.position_valid = w != 0.0 && std::isfinite(out.position[0]) && std::isfinite(out.position[1]);

  out.attributes_valid = true;
  if (colour_ >= 0) {
    const double a = z[colour_ + 3];
    // The colour's homogeneous weight is the output alpha (eq 5); rgb = z_c / z_a is
    // premultiplied again by the clamped alpha.
    const double alpha = std::min(a, 1.0);
    bool ok = a > 0.0 && std::isfinite(a);
    for (int k = 0; k < 3 && ok; ++k) {
      const double c = z[colour_ + k] / a * alpha;
      ok = std::isfinite(c);
      out.rgba[k] = static_cast<float>(c);
    }
    out.rgba[3] = static_cast<float>(alpha);
    if (!ok) std::fill(out.rgba, out.rgba + 4, 0.0f);
    out.attributes_valid = ok;
  } else {
    std::copy(rgba, rgba + 4, out.rgba);
  }
  if (depth_ >= 0) {
    const double d = z[depth_] / z[depth_ + 1];
    out.depth = std::isfinite(d) ? static_cast<float>(d) : 0.0f;
  }
}

DepthSample sampleDepthCoverage(const ImageF& depth, FrameSize source_px, double sx, double sy) {
  // The depth image may have another size than the source: read it at the same place.
  const double fx = sx * depth.width / source_px.width - 0.5;
  const double fy = sy * depth.height / source_px.height - 0.5;
  if (!std::isfinite(fx) || !std::isfinite(fy)) return {0.0, 0.0};
  const double x0 = std::floor(fx), y0 = std::floor(fy);
  const double tx = fx - x0, ty = fy - y0;
  double value = 0.0, weight = 0.0, inside = 0.0;
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i) {
      const double xi = x0 + i, yj = y0 + j;
      if (xi < 0 || yj < 0 || xi >= depth.width || yj >= depth.height) continue;
      const double w = (i ? tx : 1 - tx) * (j ? ty : 1 - ty);
      const float* p = depth.pixel(static_cast<int>(xi), static_cast<int>(yj));
      // 2 channels: (coverage·d, coverage), the homogeneous depth block (depth_raster.h);
      // 1 channel: a depth, or a hole (0, negative, non-finite: depth_file.h's "no depth").
      double cover = 1.0, covered_depth = p[0];
      if (depth.channels >= 2) {
        cover = std::isfinite(p[1]) && std::isfinite(p[0]) ? std::clamp<double>(p[1], 0.0, 1.0)
                                                           : 0.0;
        covered_depth = cover > 0.0 ? p[0] : 0.0;
      } else if (!(p[0] > 0.0f) || !std::isfinite(p[0])) {
        cover = 0.0;
        covered_depth = 0.0;
      }
      value += w * covered_depth;
      weight += w * cover;
      inside += w;
    }
  if (!(weight > 1e-12)) return {0.0, 0.0};
  return {value / weight, std::min(1.0, weight / inside)};
}

double sampleDepth(const ImageF& depth, FrameSize source_px, double sx, double sy) {
  return sampleDepthCoverage(depth, source_px, sx, sy).depth;
}

ImageF rgbaFromImage(const ImageF& source) {
  checkSourceImage(source);
  ImageF out(source.width, source.height, 4, 3);
  const size_t n = static_cast<size_t>(source.width) * static_cast<size_t>(source.height);
  const int c = source.channels;
  const int colour_channels = source.alpha_channel >= 0 ? c - 1 : c;
  for (size_t i = 0; i < n; ++i) {
    const float* in = source.data.data() + i * static_cast<size_t>(c);
    float* o = out.data.data() + i * 4;
    float colour[3];
    int k = 0;
    for (int ch = 0; ch < c && k < 3; ++ch)
      if (ch != source.alpha_channel) colour[k++] = in[ch];
    if (colour_channels == 1) colour[1] = colour[2] = colour[0];
    else if (colour_channels == 2) colour[2] = 0.0f;
    o[0] = colour[0];
    o[1] = colour[1];
    o[2] = colour[2];
    o[3] = source.alpha_channel >= 0 ? in[source.alpha_channel] : 1.0f;
  }
  return out;
}

Camera positionPart(const Camera& camera) {
  const BlockLayout& layout = camera.layout();
  const int p = layout.find(BlockKind::Position);
  if (p < 0) throw std::invalid_argument("the camera has no position block");
  const int off = layout.offsets[p], k = layout.blocks[p].size;
  std::vector<Stage> stages;
  for (const Stage& stage : camera.stages()) {
    Stage s;
    for (int i = off; i < off + k; ++i) s.q.push_back(stage.q[i].block(off, off, k, k));
    stages.push_back(std::move(s));
  }
  return Camera({layout.blocks[p]}, std::move(stages), camera.sourceSize(), camera.targetSize());
}

AttributedPath chooseAttributedPath(const Camera& camera, const CameraStructure& structure,
                                    FrameSize source_px, FrameSize out_px) {
  (void)camera;
  if (structure.geometry_depends_on_attributes) return AttributedPath::Splat;
  if (!structure.attributes_change) return AttributedPath::Geometry;
  if (structure.geometry == GeometryClass::Identity && source_px == out_px)
    return AttributedPath::ColourOnly;
  return AttributedPath::Gather;
}

namespace {

// The depth-coverage rule (depth_coverage.h) where the camera is evaluated: `untouched` is the
// sampled colour the camera was given. A colour that reads depth fades with the coverage here;
// the coverage itself goes to `coverage_out` (when asked) for the effects applied after the
// render (the depth-of-field blur), and a pixel without depth has depth output 0, "none".
void keepWithoutDepth(const AttributeEvaluator& eval, double coverage, const float* untouched,
                      float* colour, float* depth, float* coverage_out) {
  if (!eval.readsDepth()) return;
  const auto c = static_cast<float>(std::clamp(coverage, 0.0, 1.0));
  if (coverage_out) *coverage_out = c;
  if (depth && !(c > 0.0f)) *depth = 0.0f;
  if (eval.colourReadsDepth()) fadeByDepthCoverage(c, untouched, colour);
}

void writeOutput(const AttributeEvaluator::Output& o, float* colour, float* depth) {
  if (!o.attributes_valid || !(o.rgba[3] > 0.0f)) {
    std::fill(colour, colour + 4, 0.0f);
    if (depth) *depth = 0.0f;
    return;
  }
  std::copy(o.rgba, o.rgba + 4, colour);
  if (depth) *depth = o.depth;
}

long long countTransparent(const ImageF& rgba) {
  long long n = 0;
  for (size_t i = 3; i < rgba.data.size(); i += 4) n += !(rgba.data[i] > 0.0f);
  return n;
}

ParallelOptions parallelOptions(const AttributedOptions& options) {
  ParallelOptions po;
  po.threads = options.warp.threads;
  po.progress = options.warp.progress;
  return po;
}

// The second image read at source pixel point (sx, sy) of a source of `source_px`: scaled to its
// own size, bilinear (exact texels at the pixel centres of a second image of the source's size),
// clamped to its outer texel centres so a stretched second image covers the whole frame instead
// of fading in its outer half texel.
class SecondReader {
 public:
  SecondReader(const ImageF* second_rgba, FrameSize source_px)
      : sampler_(second_rgba ? std::optional<Sampler>(std::in_place, *second_rgba, Filter::Bilinear)
                             : std::nullopt),
        sx_(second_rgba ? static_cast<double>(second_rgba->width) / source_px.width : 1.0),
        sy_(second_rgba ? static_cast<double>(second_rgba->height) / source_px.height : 1.0),
        width_(second_rgba ? second_rgba->width : 1),
        height_(second_rgba ? second_rgba->height : 1) {}
  // Null when there is no second image; else `out` (4 floats) filled.
  const float* read(double sx, double sy, float* out) const {
    if (!sampler_) return nullptr;
    sampler_->sample(std::clamp(sx * sx_, 0.5, width_ - 0.5),
                     std::clamp(sy * sy_, 0.5, height_ - 0.5), out);
    return out;
  }

 private:
  std::optional<Sampler> sampler_;
  double sx_, sy_, width_, height_;
};

// Geometry identity, same size: each pixel's own colour and depth through the camera.
// `encoding` (may be null): `rgba` is in its stored domain, each row decoded as it is read.
bool colourOnly(const ImageF& rgba, const StoredEncoding* encoding, const ImageF* depth,
                const SecondReader& second, const AttributeEvaluator& eval,
                const AttributedOptions& options, AttributedImage& out) {
  const FrameSize px{rgba.width, rgba.height};
  return parallelForRows(rgba.height, parallelOptions(options), [&](int y0, int y1) {
    AttributeEvaluator::Output o;
    float b[4];
    std::vector<float> decoded;
    for (int y = y0; y < y1; ++y) {
      const float* row = rgba.pixel(0, y);
      if (encoding) {
        decoded.assign(row, row + 4 * static_cast<size_t>(rgba.width));
        encoding->decode(decoded.data(), static_cast<size_t>(rgba.width), 4, 3);
        row = decoded.data();
      }
      for (int x = 0; x < rgba.width; ++x) {
        const float* in = row + 4 * static_cast<size_t>(x);
        const Eigen::Vector2d n = normalizedFromPixel(px, {x + 0.5, y + 0.5});
        const DepthSample d =
            depth ? sampleDepthCoverage(*depth, px, x + 0.5, y + 0.5) : DepthSample{};
        eval.evaluate(n.x(), n.y(), in, d.depth, o, second.read(x + 0.5, y + 0.5, b));
        float* d_out = out.depth.empty() ? nullptr : out.depth.pixel(x, y);
        writeOutput(o, out.colour.pixel(x, y), d_out);
        keepWithoutDepth(eval, d.coverage, in, out.colour.pixel(x, y), d_out,
                         out.depth_coverage.empty() ? nullptr : out.depth_coverage.pixel(x, y));
      }
    }
  });
}

// Positions from position alone: the gather kernels find the source point, the camera then
// maps [source point | sampled colour | sampled depth].
// `camera_structure` is the whole camera's: its geometry (class, homography) is the position
// part's, since the position forms read position alone on this path.
// `rgba` is in the stored domain of `encoding` (null: linear), each sample decoded before use.
bool gather(const ImageF& rgba, const StoredEncoding* encoding, const ImageF* depth,
            const SecondReader& second, const Camera& camera,
            const CameraStructure& camera_structure, const AttributeEvaluator& eval,
            const AttributedOptions& options, AttributedImage& out, AttributedSummary& report) {
  const Camera geometry = positionPart(camera);
  const CameraStructure& structure = camera_structure;
  // The position part's own denominator (analyseStructure's rule, on the part alone): zero in
  // every entry of some stage is a camera that maps nothing.
  bool degenerate = structure.degenerate;
  const int p = geometry.layout().find(BlockKind::Position);
  if (p >= 0) {
    const size_t den = static_cast<size_t>(geometry.layout().offsets[p] + geometry.blocks()[p].size - 1);
    for (const Stage& stage : geometry.stages())
      degenerate = degenerate || stage.q[den].cwiseAbs().maxCoeff() == 0.0;
  }
  const FrameSize source_px{rgba.width, rgba.height};
  const FrameSize out_px{out.colour.width, out.colour.height};
  if (degenerate) {
    report.kernel = "degenerate";
    report.note = "the camera's position denominator is zero everywhere";
    return true;  // the output is already transparent
  }
  const KernelChoice choice = makeCoordinateKernel(geometry, structure, source_px, out_px,
                                                   options.warp.coordinates, options.warp.threads);
  report.kernel = choice.name;
  report.note = choice.note;
  const Sampler sampler(rgba, options.warp.filter, options.warp.edge);
  ParallelOptions po = parallelOptions(options);
  po.band_rows = 16;
  return parallelForRows(out_px.height, po, [&](int y0, int y1) {
    float sx[kSpanPixels], sy[kSpanPixels];
    unsigned char valid[kSpanPixels];
    float samples[kSpanPixels][4];
    AttributeEvaluator::Output o;
    float b[4];
    for (int y = y0; y < y1; ++y) {
      RowState state;
      for (int x0 = 0; x0 < out_px.width; x0 += kSpanPixels) {
        const int n = std::min(kSpanPixels, out_px.width - x0);
        choice.kernel->span(y, x0, n, sx, sy, valid, state);
        // The span's samples, read in the stored domain and decoded together (the one
        // resampling rule, core/colour/stored_encoding.h).
        for (int i = 0; i < n; ++i)
          if (valid[i]) sampler.sample(sx[i], sy[i], samples[i]);
          else std::fill(samples[i], samples[i] + 4, 0.0f);
        if (encoding) encoding->decode(samples[0], static_cast<size_t>(n), 4, 3);
        for (int i = 0; i < n; ++i) {
          float* colour = out.colour.pixel(x0 + i, y);
          float* d_out = out.depth.empty() ? nullptr : out.depth.pixel(x0 + i, y);
          if (!valid[i]) continue;  // stays transparent
          const float* sample = samples[i];
          // A transparent photo pixel has nothing to change, unless a second image is
          // composited with it (B over nothing is B).
          if (!(sample[3] > 0.0f) && !eval.readsSecond()) continue;
          const Eigen::Vector2d s = normalizedFromPixel(source_px, {sx[i], sy[i]});
          const DepthSample d =
              depth ? sampleDepthCoverage(*depth, source_px, sx[i], sy[i]) : DepthSample{};
          eval.evaluate(s.x(), s.y(), sample, d.depth, o, second.read(sx[i], sy[i], b));
          writeOutput(o, colour, d_out);
          keepWithoutDepth(eval, d.coverage, sample, colour, d_out,
                           out.depth_coverage.empty() ? nullptr
                                                      : out.depth_coverage.pixel(x0 + i, y));
        }
      }
    }
  });
}

}  // namespace

AttributedImage renderAttributed(const AttributedSources& sources, const Camera& camera,
                                 const AttributedOptions& options, AttributedSummary* summary) {
  const CameraStructure structure = validatedStructure(camera);
  return renderAttributed(sources, AnalysedCamera{camera, structure}, options, summary);
}

namespace {

// The source as the paths read it, made once for all the layers of a layered render: RGBA, in
// the stored domain when the sources carry an encoding (the one resampling rule), which the
// colour-only path then decodes pixel by pixel; so one copy serves every layer.
struct PreparedColour {
  ImageF rgba;
};

AttributedImage renderPrepared(const AttributedSources& sources, const AnalysedCamera& analysed,
                               const AttributedOptions& options, AttributedSummary* summary,
                               PreparedColour* prepared);

}  // namespace

AttributedImage renderAttributed(const AttributedSources& sources, const AnalysedCamera& analysed,
                                 const AttributedOptions& options, AttributedSummary* summary) {
  return renderPrepared(sources, analysed, options, summary, nullptr);
}

namespace {

AttributedImage renderPrepared(const AttributedSources& sources, const AnalysedCamera& analysed,
                               const AttributedOptions& options, AttributedSummary* summary,
                               PreparedColour* prepared) {
  const Camera& camera = analysed.camera;
  const CameraStructure& structure = analysed.structure;
  const ImageF& source = sources.colour;
  const ImageF* depth = sources.depth;
  const auto start = std::chrono::steady_clock::now();
  AttributedSummary local;
  AttributedSummary& report = summary ? *summary : local;
  report = AttributedSummary{};
  camera.validate();
  checkSourceImage(source);
  const FrameSize out_px = outputSizeFor(camera, options.warp.width, options.warp.height);
  const FrameSize source_px{source.width, source.height};
  AttributedPath path = chooseAttributedPath(camera, structure, source_px, out_px);
  if (!options.force_path.empty()) {
    if (options.force_path == "splat") path = AttributedPath::Splat;
    else if (options.force_path == "gather" && !structure.geometry_depends_on_attributes)
      path = AttributedPath::Gather;
    else
      throw std::invalid_argument("cannot force path \"" + options.force_path + "\" here");
  }
  report.path = path;
  const AttributeEvaluator eval(camera);
  if (eval.readsDepth() && path != AttributedPath::Geometry) {
    if (!depth || depth->empty())
      throw std::invalid_argument("this camera reads depth (it has a depth block): give a depth "
                                  "image (artcam warp --depth FILE)");
    if (depth->channels > 2) throw std::invalid_argument("the depth image must have 1 or 2 channels");
  }
  ImageF second_rgba;
  if (eval.readsSecond() && path != AttributedPath::Geometry) {
    if (!sources.second || sources.second->empty())
      throw std::invalid_argument("this camera composites a second image (it has a second-colour "
                                  "block): give one (artcam warp --second FILE)");
    if (path == AttributedPath::Splat)
      throw std::invalid_argument("a camera that composites a second image cannot also move "
                                  "pixels by their colour or depth (the splat path)");
    second_rgba = rgbaFromImage(*sources.second);
  }
  const SecondReader second(second_rgba.empty() ? nullptr : &second_rgba, source_px);
  // The paths that resample the photo read it in its stored domain (the one resampling rule);
  // the colour-only path keeps every pixel in place and the splat reads pixels at their centres,
  // so both read the linear values directly.
  const StoredEncoding* encoding =
      sources.encoding && !sources.encoding->isLinear() &&
              (path == AttributedPath::Geometry || path == AttributedPath::Gather)
          ? sources.encoding
          : nullptr;
  const auto encode = [encoding](ImageF& image) {
    encoding->encode(image.data.data(), image.data.size() / 4, 4, 3);
  };
  // With a layered render's prepared copy (stored domain where there is an encoding), the
  // colour-only path decodes it as it reads (`stored_colour_only`), the splat gets a decoded copy.
  ImageF owned;
  const ImageF* source_rgba = &owned;
  const StoredEncoding* stored_colour_only = nullptr;
  if (!prepared) {
    owned = rgbaFromImage(source);
    if (encoding) encode(owned);
  } else {
    const StoredEncoding* any =
        sources.encoding && !sources.encoding->isLinear() ? sources.encoding : nullptr;
    if (prepared->rgba.empty()) {
      prepared->rgba = rgbaFromImage(source);
      if (any) any->encode(prepared->rgba.data.data(), prepared->rgba.data.size() / 4, 4, 3);
    }
    source_rgba = &prepared->rgba;
    if (any && path == AttributedPath::ColourOnly) stored_colour_only = any;
    if (any && path == AttributedPath::Splat) {
      owned = prepared->rgba;
      any->decode(owned.data.data(), owned.data.size() / 4, 4, 3);
      source_rgba = &owned;
    }
  }
  const ImageF& rgba = *source_rgba;

  AttributedImage out;
  bool finished = true;
  if (path == AttributedPath::Geometry) {
    WarpOptions wo = options.warp;
    wo.width = out_px.width;
    wo.height = out_px.height;
    WarpSummary ws;
    out.colour = warpImage(rgba, analysed, wo, &ws);
    if (encoding && !ws.cancelled)
      encoding->decode(out.colour.data.data(), out.colour.data.size() / 4, 4, 3);
    report.kernel = ws.kernel;
    report.note = ws.note;
    finished = !ws.cancelled;
  } else if (path == AttributedPath::Splat) {
    SplatOptions so;
    so.supersample = options.splat_supersample;
    so.threads = options.warp.threads;
    so.progress = options.warp.progress;
    SplatSummary ss;
    out = splatImage(rgba, depth, camera, out_px, so, &ss);
    report.kernel = "splat";
    if (ss.dropped_triangles > 0)
      report.note = std::to_string(ss.dropped_triangles) + " triangles dropped (pole or invalid)";
    finished = !ss.cancelled;
  } else {
    out.colour = ImageF(out_px.width, out_px.height, 4, 3);
    if (eval.readsDepth()) out.depth = ImageF(out_px.width, out_px.height, 1);
    if (eval.readsDepth() && options.depth_coverage)
      out.depth_coverage = ImageF(out_px.width, out_px.height, 1);
    if (path == AttributedPath::ColourOnly) {
      report.kernel = "colour-only";
      finished = colourOnly(rgba, stored_colour_only, depth, second, eval, options, out);
    } else {
      finished = gather(rgba, encoding, depth, second, camera, structure, eval, options, out, report);
    }
  }
  report.render_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  if (!finished) {
    report.cancelled = true;
    return {};
  }
  report.transparent_pixels = countTransparent(out.colour);
  return out;
}

}  // namespace

AttributedImage renderLayers(const AttributedSources& sources, const std::vector<Camera>& layers,
                             const AttributedOptions& options, AttributedSummary* summary) {
  const AnalysedCameras analysed(layers);
  return renderLayers(sources, analysed.cameras(), options, summary);
}

AttributedImage renderLayers(const AttributedSources& sources, const std::vector<AnalysedCamera>& layers,
                             const AttributedOptions& options, AttributedSummary* summary) {
  if (layers.empty()) throw std::invalid_argument("a layered camera needs at least one layer");
  AttributedSummary local;
  AttributedSummary& report = summary ? *summary : local;
  AttributedImage total;
  double ms = 0.0;
  std::string kernels;
  // While the layers arrive, total.colour holds the sum of the layers' UNpremultiplied colours
  // in channels 0..2 and the smallest coverage so far in channel 3; best_alpha the largest, for
  // the depth. A layer's premultiplied colour s with coverage a adds s/a (nothing where a = 0,
  // which makes the smallest coverage 0 anyway).
  std::vector<float> best_alpha;
  PreparedColour prepared;  // the source converted once for every layer
  auto add = [](float* t, const float* s, bool first) {
    const float a = s[3];
    for (int k = 0; k < 3; ++k) {
      const float u = a > 0.0f ? s[k] / a : 0.0f;
      t[k] = first ? u : t[k] + u;
    }
    t[3] = first ? a : std::min(t[3], a);
  };
  for (size_t l = 0; l < layers.size(); ++l) {
    AttributedOptions lo = options;
    if (options.warp.progress) {
      const double n = static_cast<double>(layers.size());
      lo.warp.progress = [&, l, n](double f) {
        return options.warp.progress((static_cast<double>(l) + f) / n);
      };
    }
    AttributedImage layer = renderPrepared(sources, layers[l], lo, &report, &prepared);
    if (report.cancelled) return {};
    ms += report.render_ms;
    kernels += (l ? "+" : "") + report.kernel;
    if (l == 0) {
      total = std::move(layer);
      const size_t n = static_cast<size_t>(total.colour.width) * static_cast<size_t>(total.colour.height);
      best_alpha.resize(n);
      for (size_t i = 0; i < n; ++i) {
        float* t = total.colour.data.data() + 4 * i;
        best_alpha[i] = t[3];
        add(t, t, true);
      }
      continue;
    }
    if (layer.colour.width != total.colour.width || layer.colour.height != total.colour.height)
      throw std::invalid_argument("layer " + std::to_string(l) + " renders to another size");
    const size_t n = static_cast<size_t>(total.colour.width) * static_cast<size_t>(total.colour.height);
    for (size_t i = 0; i < n; ++i) {
      float* t = total.colour.data.data() + 4 * i;
      const float* s = layer.colour.data.data() + 4 * i;
      add(t, s, false);
      if (s[3] > best_alpha[i]) {
        best_alpha[i] = s[3];
        if (!total.depth.empty() && !layer.depth.empty()) total.depth.data[i] = layer.depth.data[i];
        // The coverage the depth was read with goes with it (the blur fades by it).
        if (!total.depth_coverage.empty() && !layer.depth_coverage.empty())
          total.depth_coverage.data[i] = layer.depth_coverage.data[i];
      }
    }
  }
  // Back to premultiplied at the smallest coverage.
  for (size_t i = 0; i < best_alpha.size(); ++i) {
    float* t = total.colour.data.data() + 4 * i;
    for (int k = 0; k < 3; ++k) t[k] *= t[3];
  }
  report.kernel = kernels;
  report.render_ms = ms;
  report.transparent_pixels = countTransparent(total.colour);
  return total;
}

}  // namespace artcam
