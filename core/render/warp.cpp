// The gather warp (DESIGN §3): pick the cheapest exact kernel once per camera from the
// structure analysis, then fill bands of output rows in parallel: inverse map a row, sample it.
#include "core/render/warp.h"

#include "core/model/frames.h"
#include "core/model/structure.h"
#include "core/render/inverse.h"
#include "core/render/inverse_seed.h"
#include "core/render/parallel.h"
#include "core/render/sampling.h"

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <vector>

namespace artcam {

std::string_view filterName(Filter filter) {
  switch (filter) {
    case Filter::Nearest: return "nearest";
    case Filter::Bilinear: return "bilinear";
    case Filter::Bicubic: return "bicubic";
  }
  return "unknown";
}

std::optional<Filter> filterFromName(std::string_view name) {
  if (name == "nearest") return Filter::Nearest;
  if (name == "bilinear" || name == "linear") return Filter::Bilinear;
  if (name == "bicubic" || name == "cubic") return Filter::Bicubic;
  return std::nullopt;
}

namespace {

FrameSize outputSize(const Camera& camera, const WarpOptions& options) {
  if (options.width < 0 || options.height < 0)
    throw std::invalid_argument("warp output size must not be negative");
  const FrameSize target = camera.targetSize();
  if (options.width > 0 && options.height > 0) return {options.width, options.height};
  if (options.width == 0 && options.height == 0) return target;
  // One side given: keep the target frame's aspect ratio.
  const double aspect = static_cast<double>(target.height) / target.width;
  if (options.width > 0)
    return {options.width, std::max(1, static_cast<int>(std::lround(options.width * aspect)))};
  return {std::max(1, static_cast<int>(std::lround(options.height / aspect))), options.height};
}

void checkCamera(const Camera& camera, const CameraStructure& structure) {
  const BlockLayout& layout = camera.layout();
  const int p = layout.find(BlockKind::Position);
  if (p < 0 || layout.blocks[p].size != 3)
    throw std::invalid_argument("warpImage needs a camera with a 2D image position block");
  if (structure.geometry_depends_on_attributes)
    throw std::invalid_argument(
        "this camera's geometry depends on colour or depth (pc/cp coupling): the gather warp "
        "cannot invert it; it needs the splat renderer (DESIGN §3)");
  if (structure.attributes_change)
    throw std::invalid_argument(
        "this camera also transforms colour or depth; warpImage renders position maps only, the "
        "per-pixel attribute transform is not implemented yet");
}

}  // namespace

ImageF warpImage(const ImageF& source, const Camera& camera, const WarpOptions& options,
                 WarpSummary* summary) {
  const auto start = std::chrono::steady_clock::now();
  WarpSummary local;
  WarpSummary& report = summary ? *summary : local;
  report = WarpSummary{};

  camera.validate();
  if (!(options.residual_tolerance_px > 0.0) || !std::isfinite(options.residual_tolerance_px))
    throw std::invalid_argument("warp residual tolerance must be a positive number of pixels");
  if (options.threads < 0) throw std::invalid_argument("warp thread count must not be negative");
  const Sampler sampler(source, options.filter);  // validates the source image
  const CameraStructure structure = analyseStructure(camera);
  checkCamera(camera, structure);

  const FrameSize source_px{source.width, source.height};
  const FrameSize out_px = outputSize(camera, options);
  ImageF out(out_px.width, out_px.height, sampler.outputChannels(), sampler.outputAlpha());
  const auto finishTiming = [&] {
    report.render_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  };
  if (structure.degenerate) {
    report.kernel = "degenerate";
    report.transparent_pixels = static_cast<long long>(out_px.width) * out_px.height;
    report.note = "the camera's position denominator is zero everywhere";
    finishTiming();
    return out;
  }

  const bool exact = !options.force_rational && structure.geometry != GeometryClass::Rational;
  const bool copy = exact && structure.geometry == GeometryClass::Identity && out_px == source_px;
  std::unique_ptr<InverseMap> inverse;
  if (copy) {
    report.kernel = "identity";
  } else if (exact) {
    // An identity between frames of different pixel sizes is an axis-aligned scaling.
    report.kernel = structure.geometry == GeometryClass::Identity
                        ? "affine"
                        : std::string(geometryClassName(structure.geometry));
    // The homography is stored normalised (frames.h); in pixels it is P_out · H · N_source.
    const Eigen::Matrix3d h = structure.homography;
    inverse = makeHomographyInverse(
        pixelFromNormalizedMatrix(out_px) * h * normalizedFromPixelMatrix(source_px), source_px);
  } else {
    report.kernel = "rational";
    RationalMap forward(camera, source_px, out_px);
    std::optional<RationalMap> seed;
    if (options.fit_inverse_seed) {
      Result<RationalMap> fitted = fitInverseSeed(forward, source_px, out_px);
      if (fitted) seed = std::move(*fitted);
      else report.note = "inverse seed not used: " + fitted.status.message;
    }
    RationalInverseOptions ro;
    ro.residual_tolerance_px = options.residual_tolerance_px;
    inverse = makeRationalInverse(std::move(forward), std::move(seed), source_px, ro);
  }

  std::atomic<long long> transparent{0};
  const int oc = out.channels, alpha = out.alpha_channel;
  ParallelOptions po;
  po.threads = options.threads;
  po.progress = options.progress;
  const bool finished = parallelForRows(out_px.height, po, [&](int y0, int y1) {
    long long band_transparent = 0;
    std::vector<Eigen::Vector2d> src(static_cast<size_t>(out_px.width));
    std::vector<unsigned char> valid(static_cast<size_t>(out_px.width));
    for (int y = y0; y < y1; ++y) {
      float* row = out.pixel(0, y);
      if (copy) {
        // Sampling at pixel centres would reproduce the source exactly; copying is cheaper.
        const float* in = source.pixel(0, y);
        if (oc == source.channels) {
          std::memcpy(row, in, sizeof(float) * static_cast<size_t>(out_px.width) * static_cast<size_t>(oc));
        } else {
          for (int x = 0; x < out_px.width; ++x) {
            float* px = row + static_cast<size_t>(x) * static_cast<size_t>(oc);
            std::memcpy(px, in + static_cast<size_t>(x) * static_cast<size_t>(source.channels),
                        sizeof(float) * static_cast<size_t>(source.channels));
            px[alpha] = 1.0f;
          }
        }
      } else {
        inverse->row(y, out_px.width, src.data(), valid.data());
        for (int x = 0; x < out_px.width; ++x) {
          float* px = row + static_cast<size_t>(x) * static_cast<size_t>(oc);
          if (valid[static_cast<size_t>(x)])
            sampler.sample(src[static_cast<size_t>(x)].x(), src[static_cast<size_t>(x)].y(), px);
          else
            sampler.clear(px);
        }
      }
      for (int x = 0; x < out_px.width; ++x)
        if (row[static_cast<size_t>(x) * static_cast<size_t>(oc) + static_cast<size_t>(alpha)] <= 0.0f)
          ++band_transparent;
    }
    transparent += band_transparent;
  });
  report.transparent_pixels = transparent.load();
  finishTiming();
  if (!finished) {
    report.cancelled = true;
    return ImageF{};
  }
  return out;
}

}  // namespace artcam
