// SPDX-License-Identifier: Apache-2.0
#include "core/pipeline/render.h"

#include "core/effects/depth_of_field.h"
#include "core/model/structure.h"
#include "core/piecewise/piecewise_render.h"
#include "core/render/attributed.h"
#include "core/render/depth_coverage.h"
#include "core/render/preview.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <stdexcept>

namespace artcam {

std::string secondImageSizeNote(FrameSize second, FrameSize photo) {
  if (second == photo) return {};
  return "the second image is " + std::to_string(second.width) + "x" +
         std::to_string(second.height) + ", not the photo's " + std::to_string(photo.width) + "x" +
         std::to_string(photo.height) + ": it is stretched to the photo's frame";
}

RenderInputs RenderInputs::of(const ImageF& linear_photo, const ImageF* depth,
                              const StoredEncoding* encoding) {
  RenderInputs inputs;
  inputs.photo = viewOf(linear_photo);
  inputs.linear = &linear_photo;
  inputs.depth = depth;
  inputs.encoding = encoding;
  return inputs;
}

std::string_view renderPathName(RenderPath path) {
  switch (path) {
    case RenderPath::Geometry: return "gather warp";
    case RenderPath::Preview: return "preview warp";
    case RenderPath::ColourOnly: return "colour only";
    case RenderPath::Gather: return "attributed gather";
    case RenderPath::Splat: return "splat";
    case RenderPath::Layered: return "layered";
    case RenderPath::Piecewise: return "piecewise mesh warp";
  }
  return "gather warp";
}

std::string RenderSummary::describe() const {
  std::string text(renderPathName(path));
  if (!kernel.empty()) text += " (" + kernel + ")";
  if (blurred) text += " + depth-of-field blur";
  text += ", " + std::to_string(transparent_pixels) + " transparent pixels";
  return text;
}

OutputFrame outputFrameFor(const Artcam& camera, FrameSize photo, int width, int height) {
  OutputFrame frame;
  const FrameSize source = camera.sourceSize();
  const FrameSize target = camera.targetSize();
  if (width < 0 || height < 0) throw std::invalid_argument("output size must not be negative");
  if (width > 0 || height > 0 || !source.isImage() || !photo.isImage()) {
    frame.size = outputSizeFor(camera.main(), width, height);
    return frame;
  }
  const double sx = static_cast<double>(photo.width) / source.width;
  const double sy = static_cast<double>(photo.height) / source.height;
  frame.size = {std::max(1, static_cast<int>(std::lround(target.width * sx))),
                std::max(1, static_cast<int>(std::lround(target.height * sy)))};
  // The photo's height if it had the source frame's aspect: more than a rounding pixel away
  // means the camera was made for a photo of another shape.
  const double expected_height = source.height * sx;
  if (std::abs(photo.height - expected_height) > 1.0)
    frame.warning = "the photo is " + std::to_string(photo.width) + "x" +
                    std::to_string(photo.height) + " but the camera was made for " +
                    std::to_string(source.width) + "x" + std::to_string(source.height) +
                    " (another aspect): the result is stretched per axis";
  return frame;
}

namespace {

// What a render needs to know of its camera, found once per render (docs/architecture.md).
struct Analysis {
  bool linear = false;       // renders from the linear float photo
  bool attributes = false;   // some layer changes or reads colour/depth
  // Each layer's structure (analyseStructure), in layer order: validateArtcam's.
  std::vector<CameraStructure> layers;
  // Layers that each pass one colour channel through a position camera (chromatic
  // aberration, Fig 4): those cameras in channel order, rendered by warpChannels, and theirs.
  std::vector<Camera> channels;
  std::vector<CameraStructure> channel_structures;

  std::vector<AnalysedCamera> analysedLayers(const Artcam& camera) const {
    std::vector<AnalysedCamera> out;
    for (size_t l = 0; l < camera.layers.size(); ++l) out.push_back({camera.layers[l], layers[l]});
    return out;
  }
  std::vector<AnalysedCamera> analysedChannels() const {
    std::vector<AnalysedCamera> out;
    for (size_t k = 0; k < channels.size(); ++k) out.push_back({channels[k], channel_structures[k]});
    return out;
  }
};

// A layer [position 3 | colour 4] whose position forms read position alone and whose colour
// outputs pass channel k and alpha unchanged (z_k = c_k w, z_A = c_A w, the rest 0): channel
// k, else −1. Exact comparisons: a camera edited into anything else takes the general path.
int passedChannel(const Camera& layer) {
  const std::vector<Block>& blocks = layer.blocks();
  if (blocks.size() != 2 || blocks[0].kind != BlockKind::Position || blocks[0].size != 3 ||
      blocks[1].kind != BlockKind::Colour || blocks[1].size != 4 || layer.stages().size() != 1)
    return -1;
  constexpr int kW = 2, kR = 3, kA = 6, kN = 7;
  const Stage& st = layer.stages()[0];
  if (static_cast<int>(st.q.size()) != kN) return -1;
  for (int i = 0; i < 3; ++i) {
    Eigen::MatrixXd rest = st.q[static_cast<size_t>(i)];
    rest.topLeftCorner(3, 3).setZero();
    if (!rest.isZero(0.0)) return -1;
  }
  const auto unit = [](int i) { return Eigen::VectorXd::Unit(kN, i); };
  if (st.q[kA] != symmetricOuter(unit(kA), unit(kW))) return -1;
  int channel = -1;
  for (int k = 0; k < 3; ++k) {
    const Eigen::MatrixXd& q = st.q[static_cast<size_t>(kR + k)];
    if (q.isZero(0.0)) continue;
    if (channel >= 0 || q != symmetricOuter(unit(kR + k), unit(kW))) return -1;
    channel = k;
  }
  return channel;
}

}  // namespace

std::vector<Camera> channelCameras(const Artcam& camera) {
  if (camera.layers.size() != 3 || camera.pieces || camera.depth_output != DepthOutput::Depth) return {};
  std::vector<Camera> cameras(3);
  bool seen[3] = {false, false, false};
  for (const Camera& layer : camera.layers) {
    const int k = passedChannel(layer);
    if (k < 0 || seen[k]) return {};
    seen[k] = true;
    const Stage& st = layer.stages()[0];
    std::vector<Eigen::Matrix3d> q;
    for (int i = 0; i < 3; ++i) q.emplace_back(st.q[static_cast<size_t>(i)].topLeftCorner(3, 3));
    cameras[static_cast<size_t>(k)] = Camera::rtcam(q, layer.sourceSize(), layer.targetSize());
  }
  return cameras;
}

namespace {

// `layers`: each layer's structure when the caller has it (validateArtcam's), else found here.
Analysis analyse(const Artcam& camera, std::vector<CameraStructure> layers = {}) {
  Analysis a;
  if (layers.size() != camera.layers.size()) {
    layers.clear();
    for (const Camera& layer : camera.layers) layers.push_back(analyseStructure(layer));
  }
  a.layers = std::move(layers);
  a.channels = channelCameras(camera);
  if (!a.channels.empty()) {  // the stored photo, per channel
    for (const Camera& channel : a.channels) a.channel_structures.push_back(analyseStructure(channel));
    return a;
  }
  for (const CameraStructure& s : a.layers)
    a.attributes = a.attributes || s.attributes_change || s.geometry_depends_on_attributes;
  // Patches render from the stored photo like one camera (the mesh feeds the warp's sampler);
  // with layers, attributes or depth of field they are refused by validateArtcam anyway.
  a.linear = camera.layers.size() > 1 || a.attributes || camera.depth_output != DepthOutput::Depth;
  return a;
}

RenderPath attributedPath(AttributedPath path) {
  switch (path) {
    case AttributedPath::ColourOnly: return RenderPath::ColourOnly;
    case AttributedPath::Gather: return RenderPath::Gather;
    case AttributedPath::Splat: return RenderPath::Splat;
    case AttributedPath::Geometry: return RenderPath::Geometry;
  }
  return RenderPath::Geometry;
}

long long countTransparent(const ImageF& image) {
  if (image.alpha_channel < 0) return 0;
  long long n = 0;
  for (size_t i = static_cast<size_t>(image.alpha_channel); i < image.data.size();
       i += static_cast<size_t>(image.channels))
    n += !(image.data[i] > 0.0f);
  return n;
}

double msSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

// Layers (or one attributed camera), then the depth-of-field blur when the depth output is the
// blur variance σ² (effects/depth_of_field.h).
ImageF renderAttributedCamera(const RenderInputs& inputs, const Artcam& camera, const Analysis& analysis,
                              const RenderOptions& options, FrameSize size, RenderSummary& report,
                              ImageF* depth_out) {
  AttributedOptions a;
  a.warp = options.warp;
  a.warp.width = size.width;
  a.warp.height = size.height;
  a.splat_supersample = options.splat_supersample;
  a.force_path = options.force_path;
  // The blur fades with the depth's coverage after the stack (depth_coverage.h).
  a.depth_coverage = camera.depth_output == DepthOutput::BlurVariance;
  AttributedSummary as;
  const AttributedSources sources{*inputs.linear, inputs.depth, inputs.second, inputs.encoding};
  AttributedImage out = camera.layers.size() > 1
                            ? renderLayers(sources, analysis.analysedLayers(camera), a, &as)
                            : renderAttributed(sources, AnalysedCamera{camera.main(), analysis.layers[0]}, a, &as);
  report.path = camera.layers.size() > 1 ? RenderPath::Layered : attributedPath(as.path);
  report.kernel = as.kernel;
  report.note = as.note;
  if (as.cancelled) {
    report.cancelled = true;
    return {};
  }
  if (camera.depth_output == DepthOutput::BlurVariance) {
    if (out.depth.empty())
      throw std::invalid_argument("a blur-variance camera needs a depth output");
    BlurOptions blur;
    blur.threads = options.warp.threads;
    blur.progress = options.warp.progress;
    ImageF blurred = stackBlur(out.colour, sigmaPixelsFromVariance(out.depth), blur);
    if (blurred.empty()) {
      report.cancelled = true;
      return {};
    }
    // The depth-coverage rule, as the haze follows it (depth_coverage.h): a soft painted edge
    // fades the blur in, c·blurred + (1 − c)·sharp, instead of cutting it at the last pixel the
    // mask touches. The splat path hands back no coverage: its blur is not faded.
    if (!out.depth_coverage.empty())
      fadeByDepthCoverage(out.depth_coverage, out.colour, blurred, blur.threads);
    out.colour = std::move(blurred);
    report.blurred = true;
  }
  if (depth_out) *depth_out = std::move(out.depth);
  return std::move(out.colour);
}

// The mesh warp's options from the render's: one place, so the float and the stored-photo
// paths cannot drift apart (the float path once ignored the thread count).
PiecewiseRenderOptions piecewiseOptions(const RenderOptions& options) {
  PiecewiseRenderOptions p;
  p.mesh_step_px = options.mesh_step_px;
  p.filter = options.warp.filter;
  p.edge = options.warp.edge;
  p.threads = options.warp.threads;
  p.allow_simd = !options.warp.coordinates.scalar_only;
  p.allow_avx512 = options.warp.coordinates.allow_avx512;
  return p;
}

ImageF renderPieces(const RenderInputs& inputs, const Artcam& camera, const RenderOptions& options,
                    FrameSize size, RenderSummary& report) {
  PiecewiseRenderOptions p = piecewiseOptions(options);
  p.output = size;
  report.path = RenderPath::Piecewise;
  report.kernel = std::to_string(camera.pieces->patches.size()) + " patches";
  ImageF out = renderPiecewise(*inputs.linear, *camera.pieces, p);
  // The mesh warp has no cancel points; honour a cancel asked for meanwhile.
  if (options.warp.progress && !options.warp.progress(1.0)) {
    report.cancelled = true;
    return {};
  }
  return out;
}

void requireLinear(const RenderInputs& inputs) {
  if (!inputs.linear || inputs.linear->empty())
    throw std::invalid_argument(
        "this camera (layers, colour or depth blocks, depth of field or patches) renders from the "
        "linear float photo, which was not given");
}

// Copies a float image into a float view of the same shape.
void copyInto(const ImageF& image, const ImageView& out) {
  if (out.type != PixelType::Float || out.width != image.width || out.height != image.height ||
      out.channels != image.channels)
    throw std::invalid_argument("render: the output view does not have the rendered shape (" +
                                std::to_string(image.width) + "x" + std::to_string(image.height) +
                                ", " + std::to_string(image.channels) + " float channels)");
  const size_t row = static_cast<size_t>(image.width) * static_cast<size_t>(image.channels);
  for (int y = 0; y < image.height; ++y)
    std::memcpy(out.row(y), image.data.data() + row * static_cast<size_t>(y), row * sizeof(float));
}

// The geometry kernels on the photo as stored (or the preview's mip level), into `out`.
void renderGeometry(const ConstImageView& photo, const StoredMipPyramid* pyramid,
                    const Artcam& camera, const Analysis& analysis, const RenderOptions& options,
                    const ImageView& out, RenderSummary& report) {
  WarpOptions warp = options.warp;
  warp.width = out.width;
  warp.height = out.height;
  WarpSummary ws;
  if (camera.pieces) {
    const PiecewiseRenderOptions p = piecewiseOptions(options);
    report.path = RenderPath::Piecewise;
    report.kernel = std::to_string(camera.pieces->patches.size()) + " patches";
    // A preview reads the pyramid level of about the output's scale.
    const ConstImageView& from = pyramid ? pyramid->level(pyramid->levelFor(static_cast<double>(pyramid->level(0).width) / out.width)) : photo;
    if (from.empty()) throw std::invalid_argument("render: no photo given");
    PiecewiseRenderStats stats;
    renderPiecewise(from, *camera.pieces, out, p, &stats);
    // The pixels no triangle of the mesh covers (each pixel is rasterised once): what the other
    // paths count as transparent, so a ring the patches leave is reported, not "0".
    report.transparent_pixels = static_cast<long long>(out.width) * out.height - stats.covered_pixels;
    report.cancelled = options.warp.progress && !options.warp.progress(1.0);
    return;
  }
  const AnalysedCamera main{camera.main(), analysis.layers[0]};
  if (pyramid) {
    if (analysis.channels.empty()) warpPreview(*pyramid, main, out, warp, &ws);
    else warpPreview(*pyramid, analysis.analysedChannels(), out, warp, &ws);
    report.path = RenderPath::Preview;
  } else {
    if (photo.empty()) throw std::invalid_argument("render: no photo given");
    if (analysis.channels.empty()) warpImage(photo, main, out, warp, &ws);
    else warpChannels(photo, analysis.analysedChannels(), out, warp, &ws);
    report.path = analysis.channels.empty() ? RenderPath::Geometry : RenderPath::Layered;
  }
  report.kernel = ws.kernel;
  report.note = ws.note;
  report.transparent_pixels = ws.transparent_pixels;
  report.cancelled = ws.cancelled;
}

// The caller's summary (or a local one) reset, after the camera's invariants are checked; the
// check's analysis of each layer goes into `analysis`, the render's one analysis.
RenderSummary& startReport(RenderSummary* summary, RenderSummary& local, const Artcam& camera,
                           Analysis& analysis) {
  RenderSummary& report = summary ? *summary : local;
  report = RenderSummary{};
  std::vector<CameraStructure> layers;
  if (const Status s = validateArtcam(camera, &layers); !s)
    throw std::invalid_argument("invalid camera: " + s.message);
  analysis = analyse(camera, std::move(layers));
  return report;
}

// The float render after startReport: the linear paths, or the geometry kernels on a float photo.
ImageF renderFloat(const RenderInputs& inputs, const Artcam& camera, const Analysis& analysis,
                   const RenderOptions& options, RenderSummary& report, ImageF* depth_out) {
  const ConstImageView photo = inputs.linear ? viewOf(*inputs.linear) : inputs.photo;
  // The output frame follows the full photo even when a smaller linear copy renders it.
  const FrameSize photo_size = inputs.photo.empty() ? FrameSize{photo.width, photo.height}
                                                    : FrameSize{inputs.photo.width, inputs.photo.height};
  const OutputFrame frame =
      outputFrameFor(camera, photo_size, options.warp.width, options.warp.height);
  report.size = frame.size;
  ImageF out;
  if (analysis.linear) {
    requireLinear(inputs);
    out = camera.pieces ? renderPieces(inputs, camera, options, frame.size, report)
                        : renderAttributedCamera(inputs, camera, analysis, options, frame.size, report,
                                                 depth_out);
  } else {
    if (photo.empty()) throw std::invalid_argument("render: no photo given");
    if (photo.type != PixelType::Float)
      throw std::invalid_argument(
          "render: a float output needs the photo as float (RenderInputs::linear)");
    const int channels = photo.alpha_channel >= 0 ? photo.channels : photo.channels + 1;
    out = ImageF(frame.size.width, frame.size.height, channels, channels - 1);
    // The one resampling rule: the linear copy is interpolated in the stored domain, as the
    // stored photo's warp would interpolate it.
    const StoredEncoding* encoding =
        inputs.linear && inputs.encoding && !inputs.encoding->isLinear() ? inputs.encoding : nullptr;
    ImageF stored;
    if (encoding) {
      stored = *inputs.linear;
      encoding->encode(stored.data.data(), stored.data.size() / static_cast<size_t>(stored.channels),
                       stored.channels, stored.alpha_channel);
    }
    const ImageF& stored_photo = stored;
    renderGeometry(encoding ? viewOf(stored_photo) : photo, nullptr, camera, analysis, options,
                   viewOf(out), report);
    if (report.cancelled) out = {};
    else if (encoding)
      encoding->decode(out.data.data(), out.data.size() / static_cast<size_t>(out.channels),
                       out.channels, out.alpha_channel);
  }
  if (!frame.warning.empty()) report.note = frame.warning + (report.note.empty() ? "" : "; " + report.note);
  report.transparent_pixels = countTransparent(out);
  return out;
}

}  // namespace

bool needsLinearPhoto(const Artcam& camera) { return analyse(camera).linear; }

bool rendersByGatherWarp(const Artcam& camera) {
  if (camera.pieces) return false;
  const Analysis analysis = analyse(camera);
  return !analysis.linear && analysis.channels.empty();
}

std::string extraChannelsUnsupported(const Artcam& camera) {
  const Analysis analysis = analyse(camera);
  if (!analysis.channels.empty())
    return "the camera moves each colour channel by its own geometry (chromatic aberration)";
  if (analysis.linear)
    return "the camera changes colour or depth (layers, attributes or depth of field), which "
           "has no meaning for data channels";
  return "";
}

void render(const RenderInputs& inputs, const Artcam& camera, const RenderOptions& options,
            const ImageView& out, RenderSummary* summary) {
  const auto start = std::chrono::steady_clock::now();
  RenderSummary local;
  Analysis analysis;
  RenderSummary& report = startReport(summary, local, camera, analysis);
  report.size = {out.width, out.height};
  if (analysis.linear) {
    ImageF image = renderFloat(inputs, camera, analysis, options, report, nullptr);
    if (report.cancelled) return;
    copyInto(image, out);
  } else {
    renderGeometry(inputs.photo, inputs.pyramid, camera, analysis, options, out, report);
  }
  if (!report.cancelled)
    report.transparent_pixels = finishEdge(options.warp.edge, out, report.transparent_pixels);
  report.render_ms = msSince(start);
}

ImageF render(const RenderInputs& inputs, const Artcam& camera, const RenderOptions& options,
              RenderSummary* summary, ImageF* depth_out) {
  const auto start = std::chrono::steady_clock::now();
  RenderSummary local;
  Analysis analysis;
  RenderSummary& report = startReport(summary, local, camera, analysis);
  ImageF out = renderFloat(inputs, camera, analysis, options, report, depth_out);
  if (!out.empty())
    report.transparent_pixels =
        finishEdge(options.warp.edge, viewOf(out), report.transparent_pixels);
  report.render_ms = msSince(start);
  return out;
}

int dropOpaqueAlpha(const ImageView& image) {
  if (image.alpha_channel < 0 || image.alpha_channel != image.channels - 1 || image.channels < 2)
    return image.channels;
  const int size = pixelTypeSize(image.type);
  const int c = image.channels;
  const auto opaque = [&](const unsigned char* p) {
    switch (image.type) {
      case PixelType::UInt8: return p[0] == 255;
      case PixelType::UInt16: {
        std::uint16_t v;
        std::memcpy(&v, p, 2);
        return v == 65535;
      }
      case PixelType::Float: {
        float v;
        std::memcpy(&v, p, 4);
        return v >= 1.0f;
      }
    }
    return false;
  };
  for (int y = 0; y < image.height; ++y) {
    const auto* row = static_cast<const unsigned char*>(image.row(y));
    for (int x = 0; x < image.width; ++x)
      if (!opaque(row + (static_cast<size_t>(x) * c + (c - 1)) * size)) return c;
  }
  // Packed rows of c − 1 channels, written front to back (never ahead of what is read).
  auto* base = static_cast<unsigned char*>(image.data);
  const size_t in_pixel = static_cast<size_t>(c) * size, out_pixel = static_cast<size_t>(c - 1) * size;
  size_t written = 0;
  for (int y = 0; y < image.height; ++y) {
    const auto* row = static_cast<const unsigned char*>(image.row(y));
    for (int x = 0; x < image.width; ++x) {
      std::memmove(base + written, row + static_cast<size_t>(x) * in_pixel, out_pixel);
      written += out_pixel;
    }
  }
  return c - 1;
}

bool dropOpaqueAlpha(ImageF& image) {
  const int before = image.channels;
  const int after = dropOpaqueAlpha(viewOf(image));
  if (after == before) return false;
  image.channels = after;
  image.alpha_channel = -1;
  image.data.resize(static_cast<size_t>(image.width) * static_cast<size_t>(image.height) *
                    static_cast<size_t>(after));
  return true;
}

}  // namespace artcam
